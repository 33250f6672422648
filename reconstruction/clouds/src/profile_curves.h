#pragma once
// Steps shared by the section fit (fit_sliced_scan) and its spanwise smoothing
// (smooth_spanwise): knot weights where a profile turns, and foot-point parameters.

#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>

namespace interlin::detail {

// Degrees of freedom per control point in Mallows' C_p: two coordinates, doubled because the feet
// let the curve slide along the points as well (measured: 1, 2, 3, 4 and 6 on the section family
// and the Rotor 37 slices, docs/benchmarks.md; 4 was best on both, 3 and 6 within 4 %).
constexpr Eigen::Index kDofPerControl = 4;
// At least this many points per control point: randomly spaced points leave knot spans nearly
// empty when there are more control points, and the curve oscillates between the points.
constexpr Eigen::Index kPointsPerControl = 4;
// Knots of every fitted section on multiples of 2^-16 of the parameter period: the sections'
// knot union then has no spans shorter than that (the loft snaps its parameters at 1e-5 for the
// same reason: spans well inside the range where the explicit basis is exact to round-off), and
// moving a knot by less than 1e-5 of the period changes nothing measurable in a least-squares
// fit of at most #points / 4 spans.
constexpr double kKnotGrid = 1.0 / 65536;

// Knot weights w (one per parameter interval of u, #u - 1) capped so that every knot span of a
// fit with `control` control points holds kPointsPerSpan points and is at least 4 grid steps
// long: interval i, holding m(i) points, carries at most m(i) / (kPointsPerSpan control) of the
// total weight and at most its length / (4 kKnotGrid control).
Eigen::VectorXd capped_knot_weights(const Eigen::VectorXd& w, const Eigen::VectorXd& m,
                                    const Eigen::VectorXd& u, Eigen::Index control);

// Interval weights for the knots at parameters t (#t - 1 intervals) of curve c: each interval's
// share of the arc length plus kTurningShare times its share of the turning angle, so that knots
// crowd where the profile turns (the noses, which evenly spaced knots fit only with many control
// points everywhere, letting the noise through).
Eigen::VectorXd turning_weights(const BSplineCurve& c, const Eigen::VectorXd& t);

// Closest-point parameters (the feet of parameter correction, Hoschek 1988): from the nearer of u
// and the nearest of 8 samples per knot span (a thin profile's other side is often nearer to a
// neighbour's foot), Newton steps on (C(u) - P) . C'(u) = 0, each kept only where it brings the
// point closer to the curve (else that point's next step is at most half as long), until every
// step is below 1e-10 of the period or after 20 steps; wrapped into the curve's periodic domain.
// P #P by 3, u #P.
Eigen::VectorXd closest_parameters(const BSplineCurve& c, const Eigen::MatrixXd& P,
                                   Eigen::VectorXd u);

} // namespace interlin::detail
