// R-function expressions: construction with constant folding, graph differentiation,
// substitution.
#include "interlin/interflatation/rfunctions/expression.h"

#include "node.h"
#include "op_kernels.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace interlin::rf {

namespace detail {

int arity(Op op) {
  switch (op) {
  case Op::constant:
  case Op::x:
  case Op::y:
  case Op::z:
    return 0;
  case Op::add:
  case Op::sub:
  case Op::mul:
  case Op::div:
  case Op::pow:
  case Op::atan2:
  case Op::min:
  case Op::max:
  case Op::hypot:
  case Op::ratio:
  case Op::and0:
  case Op::or0:
  case Op::curve:
  case Op::curve_du:
  case Op::curve_dv:
    return 2;
  case Op::field:
  case Op::field_dx:
  case Op::field_dy:
  case Op::field_dz:
    return 3;
  default:
    return 1;
  }
}

const char* op_name(Op op) {
  static const char* const names[] = {
      "constant", "x",     "y",        "z",        "add",   "sub",      "mul",
      "div",      "neg",   "pow_k",    "pow",      "sqrt",  "abs",      "sign",
      "sin",      "cos",   "tan",      "asin",     "acos",  "atan",     "atan2",
      "exp",      "log",   "min",      "max",      "hypot", "ratio",    "and0",
      "or0",      "curve", "curve_du", "curve_dv", "field", "field_dx", "field_dy",
      "field_dz", "add_k", "mul_k",    "k_sub",    "k_div", "div_k",    "square"};
  return names[static_cast<int>(op)];
}

double r0_nonfinite(double a, double b, double s) {
  if (a != a)
    a = -kInf;
  if (b != b)
    b = -kInf;
  if (is_finite(a) && is_finite(b)) { // the squares overflowed: scale
    const double m = std::max(std::abs(a), std::abs(b));
    const double p = a / m, q = b / m;
    return m * (s < 0 ? value<Op::and0>(p, q, 0) : value<Op::or0>(p, q, 0));
  }
  // The limits: a ^0 (+inf) = a, a ^0 (-inf) = -inf; a v0 (-inf) = a, a v0 (+inf) = +inf.
  const double absorbing = s < 0 ? -kInf : kInf;
  if (a == absorbing || b == absorbing)
    return absorbing;
  if (!is_finite(a) && !is_finite(b))
    return a; // both the neutral infinity
  return is_finite(a) ? a : b;
}

double fold_value(Op op, double a, double b, double k) {
  switch (op) {
#define INTERLIN_FOLD(o)                                                                           \
  case Op::o:                                                                                      \
    return checked_value<Op::o>(a, b, k);
    INTERLIN_RF_VALUE_OPS(INTERLIN_FOLD)
#undef INTERLIN_FOLD
  default:
    throw std::logic_error(std::string("fold_value: not a foldable operation: ") + op_name(op));
  }
}

namespace {

thread_local NodeBudget* current_budget = nullptr;

} // namespace

NodeBudget::NodeBudget(long long limit) : limit_(limit), outer_(current_budget) {
  current_budget = this;
}

NodeBudget::~NodeBudget() {
  current_budget = outer_;
}

void NodeBudget::charge(long long units) {
  NodeBudget* b = current_budget;
  if (!b)
    return;
  if (units <= b->limit_ - b->used_) { // used_ <= limit_ always: no overflow
    b->used_ += units;
    return;
  }
  throw LimitError("the model needs more than the model-size limit of " +
                       std::to_string(b->limit_) +
                       " units (expression nodes, function calls, Bezier samples)",
                   "max-model-size");
}

namespace {

NodePtr leaf(Op op, double k = 0) {
  NodeBudget::charge();
  auto n = std::make_shared<Node>();
  n->op = op;
  n->k = k;
  return n;
}

bool is_const(const NodePtr& n, double v) {
  return n->op == Op::constant && n->k == v;
}

} // namespace

// Drops the identities that graph differentiation produces in bulk (x + 0, x * 1, x * 0, ...).
double field_value(Op op, const ImplicitFunction& field, double x, double y, double z) {
  Points3 P(1, 3);
  P << x, y, z;
  Eigen::VectorXd F(1);
  if (op == Op::field) {
    field.value(P, F);
    return F(0);
  }
  Points3 G(1, 3);
  field.gradient(P, F, G);
  return G(0, static_cast<int>(op) - static_cast<int>(Op::field_dx));
}

NodePtr make(Op op, NodePtr a, NodePtr b, double k, std::shared_ptr<const Polyline> curve,
             NodePtr c, std::shared_ptr<const ImplicitFunction> field) {
  const bool ca = a && a->op == Op::constant;
  const bool cb = !b || b->op == Op::constant;
  const bool cc = !c || c->op == Op::constant;
  if (ca && cb && cc) {
    if (field)
      return leaf(Op::constant, field_value(op, *field, a->k, b->k, c->k));
    if (curve) {
      double du = 0, dv = 0;
      const double d = curve->signed_distance(a->k, b->k, &du, &dv);
      return leaf(Op::constant, op == Op::curve ? d : op == Op::curve_du ? du : dv);
    }
    return leaf(Op::constant, fold_value(op, a->k, b ? b->k : 0.0, k));
  }
  switch (op) {
  case Op::add:
    if (is_const(a, 0))
      return b;
    if (is_const(b, 0))
      return a;
    break;
  case Op::sub:
    if (is_const(b, 0))
      return a;
    if (is_const(a, 0))
      return make(Op::neg, b);
    break;
  case Op::mul:
    if (is_const(a, 0) || is_const(b, 0))
      return leaf(Op::constant, 0.0);
    if (is_const(a, 1))
      return b;
    if (is_const(b, 1))
      return a;
    if (is_const(a, -1))
      return make(Op::neg, b);
    if (is_const(b, -1))
      return make(Op::neg, a);
    break;
  case Op::div:
    if (is_const(b, 1))
      return a;
    if (is_const(a, 0))
      return leaf(Op::constant, 0.0);
    break;
  case Op::ratio:
    if (is_const(a, 0) || is_const(b, 0))
      return leaf(Op::constant, 0.0);
    break;
  case Op::neg:
    if (a->op == Op::neg)
      return a->a;
    break;
  case Op::pow_k:
    if (k == 1)
      return a;
    if (k == 0)
      return leaf(Op::constant, 1.0);
    break;
  case Op::pow:
    if (cb)
      return make(Op::pow_k, a, nullptr, b->k);
    break;
  default:
    break;
  }
  NodeBudget::charge();
  auto n = std::make_shared<Node>();
  n->op = op;
  n->k = k;
  n->depth = 1 + std::max({a->depth, b ? b->depth : 0, c ? c->depth : 0});
  if (n->depth > kMaxDepth)
    throw std::invalid_argument("expression too deep: more than " + std::to_string(kMaxDepth) +
                                " nested operations");
  n->a = std::move(a);
  n->b = std::move(b);
  n->c = std::move(c);
  n->curve = std::move(curve);
  n->field = std::move(field);
  return n;
}

} // namespace detail

using detail::make;
using detail::Node;
using detail::NodePtr;
using detail::Op;

namespace {

Expr E(NodePtr n) {
  return Expr(std::move(n));
}

} // namespace

Expr::Expr(double constant) : node_(detail::leaf(Op::constant, constant)) {}
Expr Expr::x() {
  static const NodePtr n = detail::leaf(Op::x);
  return Expr(n);
}
Expr Expr::y() {
  static const NodePtr n = detail::leaf(Op::y);
  return Expr(n);
}
Expr Expr::z() {
  static const NodePtr n = detail::leaf(Op::z);
  return Expr(n);
}
bool Expr::is_constant() const {
  return node_->op == Op::constant;
}
double Expr::constant_value() const {
  if (!is_constant())
    throw std::invalid_argument("Expr::constant_value: the expression depends on x, y or z");
  return node_->k;
}

Expr operator+(const Expr& a, const Expr& b) {
  return E(make(Op::add, a.node(), b.node()));
}
Expr operator-(const Expr& a, const Expr& b) {
  return E(make(Op::sub, a.node(), b.node()));
}
Expr operator*(const Expr& a, const Expr& b) {
  return E(make(Op::mul, a.node(), b.node()));
}
Expr operator/(const Expr& a, const Expr& b) {
  return E(make(Op::div, a.node(), b.node()));
}
Expr operator-(const Expr& a) {
  return E(make(Op::neg, a.node()));
}
Expr pow(const Expr& a, const Expr& b) {
  return E(make(Op::pow, a.node(), b.node()));
}
#define INTERLIN_UNARY(f)                                                                          \
  Expr f(const Expr& a) {                                                                          \
    return E(make(Op::f, a.node()));                                                               \
  }
INTERLIN_UNARY(sqrt)
INTERLIN_UNARY(abs)
INTERLIN_UNARY(sign)
INTERLIN_UNARY(sin)
INTERLIN_UNARY(cos)
INTERLIN_UNARY(tan)
INTERLIN_UNARY(asin)
INTERLIN_UNARY(acos)
INTERLIN_UNARY(atan)
INTERLIN_UNARY(exp)
INTERLIN_UNARY(log)
#undef INTERLIN_UNARY
Expr atan2(const Expr& y, const Expr& x) {
  return E(make(Op::atan2, y.node(), x.node()));
}
Expr min(const Expr& a, const Expr& b) {
  return E(make(Op::min, a.node(), b.node()));
}
Expr max(const Expr& a, const Expr& b) {
  return E(make(Op::max, a.node(), b.node()));
}
Expr hypot(const Expr& a, const Expr& b) {
  return E(make(Op::hypot, a.node(), b.node()));
}

Expr field(std::shared_ptr<const ImplicitFunction> body, const Expr& X, const Expr& Y,
           const Expr& Z) {
  if (!body || !body->value || !body->gradient)
    throw std::invalid_argument("field: the body needs a value and a gradient function");
  return E(make(Op::field, X.node(), Y.node(), 0, nullptr, Z.node(), std::move(body)));
}

namespace {

// Forward-mode differentiation of the graph: d(n) = sum over operands of (partial) * d(operand),
// with the partials written as expressions. Memoised per node so shared sub-expressions are
// differentiated once and the result stays a DAG.
class Differentiator {
public:
  explicit Differentiator(int axis) : axis_(axis) {}

  NodePtr d(const NodePtr& n) {
    auto it = memo_.find(n.get());
    if (it != memo_.end())
      return it->second;
    NodePtr r = rule(n);
    memo_.emplace(n.get(), r);
    return r;
  }

private:
  static NodePtr c(double v) { return detail::leaf(Op::constant, v); }

  NodePtr rule(const NodePtr& n) {
    const NodePtr& a = n->a;
    const NodePtr& b = n->b;
    switch (n->op) {
    case Op::constant:
      return c(0);
    case Op::x:
      return c(axis_ == 0);
    case Op::y:
      return c(axis_ == 1);
    case Op::z:
      return c(axis_ == 2);
    case Op::add:
      return make(Op::add, d(a), d(b));
    case Op::sub:
      return make(Op::sub, d(a), d(b));
    case Op::mul:
      return make(Op::add, make(Op::mul, d(a), b), make(Op::mul, a, d(b)));
    case Op::div: // (a' - (a/b) b') / b
      return make(Op::div, make(Op::sub, d(a), make(Op::mul, n, d(b))), b);
    case Op::neg:
      return make(Op::neg, d(a));
    case Op::pow_k: // k a^k / a a', 0 at a = 0
      return make(Op::mul, make(Op::mul, c(n->k), make(Op::ratio, n, a)), d(a));
    case Op::pow: // b a^b / a a' + a^b log(a) b'
      return make(Op::add, make(Op::mul, make(Op::mul, b, make(Op::ratio, n, a)), d(a)),
                  make(Op::mul, make(Op::mul, n, make(Op::log, a)), d(b)));
    case Op::sqrt: // a' / (2 sqrt a), 0 at a = 0
      return make(Op::mul, c(0.5), make(Op::ratio, d(a), n));
    case Op::abs:
      return make(Op::mul, make(Op::sign, a), d(a));
    case Op::sign:
      return c(0);
    case Op::sin:
      return make(Op::mul, make(Op::cos, a), d(a));
    case Op::cos:
      return make(Op::neg, make(Op::mul, make(Op::sin, a), d(a)));
    case Op::tan:
      return make(Op::mul, make(Op::add, c(1), make(Op::pow_k, n, nullptr, 2)), d(a));
    case Op::asin:
    case Op::acos: {
      NodePtr s =
          make(Op::div, d(a), make(Op::sqrt, make(Op::sub, c(1), make(Op::pow_k, a, nullptr, 2))));
      return n->op == Op::asin ? s : make(Op::neg, s);
    }
    case Op::atan:
      return make(Op::div, d(a), make(Op::add, c(1), make(Op::pow_k, a, nullptr, 2)));
    case Op::atan2: // (b a' - a b') / (a^2 + b^2)
      return make(Op::ratio, make(Op::sub, make(Op::mul, b, d(a)), make(Op::mul, a, d(b))),
                  make(Op::add, make(Op::pow_k, a, nullptr, 2), make(Op::pow_k, b, nullptr, 2)));
    case Op::exp:
      return make(Op::mul, n, d(a));
    case Op::log:
      return make(Op::div, d(a), a);
    case Op::min:
    case Op::max: { // (a' + b' -+ sign(a - b)(a' - b')) / 2: the active operand, the mean at ties
      const Op pm = n->op == Op::min ? Op::sub : Op::add;
      NodePtr sw = make(Op::mul, make(Op::sign, make(Op::sub, a, b)), make(Op::sub, d(a), d(b)));
      return make(Op::mul, c(0.5), make(pm, make(Op::add, d(a), d(b)), sw));
    }
    case Op::hypot: // (a a' + b b') / h
      return make(Op::ratio, make(Op::add, make(Op::mul, a, d(a)), make(Op::mul, b, d(b))), n);
    case Op::ratio: // (a' - (a/b) b') / b, 0 where b = 0
      return make(Op::ratio, make(Op::sub, d(a), make(Op::mul, n, d(b))), b);
    case Op::and0:
    case Op::or0: { // a' + b' -+ (a a' + b b') / sqrt(a^2 + b^2)  (seed 000 §2.3)
      NodePtr h = make(Op::hypot, a, b);
      NodePtr t = make(Op::ratio, make(Op::add, make(Op::mul, a, d(a)), make(Op::mul, b, d(b))), h);
      return make(n->op == Op::and0 ? Op::sub : Op::add, make(Op::add, d(a), d(b)), t);
    }
    case Op::curve: // grad of the signed distance; its own derivatives are taken as 0
      return make(Op::add, make(Op::mul, make(Op::curve_du, a, b, 0, n->curve), d(a)),
                  make(Op::mul, make(Op::curve_dv, a, b, 0, n->curve), d(b)));
    case Op::curve_du:
    case Op::curve_dv:
      return c(0);
    case Op::field: { // grad of the body's function; its own derivatives are taken as 0
      auto partial = [&](Op o) { return make(o, a, b, 0, nullptr, n->c, n->field); };
      return make(Op::add,
                  make(Op::add, make(Op::mul, partial(Op::field_dx), d(a)),
                       make(Op::mul, partial(Op::field_dy), d(b))),
                  make(Op::mul, partial(Op::field_dz), d(n->c)));
    }
    case Op::field_dx:
    case Op::field_dy:
    case Op::field_dz:
      return c(0);
    default:
      throw std::logic_error(std::string("derivative: unexpected operation ") + op_name(n->op));
    }
  }

  int axis_;
  std::unordered_map<const Node*, NodePtr> memo_;
};

class Substituter {
public:
  Substituter(NodePtr X, NodePtr Y, NodePtr Z)
      : X_(std::move(X)), Y_(std::move(Y)), Z_(std::move(Z)) {}

  NodePtr s(const NodePtr& n) {
    switch (n->op) {
    case Op::constant:
      return n;
    case Op::x:
      return X_;
    case Op::y:
      return Y_;
    case Op::z:
      return Z_;
    default:
      break;
    }
    auto it = memo_.find(n.get());
    if (it != memo_.end())
      return it->second;
    NodePtr a = s(n->a);
    NodePtr b = n->b ? s(n->b) : nullptr;
    NodePtr c = n->c ? s(n->c) : nullptr;
    NodePtr r =
        (a == n->a && b == n->b && c == n->c) ? n : make(n->op, a, b, n->k, n->curve, c, n->field);
    memo_.emplace(n.get(), r);
    return r;
  }

private:
  NodePtr X_, Y_, Z_;
  std::unordered_map<const Node*, NodePtr> memo_;
};

} // namespace

Expr derivative(const Expr& F, int axis) {
  if (axis < 0 || axis > 2)
    throw std::invalid_argument("derivative: axis must be 0 (x), 1 (y) or 2 (z), got " +
                                std::to_string(axis));
  return E(Differentiator(axis).d(F.node()));
}

Expr substitute(const Expr& F, const Expr& X, const Expr& Y, const Expr& Z) {
  return E(Substituter(X.node(), Y.node(), Z.node()).s(F.node()));
}

} // namespace interlin::rf
