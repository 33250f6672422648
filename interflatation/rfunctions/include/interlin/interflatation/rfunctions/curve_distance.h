#pragma once
// Hybrid representation (seed 003 §3.3, formulas (3)-(6)): a region bounded by a closed curve
// given by points or Bezier pieces becomes an implicit function, the signed Euclidean distance to
// the curve's polyline (+ inside by ray parity, - outside), usable as an R-operation operand.

#include "interlin/interflatation/rfunctions/expression.h"

#include <Eigen/Core>
#include <vector>

namespace interlin::rf {

// Inputs:
//   u, v      the plane coordinates (expressions, e.g. x and y, or transformed coordinates)
//   vertices  #V >= 3 vertices of a closed polyline (the closing segment is implicit); consecutive
//             repeated vertices are dropped
// Output: f(u, v) = sign * dist((u, v), polyline), seed 003 (3): dist by (5)-(6) (nearest point
//   on the nearest segment), sign +1 where a ray along +u crosses the polyline an odd number of
//   times (half-open rule: a segment counts when min(y0,y1) < v <= max(y0,y1)). Its gradient is the
//   unit vector away from the nearest point, pointing inward; second derivatives are taken as 0.
// Throws std::invalid_argument for fewer than 3 distinct vertices or non-finite coordinates.
Expr polygon_region(const Expr& u, const Expr& v, const std::vector<Eigen::Vector2d>& vertices);

// Points of a chain of Bezier curves (seed 003 §3.4, the NACA 0011 profile): each branch (control
// points, degree = #branch - 1) is sampled at `segments` + 1 uniform parameters; the samples are
// concatenated in order (a point repeating the previous one is dropped), ready for polygon_region.
// Throws std::invalid_argument for a branch with fewer than 2 control points or segments < 1.
std::vector<Eigen::Vector2d>
sample_bezier_chain(const std::vector<std::vector<Eigen::Vector2d>>& branches, int segments);

} // namespace interlin::rf
