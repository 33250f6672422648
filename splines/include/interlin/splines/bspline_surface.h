#pragma once
// Tensor-product B-spline surfaces and their explicit per-patch polynomial form.

#include <Eigen/Core>

namespace interlin {

// S(u,v) = sum_i sum_j N_i(u) M_j(v) ctrl.row(i + num_u * j), clamped in both directions.
//   knots_u  num_u + degree_u + 1;  knots_v  num_v + degree_v + 1
//   ctrl     (num_u * num_v) by 3
//   closed_u the boundaries u = begin and u = end coincide (closed sections); the surface is then
//            C^{degree_u - 1} across that seam and evaluation wraps u.
struct BSplineSurface {
  int degree_u = 3, degree_v = 3;
  Eigen::VectorXd knots_u, knots_v;
  Eigen::Index num_u = 0, num_v = 0;
  Eigen::MatrixXd ctrl;
  bool closed_u = false;
};

// Throws std::invalid_argument unless sizes, knots and control points are consistent and finite.
void check_surface(const BSplineSurface& s);

// Explicit form: on patch (a, b) = [breaks_u(a), breaks_u(a+1)] x [breaks_v(b), breaks_v(b+1)],
// S(u,v) = sum_{i,j} coeffs.row(((a*sv + b)*(pu+1) + i)*(pv+1) + j) (u-breaks_u(a))^i
// (v-breaks_v(b))^j, with su = #breaks_u - 1, sv = #breaks_v - 1.
struct PiecewiseSurface {
  int degree_u = 3, degree_v = 3;
  Eigen::VectorXd breaks_u, breaks_v;
  Eigen::MatrixXd coeffs;
  bool closed_u = false;
};

PiecewiseSurface to_piecewise(const BSplineSurface& s);

// Partial derivative d^(du+dv) S / du^du dv^dv at (u, v); (0,0) is the point.
Eigen::Vector3d evaluate(const PiecewiseSurface& s, double u, double v, int du = 0, int dv = 0);

// The point and every partial derivative of order 1 and 2 at (u, v), from one patch lookup and
// one pass over its coefficients (the six evaluate() calls of a Newton step in one).
struct SurfaceDerivatives {
  Eigen::Vector3d S, Su, Sv, Suu, Suv, Svv;
};
SurfaceDerivatives evaluate_derivatives(const PiecewiseSurface& s, double u, double v);

// S at every pair of the grid u x v. Output: (#u * #v) by 3, row i + #u * j.
Eigen::MatrixXd evaluate_grid(const PiecewiseSurface& s, const Eigen::VectorXd& u,
                              const Eigen::VectorXd& v);

// Parameter domain of the surface.
Eigen::Vector4d domain(const PiecewiseSurface& s); // (u0, u1, v0, v1)

} // namespace interlin
