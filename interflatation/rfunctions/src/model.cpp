// R-function model files: evaluation of the parsed statements into an expression, with the
// table of built-in functions (docs/formats.md, "R-function model files").
#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/interflatation/read_input_file.h"

#include "interlin/interflatation/rfunctions/model_expression.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/models/ifl_registry.h"
#include "interlin/interflatation/rfunctions/curve_distance.h"
#include "interlin/interflatation/rfunctions/expression.h"
#include "interlin/interflatation/rfunctions/folding.h"
#include "interlin/interflatation/rfunctions/frame_blending.h"
#include "interlin/interflatation/rfunctions/normalization.h"
#include "interlin/interflatation/rfunctions/primitives.h"
#include "interlin/interflatation/rfunctions/r_operations.h"
#include "interlin/interflatation/rfunctions/transforms.h"

#include "large_stack.h"
#include "model_parser.h"
#include "node.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <numbers>
#include <set>
#include <sstream>
#include <stdexcept>

namespace interlin {

namespace {

// The .ifl files that ifl("...") calls of the models being read are loading, outermost first. A
// normalised model (.ifl) holds .rf source that may call ifl() in turn, so a file reached again
// would load itself until memory runs out. Each nested read runs on a thread of its own, which
// inherits the chain (on_model_stack).
thread_local std::vector<std::string> ifl_chain;

// rf::detail::on_large_stack, with the caller's ifl_chain.
template <class F>
auto on_model_stack(F&& fn) {
  const std::vector<std::string> chain = ifl_chain;
  return rf::detail::on_large_stack([&] {
    ifl_chain = chain;
    return fn();
  });
}

using rf::Expr;
using rf::detail::Ast;
using rf::detail::Pos;
using rf::detail::Statement;
using rf::detail::throw_at;

struct Value {
  Value(Expr expr = 0.0) : e(std::move(expr)) {} // NOLINT: an expression is a value
  Expr e;
  bool is_list = false, is_text = false;
  std::vector<double> list;
  std::string text;
};

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// The arguments of a built-in call, with checked access.
class Args {
public:
  Args(const std::vector<Value>& v, const Ast& call, const std::string& file)
      : v_(v), call_(call), file_(file) {}
  int size() const { return static_cast<int>(v_.size()); }
  [[noreturn]] void fail(int i, const std::string& message) const {
    throw_at(file_, i >= 0 ? call_.args[i].pos : call_.pos, call_.name + ": " + message);
  }
  Expr e(int i) const {
    if (v_[i].is_text)
      fail(i, "argument " + std::to_string(i + 1) +
                  " is a text; a number or an expression is expected");
    if (v_[i].is_list)
      fail(i, "argument " + std::to_string(i + 1) +
                  " is a list; a number or an expression is expected");
    return v_[i].e;
  }
  double num(int i) const {
    const Expr x = e(i);
    if (!x.is_constant())
      fail(i, "argument " + std::to_string(i + 1) +
                  " must be a constant (it may not depend on x, y, z)");
    return x.constant_value();
  }
  int integer(int i, int lo, int hi) const {
    const double x = num(i);
    if (x != std::floor(x) || x < lo || x > hi)
      fail(i, "argument " + std::to_string(i + 1) + " must be an integer from " +
                  std::to_string(lo) + " to " + std::to_string(hi) + ", got " + number_text(x));
    return static_cast<int>(x);
  }
  // A file named by a text argument, relative to the model file's directory.
  std::string path(int i) const {
    if (!v_[i].is_text)
      fail(i, "argument " + std::to_string(i + 1) + " must be a file name in quotes, \"...\"");
    const std::filesystem::path p(v_[i].text);
    return p.is_absolute() ? p.string() : (std::filesystem::path(file_).parent_path() / p).string();
  }
  const std::vector<double>& list(int i) const {
    if (!v_[i].is_list)
      fail(i, "argument " + std::to_string(i + 1) + " must be a list [x0, y0, x1, y1, ...]");
    return v_[i].list;
  }
  std::vector<Eigen::Vector2d> points(int i) const {
    const auto& l = list(i);
    if (l.size() % 2 != 0)
      fail(i, "the list has " + std::to_string(l.size()) + " numbers; it must hold x, y pairs");
    std::vector<Eigen::Vector2d> p;
    for (std::size_t k = 0; k + 1 < l.size(); k += 2)
      p.emplace_back(l[k], l[k + 1]);
    return p;
  }
  // Left fold of a binary operation over all arguments.
  Expr fold(Expr (*f)(const Expr&, const Expr&)) const {
    Expr r = e(0);
    for (int i = 1; i < size(); ++i)
      r = f(r, e(i));
    return r;
  }

private:
  const std::vector<Value>& v_;
  const Ast& call_;
  const std::string& file_;
};

struct Builtin {
  int min_args, max_args; // max_args < 0: any number
  std::function<Expr(const Args&)> fn;
};

const std::map<std::string, Builtin>& builtins() {
  using namespace rf;
  using A = const Args&;
  static const std::map<std::string, Builtin> table = [] {
    std::map<std::string, Builtin> t;
    auto unary = [&](const char* name, Expr (*f)(const Expr&)) {
      t[name] = {1, 1, [f](A a) { return f(a.e(0)); }};
    };
    // elementary functions
    unary("sqrt", &rf::sqrt);
    unary("abs", &rf::abs);
    unary("sign", &rf::sign);
    unary("sin", &rf::sin);
    unary("cos", &rf::cos);
    unary("tan", &rf::tan);
    unary("asin", &rf::asin);
    unary("acos", &rf::acos);
    unary("atan", &rf::atan);
    unary("exp", &rf::exp);
    unary("log", &rf::log);
    t["atan2"] = {2, 2, [](A a) { return rf::atan2(a.e(0), a.e(1)); }};
    t["hypot"] = {2, 2, [](A a) { return rf::hypot(a.e(0), a.e(1)); }};
    t["pow"] = {2, 2, [](A a) { return rf::pow(a.e(0), a.e(1)); }};
    t["min"] = {2, -1, [](A a) { return a.fold(&rf::min); }};
    t["max"] = {2, -1, [](A a) { return a.fold(&rf::max); }};
    // R-operations (seed 000 §2.2); rfAND, rfOR, rfNOT as in RFPreview and seed 002's MATLAB
    for (const char* n : {"and0", "rfAND"})
      t[n] = {2, -1, [](A a) { return a.fold(&and0); }};
    for (const char* n : {"or0", "rfOR"})
      t[n] = {2, -1, [](A a) { return a.fold(&or0); }};
    for (const char* n : {"not", "rfNOT"})
      t[n] = {1, 1, [](A a) { return negation(a.e(0)); }};
    t["sub0"] = {2, -1, [](A a) { return a.fold(&sub0); }};
    t["and1"] = {2, -1, [](A a) { return a.fold(&and1); }};
    t["or1"] = {2, -1, [](A a) { return a.fold(&or1); }};
    t["and_alpha"] = {3, 3, [](A a) { return and_alpha(a.e(0), a.e(1), a.e(2)); }};
    t["or_alpha"] = {3, 3, [](A a) { return or_alpha(a.e(0), a.e(1), a.e(2)); }};
    t["alpha_variable"] = {2, 2, [](A a) { return alpha_variable(a.e(0), a.e(1)); }};
    t["and_valpha"] = {2, -1, [](A a) { return a.fold(&and_alpha_variable); }};
    t["or_valpha"] = {2, -1, [](A a) { return a.fold(&or_alpha_variable); }};
    t["and0m"] = {3, 3, [](A a) { return and0m(a.e(0), a.e(1), a.num(2)); }};
    t["or0m"] = {3, 3, [](A a) { return or0m(a.e(0), a.e(1), a.num(2)); }};
    t["andp"] = {3, 3, [](A a) { return andp(a.e(0), a.e(1), a.num(2)); }};
    t["orp"] = {3, 3, [](A a) { return orp(a.e(0), a.e(1), a.num(2)); }};
    t["and_fillet"] = {3, 3, [](A a) { return and_fillet(a.e(0), a.e(1), a.e(2)); }};
    t["or_fillet"] = {3, 3, [](A a) { return or_fillet(a.e(0), a.e(1), a.e(2)); }};
    t["equiv"] = {2, 2, [](A a) { return equiv(a.e(0), a.e(1)); }};
    t["equiv_eps"] = {4, 4,
                      [](A a) { return equiv_eps(a.e(0), a.e(1), a.num(2), a.integer(3, 1, 20)); }};
    // normalisation, pieces, walls (seed 000 §2.6)
    unary("normalize", &normalize);
    unary("normalize_grad", &normalize_by_gradient);
    unary("grad_norm", &gradient_norm);
    t["dx"] = {1, 1, [](A a) { return derivative(a.e(0), 0); }};
    t["dy"] = {1, 1, [](A a) { return derivative(a.e(0), 1); }};
    t["dz"] = {1, 1, [](A a) { return derivative(a.e(0), 2); }};
    t["piece"] = {2, 2, [](A a) { return piece(a.e(0), a.e(1)); }};
    t["wall"] = {2, 2, [](A a) { return wall(a.e(0), a.e(1)); }};
    t["inner_wall"] = {2, 2, [](A a) { return inner_wall(a.e(0), a.e(1)); }};
    // primitives
    t["strip"] = {2, 2, [](A a) { return strip(a.e(0), a.e(1)); }};
    t["strip_smooth"] = {2, 2, [](A a) { return strip_smooth(a.e(0), a.e(1)); }};
    t["layer"] = {3, 3, [](A a) { return layer(a.e(0), a.e(1), a.e(2)); }};
    t["halfplane"] = {5, 5, [](A a) { return halfplane(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4)); }};
    t["circle"] = {3, 3, [](A a) { return circle(a.e(0), a.e(1), a.e(2)); }};
    t["circle_smooth"] = {3, 3, [](A a) { return circle_smooth(a.e(0), a.e(1), a.e(2)); }};
    t["rectangle"] = {4, 4, [](A a) { return rectangle(a.e(0), a.e(1), a.e(2), a.e(3)); }};
    t["ellipse"] = {4, 4, [](A a) { return ellipse(a.e(0), a.e(1), a.e(2), a.e(3)); }};
    t["segment"] = {
        6, 6, [](A a) { return segment(a.e(0), a.e(1), a.num(2), a.num(3), a.num(4), a.num(5)); }};
    t["halfspace"] = {7, 7, [](A a) {
                        return halfspace(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4), a.e(5), a.e(6));
                      }};
    t["sphere"] = {4, 4, [](A a) { return sphere(a.e(0), a.e(1), a.e(2), a.e(3)); }};
    t["cuboid"] = {6, 6,
                   [](A a) { return cuboid(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4), a.e(5)); }};
    t["cylinder"] = {5, 5, [](A a) { return cylinder(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4)); }};
    t["cone"] = {5, 5, [](A a) { return cone(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4)); }};
    t["torus"] = {5, 5, [](A a) { return torus(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4)); }};
    t["ellipsoid"] = {
        6, 6, [](A a) { return ellipsoid(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4), a.e(5)); }};
    // transforms (seed 000 §2.8)
    t["at"] = {4, 4, [](A a) { return substitute(a.e(0), a.e(1), a.e(2), a.e(3)); }};
    t["translate"] = {4, 4, [](A a) { return translate(a.e(0), a.e(1), a.e(2), a.e(3)); }};
    t["rotate_x"] = {2, 2, [](A a) { return rotate_x(a.e(0), a.e(1)); }};
    t["rotate_y"] = {2, 2, [](A a) { return rotate_y(a.e(0), a.e(1)); }};
    t["rotate_z"] = {2, 2, [](A a) { return rotate_z(a.e(0), a.e(1)); }};
    t["rotate"] = {5, 5, [](A a) { return rotate(a.e(0), a.num(1), a.num(2), a.num(3), a.e(4)); }};
    t["scale"] = {2, 2, [](A a) { return scale(a.e(0), a.e(1)); }};
    t["scale_xyz"] = {4, 4, [](A a) { return scale_xyz(a.e(0), a.e(1), a.e(2), a.e(3)); }};
    t["twist_x"] = {2, 2, [](A a) { return twist_x(a.e(0), a.e(1)); }};
    t["twist_y"] = {2, 2, [](A a) { return twist_y(a.e(0), a.e(1)); }};
    t["twist_z"] = {2, 2, [](A a) { return twist_z(a.e(0), a.e(1)); }};
    unary("revolve_x", &revolve_x);
    unary("revolve_x_smooth", &revolve_x_smooth);
    unary("revolve_z", &revolve_z);
    unary("revolve_z_smooth", &revolve_z_smooth);
    t["similar_z"] = {2, 2, [](A a) { return similar_z(a.e(0), a.e(1)); }};
    t["cone_map"] = {4, 4, [](A a) { return cone_map(a.e(0), a.e(1), a.e(2), a.e(3)); }};
    t["lerp"] = {3, 3, [](A a) { return lerp(a.e(0), a.e(1), a.e(2)); }};
    // folding (seed 000 §2.7)
    t["mu"] = {2, 2, [](A a) { return mu(a.e(0), a.num(1)); }};
    t["mu_fourier"] = {3, 3,
                       [](A a) { return mu_fourier(a.e(0), a.num(1), a.integer(2, 1, 1000)); }};
    t["mu_finite"] = {3, 3, [](A a) { return mu_finite(a.e(0), a.num(1), a.e(2)); }};
    t["mu_cyclic"] = {2, 2, [](A a) { return mu_cyclic(a.e(0), a.num(1)); }};
    t["mu_cyclic_fourier"] = {
        3, 3, [](A a) { return mu_cyclic_fourier(a.e(0), a.num(1), a.integer(2, 1, 1000)); }};
    t["fold_x"] = {2, 2, [](A a) { return fold_x(a.e(0), a.num(1)); }};
    t["fold_x_fourier"] = {
        3, 3, [](A a) { return fold_x_fourier(a.e(0), a.num(1), a.integer(2, 1, 1000)); }};
    t["fold_x_finite"] = {3, 3, [](A a) { return fold_x_finite(a.e(0), a.num(1), a.e(2)); }};
    t["fold_x_asym"] = {2, 2, [](A a) { return fold_x_asym(a.e(0), a.num(1)); }};
    t["fold_cyclic"] = {2, 2, [](A a) { return fold_cyclic(a.e(0), a.num(1)); }};
    t["fold_cyclic_fourier"] = {
        3, 3, [](A a) { return fold_cyclic_fourier(a.e(0), a.num(1), a.integer(2, 1, 1000)); }};
    t["fold_cyclic_asym"] = {2, 2, [](A a) { return fold_cyclic_asym(a.e(0), a.num(1)); }};
    // blending on a frame (seed 000 §2.9)
    t["segment_frame"] = {3, 3, [](A a) { return segment_frame(a.e(0), a.e(1), a.e(2)); }};
    t["blend_segment"] = {
        7, 7,
        [](A a) { return blend_segment(a.e(0), a.e(1), a.e(2), a.e(3), a.e(4), a.e(5), a.e(6)); }};
    t["arc_frame"] = {4, 4, [](A a) { return arc_frame(a.e(0), a.e(1), a.e(2), a.num(3)); }};
    // implicit bodies of .ifl files (seed 001 ch. 4 models, point-cloud fits) as operands
    t["ifl"] = {1, 1, [](A a) {
                  const std::string path = a.path(0);
                  std::error_code ec;
                  const std::filesystem::path real = std::filesystem::weakly_canonical(path, ec);
                  const std::string key = ec ? path : real.string();
                  if (std::count(ifl_chain.begin(), ifl_chain.end(), key))
                    a.fail(0, path + " is being loaded already: ifl(\"...\") calls in a cycle");
                  ifl_chain.push_back(key);
                  struct Pop {
                    ~Pop() { ifl_chain.pop_back(); }
                  } pop;
                  std::shared_ptr<const ImplicitFunction> body;
                  try {
                    body = std::make_shared<const ImplicitFunction>(load_ifl(path));
                  } catch (const InputError& e) {
                    a.fail(0, e.what());
                  }
                  return rf::field(std::move(body), Expr::x(), Expr::y(), Expr::z());
                }};
    // regions bounded by curves (seed 003 §3.3)
    t["polygon_region"] = {3, 3, [](A a) { return polygon_region(a.e(0), a.e(1), a.points(2)); }};
    t["bezier_region"] = {
        4, -1, [](A a) {
          std::vector<std::vector<Eigen::Vector2d>> branches;
          double work = 0; // de Casteljau: segments x (control points)^2
          const int segments = a.integer(2, 1, 100000);
          for (int i = 3; i < a.size(); ++i) {
            branches.push_back(a.points(i));
            work +=
                double(segments) * double(branches.back().size()) * double(branches.back().size());
          }
          // Sampling counts against the model size: a short file could
          // otherwise ask for hours of it and millions of polygon vertices.
          rf::detail::NodeBudget::charge(static_cast<long long>(std::min(work, 1e18)));
          return polygon_region(a.e(0), a.e(1), sample_bezier_chain(branches, segments));
        }};
    return t;
  }();
  return table;
}

// Levenshtein distance, for "did you mean" hints.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> d(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    d[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t prev = d[0];
    d[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t cur = d[j];
      d[j] = std::min({d[j] + 1, d[j - 1] + 1, prev + (a[i - 1] != b[j - 1])});
      prev = cur;
    }
  }
  return d[b.size()];
}

template <class Map>
std::string hint(const std::string& name, const Map& candidates) {
  std::string best;
  std::size_t best_d = 3;
  for (const auto& [key, value] : candidates) {
    const std::size_t d = edit_distance(name, key);
    if (d < best_d) {
      best_d = d;
      best = key;
    }
  }
  return best.empty() ? "" : " (did you mean '" + best + "'?)";
}

struct Def;
using Scope = std::map<std::string, Expr>;
using Defs = std::map<std::string, std::shared_ptr<const Def>>;

struct Def {
  std::vector<std::string> params;
  Ast body;
  std::shared_ptr<const Scope> scope; // the variables at the definition
  std::shared_ptr<const Defs> defs;   // the functions defined before it
};

class Evaluator {
public:
  Evaluator(const std::string& file, const ModelOptions& options) : file_(file), options_(options) {
    globals_["x"] = Expr::x();
    globals_["y"] = Expr::y();
    globals_["z"] = Expr::z();
    globals_["pi"] = std::numbers::pi;
  }

  ModelExpression run(const std::vector<Statement>& program) {
    const rf::detail::NodeBudget budget(options_.max_size);
    for (const Statement& st : program)
      execute(st);
    for (const auto& [name, value] : options_.parameters)
      if (!declared_params_.count(name))
        throw InputError(file_ + ": parameter '" + name +
                         "' is not declared by a 'param' statement in the model" +
                         hint(name, declared_params_));
    if (!box_set_)
      throw InputError(file_ + ": the model has no box statement; declare the region that holds "
                               "the body with box(x0, y0, z0, x1, y1, z1);");
    auto out = globals_.find(options_.output);
    if (out == globals_.end() || !assigned_.count(options_.output))
      throw InputError(file_ + ": the model does not assign the output variable '" +
                       options_.output + "'");
    return {out->second, box_};
  }

private:
  [[noreturn]] void fail(Pos pos, const std::string& message) const {
    throw_at(file_, pos, message);
  }

  void execute(const Statement& st) {
    try {
      execute_checked(st);
    } catch (const std::invalid_argument& e) { // e.g. an expression nested too deeply
      fail(st.pos, e.what());
    } catch (const LimitError& e) { // the model-size budget: named with the statement
      throw LimitError(file_ + ":" + std::to_string(st.pos.line) + ":" +
                           std::to_string(st.pos.column) + ": " + e.what(),
                       e.option);
    }
  }

  void execute_checked(const Statement& st) {
    switch (st.kind) {
    case Statement::Kind::box: {
      if (box_set_)
        fail(st.pos, "box declared twice (first at line " + std::to_string(box_pos_.line) + ")");
      double b[6];
      for (int k = 0; k < 6; ++k) {
        const Value v = eval(st.exprs[k], globals_, defs_, 0);
        if (v.is_list || v.is_text || !v.e.is_constant() || !std::isfinite(v.e.constant_value()))
          fail(st.exprs[k].pos, "box bounds must be finite constants");
        b[k] = v.e.constant_value();
      }
      for (int k = 0; k < 3; ++k)
        if (!(b[k] < b[k + 3]))
          fail(st.exprs[k + 3].pos, std::string("box: the upper ") + "xyz"[k] + " bound (" +
                                        number_text(b[k + 3]) + ") must exceed the lower (" +
                                        number_text(b[k]) + ")");
      box_ =
          Eigen::AlignedBox3d(Eigen::Vector3d(b[0], b[1], b[2]), Eigen::Vector3d(b[3], b[4], b[5]));
      box_set_ = true;
      box_pos_ = st.pos;
      return;
    }
    case Statement::Kind::def: {
      if (builtins().count(st.name))
        fail(st.pos, "'" + st.name + "' is a built-in function and cannot be redefined");
      if (defs_.count(st.name))
        fail(st.pos, "function '" + st.name + "' is already defined");
      std::set<std::string> seen;
      for (std::size_t i = 0; i < st.params.size(); ++i)
        if (!seen.insert(st.params[i]).second)
          fail(st.param_pos[i], "parameter '" + st.params[i] + "' appears twice");
      auto def = std::make_shared<Def>();
      def->params = st.params;
      def->body = st.exprs[0];
      def->scope = std::make_shared<const Scope>(globals_);
      def->defs = std::make_shared<const Defs>(defs_);
      defs_[st.name] = def;
      return;
    }
    case Statement::Kind::param:
    case Statement::Kind::assign: {
      if (st.name == "x" || st.name == "y" || st.name == "z")
        fail(st.pos, "cannot assign to the coordinate '" + st.name + "'");
      if (st.name == "def" || st.name == "param" || st.name == "box")
        fail(st.pos, "'" + st.name + "' is a keyword");
      const Value v = eval(st.exprs[0], globals_, defs_, 0);
      if (v.is_list || v.is_text)
        fail(st.exprs[0].pos, std::string("a ") + (v.is_list ? "list" : "text") +
                                  " cannot be assigned to a variable; write it in the call");
      Expr e = v.e;
      if (st.kind == Statement::Kind::param) {
        if (declared_params_.count(st.name))
          fail(st.pos, "parameter '" + st.name + "' is declared twice");
        if (!e.is_constant())
          fail(st.exprs[0].pos, "the default of parameter '" + st.name + "' must be a constant");
        declared_params_[st.name] = st.pos;
        auto o = options_.parameters.find(st.name);
        if (o != options_.parameters.end())
          e = o->second;
      }
      globals_[st.name] = e;
      assigned_.insert(st.name);
      return;
    }
    }
  }

  Value eval(const Ast& a, const Scope& scope, const Defs& defs, int depth) const {
    if (depth > limits::call_depth)
      fail(a.pos, "function calls nested too deeply (more than " +
                      std::to_string(limits::call_depth) + " levels; a fixed limit)");
    rf::detail::NodeBudget::charge(); // expanding calls can take exponential work: count it
    switch (a.kind) {
    case Ast::Kind::number:
      return {a.number};
    case Ast::Kind::name: {
      auto it = scope.find(a.name);
      if (it != scope.end())
        return {it->second};
      if (builtins().count(a.name) || defs.count(a.name))
        fail(a.pos, "'" + a.name + "' is a function; call it as " + a.name + "(...)");
      fail(a.pos, "unknown variable '" + a.name + "'" + hint(a.name, scope));
    }
    case Ast::Kind::text: {
      Value v;
      v.is_text = true;
      v.text = a.name;
      return v;
    }
    case Ast::Kind::list: {
      Value v;
      v.is_list = true;
      for (const Ast& item : a.args) {
        const Value x = eval(item, scope, defs, depth);
        if (x.is_list || x.is_text || !x.e.is_constant() || !std::isfinite(x.e.constant_value()))
          fail(item.pos, "list entries must be finite constants");
        v.list.push_back(x.e.constant_value());
      }
      return v;
    }
    case Ast::Kind::unary: {
      const Expr o = scalar(a.args[0], scope, defs, depth);
      return {a.op == '-' ? -o : o};
    }
    case Ast::Kind::binary: {
      const Expr l = scalar(a.args[0], scope, defs, depth);
      const Expr r = scalar(a.args[1], scope, defs, depth);
      switch (a.op) {
      case '+':
        return {l + r};
      case '-':
        return {l - r};
      case '*':
        return {l * r};
      case '/':
        return {l / r};
      default:
        return {rf::pow(l, r)};
      }
    }
    case Ast::Kind::call:
      return {call(a, scope, defs, depth)};
    }
    fail(a.pos, "internal error: unknown syntax node");
  }

  Expr scalar(const Ast& a, const Scope& scope, const Defs& defs, int depth) const {
    Value v = eval(a, scope, defs, depth);
    if (v.is_list)
      fail(a.pos, "a list [...] can only be an argument of polygon_region or bezier_region");
    if (v.is_text)
      fail(a.pos, "a text \"...\" can only be the file name argument of ifl(\"...\")");
    return v.e;
  }

  Expr call(const Ast& a, const Scope& scope, const Defs& defs, int depth) const {
    std::vector<Value> args;
    for (const Ast& arg : a.args)
      args.push_back(eval(arg, scope, defs, depth + 1));
    const int n = static_cast<int>(args.size());
    auto d = defs.find(a.name);
    if (d != defs.end()) {
      const Def& def = *d->second;
      if (n != static_cast<int>(def.params.size()))
        fail(a.pos, a.name + " expects " + std::to_string(def.params.size()) +
                        " argument(s), got " + std::to_string(n));
      Scope local = *def.scope;
      for (int i = 0; i < n; ++i) {
        if (args[i].is_list || args[i].is_text)
          fail(a.args[i].pos, "a list or a text cannot be passed to a user function");
        local[def.params[i]] = args[i].e;
      }
      return scalar(def.body, local, *def.defs, depth + 1);
    }
    auto b = builtins().find(a.name);
    if (b == builtins().end()) {
      if (scope.count(a.name))
        fail(a.pos, "'" + a.name + "' is a variable, not a function");
      std::map<std::string, int> names;
      for (const auto& kv : builtins())
        names[kv.first] = 0;
      for (const auto& kv : defs)
        names[kv.first] = 0;
      fail(a.pos, "unknown function '" + a.name + "'" + hint(a.name, names));
    }
    const Builtin& f = b->second;
    if (n < f.min_args || (f.max_args >= 0 && n > f.max_args)) {
      std::string expected = f.min_args == f.max_args ? std::to_string(f.min_args)
                             : f.max_args < 0
                                 ? "at least " + std::to_string(f.min_args)
                                 : std::to_string(f.min_args) + " to " + std::to_string(f.max_args);
      fail(a.pos, a.name + " expects " + expected + " argument(s), got " + std::to_string(n));
    }
    try {
      return f.fn(Args(args, a, file_));
    } catch (const std::invalid_argument& e) { // a library check, e.g. a negative radius
      fail(a.pos, e.what());
    }
  }

  const std::string& file_;
  const ModelOptions& options_;
  Scope globals_;
  Defs defs_;
  std::set<std::string> assigned_;
  std::map<std::string, Pos> declared_params_;
  Eigen::AlignedBox3d box_;
  bool box_set_ = false;
  Pos box_pos_;
};

} // namespace

ModelExpression parse_model_expression(const std::string& text, const std::string& name,
                                       const ModelOptions& options) {
  return on_model_stack(
      [&] { return Evaluator(name, options).run(rf::detail::parse_model_text(text, name)); });
}

ModelExpression load_model_expression(const std::string& path, const ModelOptions& options) {
  return parse_model_expression(read_input_file(path), path, options);
}

ImplicitFunction parse_model(const std::string& text, const std::string& name,
                             const ModelOptions& options) {
  return on_model_stack([&] { // the expression is also destroyed on that stack
    const ModelExpression m =
        Evaluator(name, options).run(rf::detail::parse_model_text(text, name));
    return rf::compile(m.F, m.box);
  });
}

ImplicitFunction load_model(const std::string& path, const ModelOptions& options) {
  return parse_model(read_input_file(path), path, options);
}

} // namespace interlin
