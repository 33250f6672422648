#pragma once
// Cardinal blending functions of interlineation (digest 001 §5.1 [SUPPLEMENT]):
// alpha_i(x_k) = delta_ik on nodes x_0 < ... < x_{n-1}, built from the explicit nonuniform
// B-splines (seed 001, Theorem 1) of the splines module. Degree 1 gives the hat functions of
// composite bilinear Coons (C0), degree 2 a C1 and degree 3 a C2 family.

#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/spline_basis.h"

namespace interlin {

// All n cardinal functions as one clamped curve with n-dimensional control points:
// curve(x) = (alpha_0(x), ..., alpha_{n-1}(x)).
//   nodes     n increasing nodes
//   periodic  the functions are periodic with `period`; the curve covers one period
//             [begin, begin + period], which contains every node
//   basis     the curve's basis in explicit per-span form (evaluation)
struct CardinalSplines {
  Eigen::VectorXd nodes;
  BSplineCurve curve;
  SplineBasis basis;
  bool periodic = false;
  double begin = 0, period = 0;
};

// Open family: alpha_i is the spline of degree min(degree, n-1) through the data delta_ik with
// knots by averaging (interpolate_open of the identity). n >= 2 (n = 1 gives alpha_0 = 1).
// Throws std::invalid_argument for non-increasing nodes or degree < 1.
CardinalSplines cardinal_splines(const Eigen::VectorXd& nodes, int degree);

// Periodic family with period `period` on [begin, begin + period): degree 1 (periodic hats) or
// degree 3 (periodic cubic splines with knots at the nodes, C2, from the cyclic system for the
// second derivatives M_i: h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (second
// divided difference), which is regular for every n >= 2; n = 1 gives alpha_0 = 1).
// Nodes must lie in [begin, begin + period). The result is written as a clamped curve on
// [begin, begin + period] with knots at the nodes; it is C^(degree-1) across the period's ends.
CardinalSplines periodic_cardinal_splines(const Eigen::VectorXd& nodes, double begin, double period,
                                          int degree);

// Values and derivatives of all n functions at x (periodic families wrap x into the period).
// Output: (nderiv+1) by n, row d = d-th derivatives.
Eigen::MatrixXd evaluate(const CardinalSplines& c, double x, int nderiv = 0);

} // namespace interlin
