#pragma once
// R-function expressions: scalar fields F(x,y,z) built from constants, the coordinates and
// elementary operations, compiled into a batch-evaluated ImplicitFunction (seeds 000, 002, 003).
// Everything in interlin/interflatation/{r_operations,primitives,normalization,transforms,
// folding,frame_blending,curve_distance}.h returns an Expr; the .rf model language
// (model.h) is a front end to the same functions.
//
//   using namespace interlin::rf;
//   Expr x = Expr::x(), y = Expr::y(), z = Expr::z();
//   Expr body = and0(sphere(x, y, z, 1.0), -cylinder(x, y, z, 0.5, 2.0));
//   ImplicitFunction F = compile(body, box);

#include "interlin/interflatation/implicit_function.h"

#include <Eigen/Geometry>
#include <memory>

namespace interlin::rf {

namespace detail {
struct Node;
}

// An immutable expression; copies share structure (a DAG), so reusing a sub-expression costs
// nothing. Operations on constants fold at construction.
class Expr {
public:
  Expr(double constant = 0); // NOLINT: numbers convert implicitly, as in formulas
  explicit Expr(std::shared_ptr<const detail::Node> node) : node_(std::move(node)) {}

  static Expr x();
  static Expr y();
  static Expr z();

  bool is_constant() const;
  // The value of a constant expression; throws std::invalid_argument otherwise.
  double constant_value() const;
  const std::shared_ptr<const detail::Node>& node() const { return node_; }

private:
  std::shared_ptr<const detail::Node> node_;
};

Expr operator+(const Expr& a, const Expr& b);
Expr operator-(const Expr& a, const Expr& b);
Expr operator*(const Expr& a, const Expr& b);
Expr operator/(const Expr& a, const Expr& b);
Expr operator-(const Expr& a);

// Elementary functions (IEEE semantics: sqrt of a negative or log of a non-positive number is
// undefined, see compile()).
Expr pow(const Expr& a, const Expr& b); // a^b; an integer constant b allows a negative base
Expr sqrt(const Expr& a);
Expr abs(const Expr& a);
Expr sign(const Expr& a); // -1, 0, 1
Expr sin(const Expr& a);
Expr cos(const Expr& a);
Expr tan(const Expr& a);
Expr asin(const Expr& a);
Expr acos(const Expr& a);
Expr atan(const Expr& a);
Expr atan2(const Expr& y, const Expr& x);
Expr exp(const Expr& a);
Expr log(const Expr& a);
Expr min(const Expr& a, const Expr& b);
Expr max(const Expr& a, const Expr& b);
Expr hypot(const Expr& a, const Expr& b); // sqrt(a^2 + b^2)

// An implicit body defined elsewhere (an .ifl model, any ImplicitFunction) as an operand,
// evaluated at the point (X, Y, Z): R-operations can combine it with primitives, transforms move
// it. Its gradient comes from body->gradient (its own second derivatives are taken as 0), so
// derivative() and compile()'s gradient work through it. The body is called once per block of
// points. Throws std::invalid_argument for a null body.
Expr field(std::shared_ptr<const ImplicitFunction> body, const Expr& X, const Expr& Y,
           const Expr& Z);

// The partial derivative dF/d(axis), axis 0, 1, 2 for x, y, z, as an expression: forward-mode
// differentiation of the expression graph (the dual-number rules applied to the nodes), exact
// and itself differentiable. At singular points (R0 corners, sqrt at 0, atan2 at the origin) the
// singular factor is taken as 0.
Expr derivative(const Expr& F, int axis);

// F(X, Y, Z): F with the coordinates x, y, z replaced by the expressions X, Y, Z (simultaneously).
// Every coordinate transform is a substitution (seed 000 §2.8: "the 3D object is
// w(psi1(x,y,z), psi2(x,y,z)) = 0").
Expr substitute(const Expr& F, const Expr& X, const Expr& Y, const Expr& Z);

// Number of distinct operations in F after merging common sub-expressions.
int operation_count(const Expr& F);

// Compiles F into an ImplicitFunction with the given box.
// - value: F at every point, evaluated block by block (256 points) with one loop per operation
//   over the block (no call per point); gradient: the same program on dual numbers (value and
//   the three partial derivatives, forward mode).
// - Values are finite: where F is undefined (0/0, sqrt of a negative) the value is -DBL_MAX
//   (outside); +-inf become +-DBL_MAX; non-finite gradient components are 0.
// - Thread-safe: the program is immutable and shared by copies; scratch space is per thread.
ImplicitFunction compile(const Expr& F, const Eigen::AlignedBox3d& box);

} // namespace interlin::rf
