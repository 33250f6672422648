#pragma once
// B-spline curve interpolation through points: open (clamped) and closed (periodic).

#include "interlin/splines/bspline_curve.h"

namespace interlin {

// Open clamped interpolant C(u_i) = P_i of degree min(degree, #P-1), knots by averaging.
//   P  #P by dim;  u  #P increasing parameters with u(0) = 0, u(end) = 1
BSplineCurve interpolate_open(const Eigen::MatrixXd& P, const Eigen::VectorXd& u, int degree);

// Periodic interpolant through a closed polygon: C(u_i) = P_i, C closed and C^{degree-1}
// everywhere, seam included.
//   P      N by dim, the distinct points (do not repeat P_0 at the end)
//   u      N+1 increasing parameters: u(0..N-1) for the points, u(N) closes the loop
//   knots  optional periodic knot vector (periodic_knots of some parameter vector); the sites u
//          must satisfy the Schoenberg–Whitney condition for it, else std::runtime_error.
// Output: periodic curve with N+degree control points; domain contains [u(0), u(N)].
BSplineCurve interpolate_closed(const Eigen::MatrixXd& P, const Eigen::VectorXd& u, int degree);
BSplineCurve interpolate_closed(const Eigen::MatrixXd& P, const Eigen::VectorXd& u, int degree,
                                const Eigen::VectorXd& knots);

} // namespace interlin
