#pragma once
// Internal: the node of an R-function expression graph. Expressions are immutable trees of shared
// nodes (a DAG once variables are reused); compile() hash-conses them into a program.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/limits.h"

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace interlin::rf::detail {

// Elementary operations. Everything the library offers (R-operations, primitives, transforms,
// normalisation) is built from these, so the kernels, the constant folder and the graph
// differentiation each handle one short list.
enum class Op : unsigned char {
  // leaves
  constant,
  x,
  y,
  z,
  // arithmetic
  add,
  sub,
  mul,
  div,
  neg,
  pow_k, // a^k, k a constant
  pow,   // a^b
  // elementary functions
  sqrt,
  abs,
  sign,
  sin,
  cos,
  tan,
  asin,
  acos,
  atan,
  atan2, // atan2(a, b)
  exp,
  log,
  min,
  max,
  hypot, // sqrt(a^2 + b^2)
  ratio, // a / b, and 0 where b = 0: the derivative factors at singular points
  // R0 system, seed 000 (2.1): a + b -+ sqrt(a^2 + b^2)
  and0,
  or0,
  // signed distance to a closed polyline (seed 003 (3)-(6)) and its partial derivatives
  curve,
  curve_du,
  curve_dv,
  // an implicit body from elsewhere (an .ifl model) at the point (a, b, c), and its partial
  // derivatives
  field,
  field_dx,
  field_dy,
  field_dz,
  // immediate forms, only in compiled programs: one operand and the constant k
  add_k,  // a + k
  mul_k,  // a * k
  k_sub,  // k - a
  k_div,  // k / a
  div_k,  // a / k
  square, // a * a
};

// A closed polyline in the plane: the boundary of a 2D region for the `curve` operations.
struct Polyline {
  std::vector<Eigen::Vector2d> points; // vertices; the closing segment is implicit
  double orientation = 1;              // twice the signed area: > 0 counter-clockwise
  // Signed distance: + inside (odd number of crossings, half-open rule), - outside; gradient
  // (du, dv) of the signed distance (the unit vector away from the nearest point, oriented
  // inward; on the curve the inward normal of the nearest segment).
  double signed_distance(double u, double v, double* du = nullptr, double* dv = nullptr) const;
};

// The longest operand chain an expression may have (limits::expression_depth): the graph
// passes (differentiation, substitution, compilation, destruction) recurse along it.
inline constexpr int kMaxDepth = limits::expression_depth;

struct Node {
  Op op;
  double k = 0;                                  // the constant of `constant` and `pow_k`
  int depth = 0;                                 // longest chain of operands below this node
  std::shared_ptr<const Node> a, b, c;           // c: the third operand of the field ops
  std::shared_ptr<const Polyline> curve;         // for the curve operations
  std::shared_ptr<const ImplicitFunction> field; // for the field operations
};

using NodePtr = std::shared_ptr<const Node>;

int arity(Op op);
const char* op_name(Op op);

// A budget of work while it is alive on its thread: every node make() builds counts one, and
// the model evaluator charges each function call it expands and the samples of Bezier regions;
// past `limit` units a LimitError is thrown (limits::model_size). Budgets nest: the innermost
// one counts. Without a budget nothing is counted.
class NodeBudget {
public:
  explicit NodeBudget(long long limit);
  ~NodeBudget();
  NodeBudget(const NodeBudget&) = delete;
  NodeBudget& operator=(const NodeBudget&) = delete;
  // Charges `units` to the current thread's budget, if any.
  static void charge(long long units = 1);

private:
  long long limit_, used_ = 0;
  NodeBudget* outer_;
};

// The one constructor of operation nodes: folds constants and drops identities (x + 0, x * 1, ...).
NodePtr make(Op op, NodePtr a, NodePtr b = nullptr, double k = 0,
             std::shared_ptr<const Polyline> curve = nullptr, NodePtr c = nullptr,
             std::shared_ptr<const ImplicitFunction> field = nullptr);

// The value (op field) or a partial derivative (field_dx, ...) of `field` at one point.
double field_value(Op op, const ImplicitFunction& field, double x, double y, double z);

} // namespace interlin::rf::detail
