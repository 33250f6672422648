#pragma once
// seed 001 §2.2 (digest 001 §2.2, T18): closed section curves (blade sections) from points.
//
// The seed's model: x(t) = sum_k SS_2(t, M, k) CX_k, y likewise, quadratic B-splines whose knots
// are the chord-length parameters F_p of the points; for 33 points P_0..P_32 (P_32 = P_0) that is
// 34 coefficients, 33 interpolation rows and one tangent-closure row C'(F_0) = C'(F_32). With
// knots at the data parameters every row has two non-zeros and the system has the alternating
// null vector: for uniform parameters and an even number of intervals (33 points) it is exactly
// singular, for 34 points regular (digest ⚠, T18). seed_section_curve builds that system and
// detects the singular mode; closed_section_curve avoids it (periodic spline, knots at the
// midpoints for even degree, or least squares).

#include "interlin/splines/approximate_curve.h"
#include "interlin/splines/bspline_curve.h"

namespace interlin {

// The seed's literal system (§2.2): P #P by dim with the last point equal to the first (the
// closed polygon P_0..P_M, M >= 3 intervals), F #P increasing parameters. Output: the clamped
// quadratic curve on knots (F_0, F_0, F_0, F_1, ..., F_{M-1}, F_M, F_M, F_M), M + 2 control
// points, through every point, with C'(F_0) = C'(F_M).
// Throws std::runtime_error naming the alternating mode when the system is singular (relative
// smallest singular value below 1e-12), std::invalid_argument for bad input.
BSplineCurve seed_section_curve(const Eigen::MatrixXd& P, const Eigen::VectorXd& F);

struct SectionCurveOptions {
  int degree = 2;                  // the seed's quadratic; 3 for C2 sections
  bool least_squares = false;      // false: interpolate every point
  int num_ctrl = 0;                // least squares: control points (0: automatic)
  double smoothing = 0;            // least squares: smoothing weight (approximate_curve)
  double tolerance = 0;            // least squares: max deviation to reach
  double parameter_exponent = 1.0; // chord length (the digest's F_p), 0.5 centripetal
};

struct SectionCurve {
  BSplineCurve curve;       // periodic, C^{degree-1} at the seam
  Eigen::VectorXd u;        // #P parameters of the points
  double max_deviation = 0; // max |C(u_i) - P_i| (round-off when interpolating)
  bool met_tolerance = true;
};

// Closed curve through (or near) the distinct points P (#P by dim, P_0 not repeated), avoiding
// the singular mode: interpolation uses periodic knots at the sites (odd degree) or midpoints
// (even degree), least squares follows approximate_curve. Throws std::invalid_argument for bad
// input (degree < 1, degree >= #P, ...).
SectionCurve closed_section_curve(const Eigen::MatrixXd& P,
                                  const SectionCurveOptions& options = {});

} // namespace interlin
