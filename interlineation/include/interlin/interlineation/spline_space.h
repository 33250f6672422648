#pragma once
// A function that lies in a spline space, written on that space's B-spline basis: collocation at
// the Greville abscissae (which always satisfy the Schoenberg-Whitney condition), so the result
// is the function itself whenever it belongs to the space. Used to put blending functions and
// curves of lower degree or smoothness onto the basis of a Gordon surface (degree elevation).

#include "interlin/splines/bspline_curve.h"

#include <functional>

namespace interlin {

// Greville abscissae xi_i = (t_{i+1} + ... + t_{i+p}) / p, i = 0..#knots-p-2.
//   knots  clamped knot vector (check_knots-valid), degree p >= 1
Eigen::VectorXd greville_abscissae(const Eigen::VectorXd& knots, int degree);

// Inputs:
//   f       values at the given parameters: f(s) is #s by dim
//   knots   clamped knot vector of the target space, degree >= 1
// Output: the clamped curve C of that space with C(xi_i) = f(xi_i) at every Greville abscissa.
// Greville sites always satisfy Schoenberg-Whitney, so this cannot fail for valid knot vectors.
BSplineCurve interpolate_in_space(const std::function<Eigen::MatrixXd(const Eigen::VectorXd&)>& f,
                                  const Eigen::VectorXd& knots, int degree);

// Interpolation in a given spline space: the clamped curve C on `knots` (degree >= 1) with
// C(sites(i)) = P.row(i). #sites = #knots - degree - 1, sites increasing and satisfying the
// Schoenberg-Whitney condition for the knots (else std::runtime_error "singular"); also refused
// (std::runtime_error) when the control points exceed the data's spread 1000-fold, the sign of
// a site/knot pattern that is regular but oscillates wildly between the sites.
BSplineCurve interpolate_in_space(const Eigen::MatrixXd& P, const Eigen::VectorXd& sites,
                                  const Eigen::VectorXd& knots, int degree);

// The same clamped curve as a spline of degree `degree` >= c.degree: end knots of multiplicity
// degree+1, every interior knot's multiplicity raised by degree - c.degree (so the continuity at
// the knot is unchanged). Exact up to round-off of one small collocation solve.
BSplineCurve elevate_degree(const BSplineCurve& c, int degree);

} // namespace interlin
