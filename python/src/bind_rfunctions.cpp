// Python bindings of interflatation/: implicit bodies F(x, y, z) (class Implicit: values and
// gradients on arrays of points), R-function models (.rf files), the R-function expression
// language as the submodule interlin.rf, Monte Carlo volumes.
#include "bindings.h"

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/load_implicit.h"
#include "interlin/interflatation/rfunctions/curve_distance.h"
#include "interlin/interflatation/rfunctions/expression.h"
#include "interlin/interflatation/rfunctions/folding.h"
#include "interlin/interflatation/rfunctions/frame_blending.h"
#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/interflatation/rfunctions/model_expression.h"
#include "interlin/interflatation/rfunctions/normalization.h"
#include "interlin/interflatation/rfunctions/primitives.h"
#include "interlin/interflatation/rfunctions/r_operations.h"
#include "interlin/interflatation/rfunctions/transforms.h"
#include "interlin/interflatation/rfunctions/volume_estimate.h"

#include <memory>

namespace interlin::python {

namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using rf::Expr;
using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Points are evaluated in blocks: a column-major copy of one block at a time (not of the whole
// array), which is what the batch evaluators want.
constexpr Index kBlock = 4096;

const double* points_data(const DoubleArray& P) {
  if (P.ndim() != 2 || P.shape(1) != 3)
    throw py::value_error("P: expected an (N, 3) array of points");
  return P.data();
}

} // namespace

VectorXd values_at(const ImplicitFunction& f, const DoubleArray& P) {
  const double* p = points_data(P);
  const Index n = P.shape(0);
  VectorXd F(n);
  py::gil_scoped_release release;
  Points3 block;
  for (Index b = 0; b < n; b += kBlock) {
    const Index m = std::min(kBlock, n - b);
    block = Eigen::Map<const RowPoints>(p + 3 * b, m, 3);
    f.value(block, F.segment(b, m));
  }
  return F;
}

py::tuple gradients_at(const ImplicitFunction& f, const DoubleArray& P) {
  if (!f.gradient)
    throw py::value_error("this implicit function has no gradient");
  const double* p = points_data(P);
  const Index n = P.shape(0);
  VectorXd F(n);
  Points3 G(n, 3);
  {
    py::gil_scoped_release release;
    Points3 block;
    for (Index b = 0; b < n; b += kBlock) {
      const Index m = std::min(kBlock, n - b);
      block = Eigen::Map<const RowPoints>(p + 3 * b, m, 3);
      f.gradient(block, F.segment(b, m), G.middleRows(b, m));
    }
  }
  return py::make_tuple(std::move(F), std::move(G));
}

namespace {

// F(P) -> (N,) and optionally grad(P) -> (F (N,), G (N, 3)) as an ImplicitFunction.
ImplicitFunction from_python(py::function value, std::optional<py::function> gradient,
                             const std::optional<MatrixXd>& box) {
  ImplicitFunction f;
  const auto v = std::make_shared<PythonCallable>(PythonCallable{std::move(value)});
  f.value = [v](const Eigen::Ref<const Points3>& P, Eigen::Ref<VectorXd> F) {
    py::gil_scoped_acquire gil;
    const RowPoints rows = P;
    const auto r =
        DoubleArray::ensure(v->f(py::array_t<double>({rows.rows(), Index(3)}, rows.data())));
    if (!r || r.size() != P.rows())
      throw py::value_error("an implicit function f(P) must return an array of len(P) numbers");
    F = Eigen::Map<const VectorXd>(r.data(), P.rows());
  };
  if (gradient) {
    const auto g = std::make_shared<PythonCallable>(PythonCallable{std::move(*gradient)});
    f.gradient = [g](const Eigen::Ref<const Points3>& P, Eigen::Ref<VectorXd> F,
                     Eigen::Ref<Points3> G) {
      py::gil_scoped_acquire gil;
      const RowPoints rows = P;
      const py::tuple r = g->f(py::array_t<double>({rows.rows(), Index(3)}, rows.data()));
      const auto Fv = DoubleArray::ensure(r[0]);
      const auto Gv = DoubleArray::ensure(r[1]);
      if (!Fv || !Gv || Fv.size() != P.rows() || Gv.size() != 3 * P.rows())
        throw py::value_error("a gradient g(P) must return (F (N,), G (N, 3))");
      F = Eigen::Map<const VectorXd>(Fv.data(), P.rows());
      G = Eigen::Map<const RowPoints>(Gv.data(), P.rows(), 3);
    };
  }
  if (box)
    f.box = box_from_array(*box);
  return f;
}

void bind_implicit(py::module_& m) {
  py::class_<ImplicitFunction>(m, "Implicit", R"(An implicit body F(x, y, z): F > 0 inside, 0 on
the surface, < 0 outside. From a model (load_model, parse_model, rf.compile), or from Python:
Implicit(f, box=None, gradient=None) with f(P (N, 3)) -> (N,) and gradient(P) -> (F, G (N, 3)).

Methods: f(P) or f.value(P) -> (N,); f.gradient(P) -> (F (N,), G (N, 3)); P is (N, 3).
Attribute box: (2, 3) array [min, max], or None.)")
      .def(py::init(&from_python), py::arg("f"), py::arg("gradient") = py::none(),
           py::arg("box") = py::none())
      .def("value", &values_at, py::arg("P"), "F at the points P (N, 3) -> (N,).")
      .def("__call__", &values_at, py::arg("P"))
      .def("gradient", &gradients_at, py::arg("P"),
           "(F (N,), G (N, 3)): values and exact gradients (dual numbers for models).")
      .def_property_readonly("has_gradient",
                             [](const ImplicitFunction& f) { return bool(f.gradient); })
      .def_property_readonly("box", [](const ImplicitFunction& f) -> py::object {
        if (f.box.isEmpty())
          return py::none();
        return py::cast(box_to_array(f.box));
      });

  const auto options = [](const std::map<std::string, double>& parameters,
                          const std::string& output) {
    return ModelOptions{output, parameters};
  };
  m.def(
      "load_model",
      [options](const std::string& path, const std::map<std::string, double>& parameters,
                const std::string& output) {
        py::gil_scoped_release release;
        return load_implicit(path, options(parameters, output));
      },
      py::arg("path"), py::arg("parameters") = std::map<std::string, double>{},
      py::arg("output") = "res",
      R"(Reads a model file -> Implicit, by extension as `interlin eval` and `mesh` do: an
R-function model (.rf, compiled; parameters override its `param` values, output names the
variable, default res) or an implicit model file (.ifl: interlin.implicit() or `interlin
implicit` wrote it; parameters and output must be left at their defaults).
InputError "FILE:LINE: ..." as the CLI prints it.)");
  m.def(
      "parse_model",
      [options](const std::string& text, const std::string& name,
                const std::map<std::string, double>& parameters, const std::string& output) {
        return parse_model(text, name, options(parameters, output));
      },
      py::arg("text"), py::arg("name") = "<model>",
      py::arg("parameters") = std::map<std::string, double>{}, py::arg("output") = "res",
      "The same from model text in memory; name stands for the file in messages.");
  m.def(
      "estimate_volume",
      [](const ImplicitFunction& f, double cell, unsigned seed, int threads) {
        VolumeEstimate v;
        {
          py::gil_scoped_release release;
          v = estimate_volume(f, cell, seed, threads);
        }
        return py::make_tuple(v.volume, v.standard_error, v.samples);
      },
      py::arg("f"), py::arg("cell"), py::arg("seed") = 1, py::arg("threads") = 1,
      "Volume of {F > 0} inside f.box by stratified Monte Carlo: (volume, standard_error, "
      "samples).");
}

void bind_expr(py::module_& rf) {
  py::class_<Expr>(rf, "Expr", R"(An R-function expression in x, y, z (seeds 000, 002, 003).
Build with the coordinates rf.x, rf.y, rf.z, numbers, + - * / ** and the functions of
interlin.rf; compile with rf.compile(expr, box) into an Implicit.)")
      .def(py::init<double>(), py::arg("constant") = 0.0)
      .def_property_readonly("is_constant", &Expr::is_constant)
      .def_property_readonly("value", &Expr::constant_value, "The value of a constant expression.")
      .def(py::self + py::self)
      .def(py::self - py::self)
      .def(py::self * py::self)
      .def(py::self / py::self)
      .def(-py::self)
      .def(double() + py::self)
      .def(double() - py::self)
      .def(double() * py::self)
      .def(double() / py::self)
      .def("__pow__", [](const Expr& a, const Expr& b) { return rf::pow(a, b); })
      .def("__rpow__", [](const Expr& a, double b) { return rf::pow(Expr(b), a); });
  py::implicitly_convertible<double, Expr>();
  py::implicitly_convertible<int, Expr>();
  rf.attr("x") = Expr::x();
  rf.attr("y") = Expr::y();
  rf.attr("z") = Expr::z();

  using U = Expr (*)(const Expr&);
  using B = Expr (*)(const Expr&, const Expr&);
  for (const auto& [name, f] :
       std::vector<std::pair<const char*, U>>{{"sqrt", rf::sqrt},
                                              {"abs", rf::abs},
                                              {"sign", rf::sign},
                                              {"sin", rf::sin},
                                              {"cos", rf::cos},
                                              {"tan", rf::tan},
                                              {"asin", rf::asin},
                                              {"acos", rf::acos},
                                              {"atan", rf::atan},
                                              {"exp", rf::exp},
                                              {"log", rf::log},
                                              {"negation", rf::negation},
                                              {"normalize", rf::normalize},
                                              {"normalize_by_gradient", rf::normalize_by_gradient},
                                              {"gradient_norm", rf::gradient_norm},
                                              {"revolve_x", rf::revolve_x},
                                              {"revolve_x_smooth", rf::revolve_x_smooth},
                                              {"revolve_z", rf::revolve_z},
                                              {"revolve_z_smooth", rf::revolve_z_smooth}})
    rf.def(name, f, py::arg("a"));
  for (const auto& [name, f] :
       std::vector<std::pair<const char*, B>>{{"pow", rf::pow},
                                              {"atan2", rf::atan2},
                                              {"min", rf::min},
                                              {"max", rf::max},
                                              {"hypot", rf::hypot},
                                              {"and0", rf::and0},
                                              {"or0", rf::or0},
                                              {"sub0", rf::sub0},
                                              {"and1", rf::and1},
                                              {"or1", rf::or1},
                                              {"equiv", rf::equiv},
                                              {"piece", rf::piece},
                                              {"wall", rf::wall},
                                              {"inner_wall", rf::inner_wall},
                                              {"alpha_variable", rf::alpha_variable},
                                              {"and_alpha_variable", rf::and_alpha_variable},
                                              {"or_alpha_variable", rf::or_alpha_variable},
                                              {"strip", rf::strip},
                                              {"strip_smooth", rf::strip_smooth},
                                              {"scale", rf::scale},
                                              {"rotate_x", rf::rotate_x},
                                              {"rotate_y", rf::rotate_y},
                                              {"rotate_z", rf::rotate_z},
                                              {"twist_x", rf::twist_x},
                                              {"twist_y", rf::twist_y},
                                              {"twist_z", rf::twist_z},
                                              {"similar_z", rf::similar_z}})
    rf.def(name, f, py::arg("a"), py::arg("b"));
  rf.def("derivative", &rf::derivative, py::arg("F"), py::arg("axis"),
         "dF/d(axis), axis 0, 1, 2 for x, y, z, as an expression (exact).");
  rf.def("substitute", &rf::substitute, py::arg("F"), py::arg("X"), py::arg("Y"), py::arg("Z"),
         "F(X, Y, Z).");
  rf.def("operation_count", &rf::operation_count, py::arg("F"));
  rf.def("and_alpha", &rf::and_alpha, py::arg("a"), py::arg("b"), py::arg("alpha"));
  rf.def("or_alpha", &rf::or_alpha, py::arg("a"), py::arg("b"), py::arg("alpha"));
  rf.def("and0m", &rf::and0m, py::arg("a"), py::arg("b"), py::arg("m"));
  rf.def("or0m", &rf::or0m, py::arg("a"), py::arg("b"), py::arg("m"));
  rf.def("andp", &rf::andp, py::arg("a"), py::arg("b"), py::arg("p"));
  rf.def("orp", &rf::orp, py::arg("a"), py::arg("b"), py::arg("p"));
  rf.def("and_fillet", &rf::and_fillet, py::arg("a"), py::arg("b"), py::arg("rho"));
  rf.def("or_fillet", &rf::or_fillet, py::arg("a"), py::arg("b"), py::arg("rho"));
  rf.def("equiv_eps", &rf::equiv_eps, py::arg("a"), py::arg("b"), py::arg("eps"), py::arg("n"));
  rf.def("lerp", &rf::lerp, py::arg("a"), py::arg("b"), py::arg("t"));
}

void bind_primitives(py::module_& rf) {
  using namespace rf;
  const auto u = py::arg("u"), v = py::arg("v"), x = py::arg("x"), y = py::arg("y"),
             z = py::arg("z");
  rf.def("layer", &layer, u, py::arg("lo"), py::arg("hi"));
  rf.def("halfplane", &halfplane, u, v, py::arg("a"), py::arg("b"), py::arg("c"));
  rf.def("circle", &circle, u, v, py::arg("R"));
  rf.def("circle_smooth", &circle_smooth, u, v, py::arg("R"));
  rf.def("rectangle", &rectangle, u, v, py::arg("a"), py::arg("b"));
  rf.def("ellipse", &ellipse, u, v, py::arg("a"), py::arg("b"));
  rf.def("segment", &segment, u, v, py::arg("x1"), py::arg("y1"), py::arg("x2"), py::arg("y2"));
  rf.def("halfspace", &halfspace, x, y, z, py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"));
  rf.def("sphere", &sphere, x, y, z, py::arg("R"), "(R^2 - r^2) / (2R), normalised.");
  rf.def("cuboid", &cuboid, x, y, z, py::arg("a"), py::arg("b"), py::arg("c"));
  rf.def("cylinder", &cylinder, x, y, z, py::arg("R"), py::arg("h"));
  rf.def("cone", &cone, x, y, z, py::arg("R"), py::arg("H"));
  rf.def("torus", &torus, x, y, z, py::arg("R"), py::arg("r"));
  rf.def("ellipsoid", &ellipsoid, x, y, z, py::arg("a"), py::arg("b"), py::arg("c"));
  rf.def("translate", &translate, py::arg("F"), py::arg("dx"), py::arg("dy"), py::arg("dz"));
  rf.def("rotate", &rotate, py::arg("F"), py::arg("ax"), py::arg("ay"), py::arg("az"),
         py::arg("angle"));
  rf.def("scale_xyz", &scale_xyz, py::arg("F"), py::arg("sx"), py::arg("sy"), py::arg("sz"));
  rf.def("cone_map", &cone_map, py::arg("F"), py::arg("x0"), py::arg("y0"), py::arg("z0"));
  rf.def("fold_x", &fold_x, py::arg("F"), py::arg("h"));
  rf.def("fold_cyclic", &fold_cyclic, py::arg("F"), py::arg("n"));
  rf.def("fold_cyclic_fourier", &fold_cyclic_fourier, py::arg("F"), py::arg("n"), py::arg("N"));
  rf.def("segment_frame", &segment_frame, u, py::arg("r"), py::arg("a"));
  rf.def("arc_frame", &arc_frame, u, v, py::arg("R"), py::arg("beta"));
  rf.def(
      "polygon_region",
      [](const Expr& u, const Expr& v, const MatrixXd& V) {
        require_shape(V, 2, "vertices", 3);
        std::vector<Eigen::Vector2d> vertices;
        for (Index i = 0; i < V.rows(); ++i)
          vertices.push_back(V.row(i).transpose());
        return polygon_region(u, v, vertices);
      },
      u, v, py::arg("vertices"),
      "Signed distance to the closed polyline vertices (#V, 2), + inside (seed 003 (3)-(6)).");
  rf.def(
      "compile", [](const Expr& F, const MatrixXd& box) { return compile(F, box_from_array(box)); },
      py::arg("F"), py::arg("box"),
      "Compiles F into an Implicit (batch values, dual-number gradients); box (2, 3) [min, max].");
  rf.def(
      "load_model_expression",
      [](const std::string& path, const std::map<std::string, double>& parameters,
         const std::string& output) {
        ModelExpression e = load_model_expression(path, ModelOptions{output, parameters});
        return py::make_tuple(e.F, box_to_array(e.box));
      },
      py::arg("path"), py::arg("parameters") = std::map<std::string, double>{},
      py::arg("output") = "res", "A model file's expression and box, not compiled: (Expr, box).");
}

} // namespace

void bind_rfunctions(py::module_& m) {
  bind_implicit(m);
  py::module_ rf = m.def_submodule("rf", "R-function expressions (seeds 000, 002, 003).");
  bind_expr(rf);
  bind_primitives(rf);
}

} // namespace interlin::python
