#pragma once
// The foot of the perpendicular from a point to a surface patch: Newton's method on
// |S(u,v) - p|^2 / 2 from a given start, with the parameter domain as box constraints. The local
// step every closest-point search ends with (global searches choose the starts).

#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>

namespace interlin {

// Result of surface_foot.
//   u, v       parameters of the foot
//   distance   |S(u,v) - p|
//   jet        S and its derivatives up to order 2 at the foot (jet.S is the foot)
//   clamped_u, clamped_v  the foot lies on that boundary of the domain (an open-u surface's u
//              bounds, the v bounds), where the residual need not be normal to the surface
//   iterations Newton steps taken
struct SurfaceFoot {
  double u = 0, v = 0, distance = 0;
  SurfaceJet jet;
  bool clamped_u = false, clamped_v = false;
  int iterations = 0;
};

// Inputs:
//   S       the surface; closed_u surfaces wrap in u, otherwise u is kept in its domain; v is
//           always kept in its domain
//   p       the point
//   u, v    the start (any values; wrapped or clamped into the domain)
//   max_iterations  Newton steps at most
// Method: Newton on f = |S - p|^2 / 2 with the exact Hessian (S_u.S_u + S_uu.r, ...) where it is
// positive definite, Gauss-Newton otherwise; a coordinate on its bound whose step points out of
// the domain is held (active set) and the other one takes its 1-D Newton step; halving line
// search on f. Stops when the foot moves less than 1e-15 x (|p| + 1) or f stops decreasing.
// Output: a local minimum of the distance (the nearest foot when the start is in its basin).
SurfaceFoot surface_foot(const PiecewiseSurface& S, const Eigen::Vector3d& p, double u, double v,
                         int max_iterations = 50);

} // namespace interlin
