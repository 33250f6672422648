#pragma once
// The boundary of a plane region G, seen as the operators of Theorem 4 need it: the crossings of
// axis-parallel lines with dG. Three kinds of boundary: an implicit curve g = 0 (G: g > 0), a
// polygon, and a closed B-spline section curve (splines/).

#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <vector>

namespace interlin {

// A region G inside `box`.
//   chords(axis, c)  the intervals of the line {p(axis) = c} that lie in G, in the other
//                    coordinate: increasing, disjoint pairs (lo_0, hi_0, lo_1, hi_1, ...); their
//                    ends are on dG (or on the box)
struct PlaneBoundary {
  Eigen::AlignedBox2d box;
  std::function<std::vector<double>(int axis, double c)> chords;
};

// G = {g > 0} in `box`. Chords are the runs of g > 0 among `samples` equally spaced points of
// the line, their ends refined by bisection to round-off; a run shorter than the sample spacing
// can be missed (choose samples accordingly). Throws std::invalid_argument for samples < 2 or an
// empty box.
PlaneBoundary implicit_boundary(std::function<double(const Eigen::Vector2d&)> g,
                                const Eigen::AlignedBox2d& box, int samples = 512);

// G = the inside of the closed polygon V (#V >= 3 by 2, the closing edge implicit; any
// orientation, no self-crossings). Chords are exact (edge intersections; a crossing counts
// when min(v0, v1) < c <= max(v0, v1) of the edge's ends). Throws std::invalid_argument for fewer
// than 3 vertices or non-finite coordinates.
PlaneBoundary polygon_boundary(const Eigen::MatrixX2d& V);

// G = the inside of a closed planar B-spline curve (2-D control points, e.g. a blade section of
// splines/closed_curve). Crossings of the curve's coordinate with c: sign changes among
// `samples_per_span` points per knot span, refined by bisection in the parameter.
// Throws std::invalid_argument for a curve that is not 2-D or not closed (ends apart by more
// than 1e-9 x its box diagonal).
PlaneBoundary curve_boundary(const BSplineCurve& curve, int samples_per_span = 16);

} // namespace interlin
