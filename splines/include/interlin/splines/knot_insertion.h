#pragma once
// Knot insertion: exact changes of basis that keep the curve point for point.

#include "interlin/splines/bspline_curve.h"
#include <vector>

namespace interlin {

// Inserts the sorted knots X (values inside the domain, repeats allowed) into a non-periodic
// curve (Piegl & Tiller, algorithm A5.4, O(#ctrl + #X * degree)).
BSplineCurve refine_knots(const BSplineCurve& c, const Eigen::VectorXd& X);

// The periodic curve c restricted to the window [a, a + period] as a clamped (open) curve:
// same points, end knots of multiplicity degree+1. Used before export (IGES) and knot merging.
BSplineCurve periodic_to_clamped(const BSplineCurve& c, double a);

// Smallest knot vector containing every input knot vector: each distinct value (compared
// exactly) with its largest multiplicity.
Eigen::VectorXd knot_union(const std::vector<Eigen::VectorXd>& knot_vectors);

// Refines clamped curves of equal degree and domain to their knot union, so that they share one
// knot vector (Piegl & Tiller §10.3, "compatible curves"); every curve is unchanged point for
// point. Throws std::invalid_argument for periodic curves or differing degree/domain.
std::vector<BSplineCurve> make_compatible(const std::vector<BSplineCurve>& curves);

// The piece [a, b] of a clamped curve as a clamped curve on [0, 1] (the same points, knots mapped
// affinely): a < b in the domain, or for a closed curve (first and last control points equal)
// a > b, the piece through the end of the domain and on from its start (joined there by a knot of
// multiplicity degree). Knots a and b are inserted up to multiplicity degree (refine_knots).
// Throws std::invalid_argument for a == b or ends outside the domain.
BSplineCurve curve_piece(const BSplineCurve& c, double a, double b);

} // namespace interlin
