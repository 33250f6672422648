#pragma once
// B-spline curves of any degree and dimension, and their explicit per-span polynomial form.

#include <Eigen/Core>

namespace interlin {

// C(u) = sum_i N_{i,degree}(u) ctrl.row(i), u in [knots(degree), knots(#ctrl)].
//   knots  #ctrl + degree + 1, non-decreasing
//   ctrl   #ctrl by dim
//   periodic  the last `degree` rows of ctrl repeat the first ones and the knot vector is the
//             periodic extension of one period: C is closed and C^{degree-1} at the seam, and
//             evaluation wraps u into the domain.
struct BSplineCurve {
  int degree = 3;
  Eigen::VectorXd knots;
  Eigen::MatrixXd ctrl;
  bool periodic = false;
};

// Parameter domain [knots(degree), knots(#ctrl)].
double domain_begin(const BSplineCurve& c);
double domain_end(const BSplineCurve& c);

// Explicit form (seed 001 §2.1.3 applied to a curve): on span j, C(u) = sum_q coeffs.row(j*(p+1)+q)
// (u - breaks(j))^q. Only non-empty spans of the domain are kept.
//   breaks  s+1 increasing values, the domain's distinct knots
//   coeffs  (s*(degree+1)) by dim
struct PiecewiseCurve {
  int degree = 3;
  Eigen::VectorXd breaks;
  Eigen::MatrixXd coeffs;
  bool periodic = false;
};

PiecewiseCurve to_piecewise(const BSplineCurve& c);

// deriv-th derivative of the curve at each u (Horner per span). Output: #u by dim.
Eigen::MatrixXd evaluate(const PiecewiseCurve& c, const Eigen::VectorXd& u, int deriv = 0);
Eigen::MatrixXd evaluate(const BSplineCurve& c, const Eigen::VectorXd& u, int deriv = 0);

} // namespace interlin
