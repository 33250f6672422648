#pragma once
// Exact point-to-surface distance: the foot of the perpendicular from each point to a B-spline
// surface, by Newton's method on |S(u,v) - p|^2 started from the nearest samples of a dense grid
// (nearest neighbours by FLANN).

#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>

namespace interlin {

// Inputs:
//   S          the surface (closed_u surfaces wrap in u)
//   P          #P by 3 query points
//   samples_u, samples_v  start grid; a few grid cells per feature of the surface is enough,
//              Newton converges quadratically from there
// Outputs (#P each): parameters u, v of the closest point, its position foot (#P by 3) and the
//   distance |S(u,v) - p|. The foot is a local minimum to round-off: the residual is orthogonal
//   to S_u and S_v (or lies on a v boundary).
struct SurfaceProjection {
  Eigen::VectorXd u, v, distance;
  Eigen::MatrixXd foot;
};

SurfaceProjection project_to_surface(const PiecewiseSurface& S, const Eigen::MatrixXd& P,
                                     int samples_u = 512, int samples_v = 128);

} // namespace interlin
