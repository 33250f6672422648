#pragma once
// Traces of a function of two variables on the lines of a rectangular grid (seed 001 §2.5-2.7):
// the data of every interlineation operator. A trace is the restriction of f (scalar or vector
// valued) to one line, given as a callable, as sampled data (interpolated) or as a spline curve.

#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace interlin {

// t(s, d) = d-th derivative of the trace at the coordinate s along its line, a row of dim
// values (dim = 1 for scalar functions). Callables that cannot differentiate should throw
// std::invalid_argument for d > 0 (operators ask for derivatives only when evaluated with them).
using Trace = std::function<Eigen::RowVectorXd(double s, int deriv)>;

// The trace given by a spline curve (value and every derivative; periodic curves wrap).
Trace spline_trace(const BSplineCurve& c);

// The trace through sampled data: the open interpolating spline of degree min(degree, #s - 1)
// through values.row(k) at s(k) (s increasing). Reproduces the samples exactly.
Trace sampled_trace(const Eigen::VectorXd& s, const Eigen::MatrixXd& values, int degree);

// Traces on the lines x = x_i (functions of y) and y = y_j (functions of x); either family may be
// empty (interlineation on one family of lines).
//   x     #x increasing;  on_x[i](y, d) = d^d/dy^d f(x_i, y)
//   y     #y increasing;  on_y[j](x, d) = d^d/dx^d f(x, y_j)
struct LineTraces {
  Eigen::VectorXd x, y;
  std::vector<Trace> on_x, on_y;
};

// Compatibility at the crossings: on_x[i](y_j) = on_y[j](x_i) for all i, j, to within
// tolerance * max(1, |value|) in every component. Returns f(x_i, y_j) as (#x * #y) by dim
// (row i + #x * j, the mean of the two traces' values). Throws std::invalid_argument naming the
// first crossing where the traces disagree, or for sizes that do not match (#x vs on_x, ...),
// non-increasing lines or traces of different dimensions.
Eigen::MatrixXd crossing_values(const LineTraces& traces, double tolerance = 1e-10);

// The same test for any pair of trace families: a(i)(s_a(j), deriv_a) against
// b(j)(s_b(i), deriv_b); `what` names the quantity in the message ("value", "f_x", ...).
// Returns the means, (#a * #b) by dim, row i + #a * j.
Eigen::MatrixXd crossing_values(const std::vector<Trace>& a, const Eigen::VectorXd& s_b,
                                int deriv_a, const std::vector<Trace>& b,
                                const Eigen::VectorXd& s_a, int deriv_b, double tolerance,
                                const std::string& what);

} // namespace interlin
