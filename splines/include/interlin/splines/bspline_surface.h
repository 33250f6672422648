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

// The second-order jet of S at (u, v): the point and its partial derivatives up to order 2, in
// one pass over the patch's coefficients (Horner in v for the three v-orders, then in u).
// Outside the domain (open directions) the end patches' polynomials are extended.
struct SurfaceJet {
  Eigen::Vector3d S = Eigen::Vector3d::Zero(), Su = Eigen::Vector3d::Zero(),
                  Sv = Eigen::Vector3d::Zero(), Suu = Eigen::Vector3d::Zero(),
                  Suv = Eigen::Vector3d::Zero(), Svv = Eigen::Vector3d::Zero();
};
SurfaceJet evaluate_jet(const PiecewiseSurface& s, double u, double v);

// S at every pair of the grid u x v. Output: (#u * #v) by 3, row i + #u * j.
Eigen::MatrixXd evaluate_grid(const PiecewiseSurface& s, const Eigen::VectorXd& u,
                              const Eigen::VectorXd& v);

// Parameter domain of the surface.
Eigen::Vector4d domain(const PiecewiseSurface& s); // (u0, u1, v0, v1)

} // namespace interlin
