#pragma once
// Least-squares B-spline curve approximation with a smoothing weight and a user tolerance, for
// noisy section data (seed 001 ch. 3: "the coefficients are found by least squares"; digest 001
// §2.2 option (b), least squares with regularisation). Minimises
//   (1/N) sum_i |C(u_i) - P_i|^2 + lambda * int |C''(u)|^2 du / L^2,
// L the polyline length (so lambda is dimensionless), over the control points, open (clamped) or
// closed (periodic, C^{p-1} at the seam).

#include "interlin/splines/bspline_curve.h"

namespace interlin {

struct ApproximationOptions {
  int degree = 3;
  bool closed = false;
  int num_ctrl = 0;     // distinct control points (the start when tolerance > 0);
                        // 0 = max(degree + 1, 8)
  double smoothing = 0; // lambda >= 0 (needs degree >= 2 when > 0)
  double tolerance = 0; // > 0: double num_ctrl (up to #P) until the max deviation <= tolerance
  double parameter_exponent = 1.0; // 1 chord length, 0.5 centripetal
  // Given parameters instead (#P increasing from 0, closed: #P + 1 with the closing one last;
  // e.g. chord lengths of a smoothed copy of noisy points); empty: chord_parameters(P).
  Eigen::VectorXd parameters;
  // Closed curves only, > 0: every knot is rounded to a multiple of knot_grid (the parameters
  // must start at one and span one, e.g. chord parameters 0..1 and a power of 1/2), so that
  // curves fitted separately share knot values and their knot union (make_compatible) has no
  // near-coincident knots. Throws std::invalid_argument if rounding merges two knots.
  double knot_grid = 0;
  // Closed curves only, non-empty: #P positive weights, w_i for the parameter interval
  // [u_i, u_{i+1}] (the last one closing the curve); the knots split the cumulative weight into
  // equal parts (linear inside an interval), so a heavier stretch gets shorter knot spans. Empty:
  // all 1 (parameter quantiles).
  Eigen::VectorXd knot_weights;
};

struct Approximation {
  BSplineCurve curve;
  Eigen::VectorXd u;        // parameters of the points (#P), in the curve's domain
  double max_deviation = 0; // max_i |C(u_i) - P_i|
  double rms_deviation = 0;
  Eigen::Index worst_point = 0;
  bool met_tolerance = true; // false when the tolerance was not reached with #P control points
};

// Inputs: P #P by dim (consecutive points distinct; closed: do not repeat P_0), options.
// Knots follow the data (Piegl & Tiller eq. 9.68-9.69 averaging; periodic: parameter quantiles),
// so every knot span holds data. Throws std::invalid_argument for bad options (degree < 1,
// degree >= #P, num_ctrl out of [degree+1, #P], negative smoothing, non-finite points) and
// std::runtime_error when the normal equations are singular.
Approximation approximate_curve(const Eigen::MatrixXd& P, const ApproximationOptions& options);

// int |C''(u)|^2 du over the curve's domain (exact Gauss quadrature per span). Degree >= 2.
double bending_energy(const BSplineCurve& c);

} // namespace interlin
