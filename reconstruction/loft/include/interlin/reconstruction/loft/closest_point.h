#pragma once
// Exact point-to-surface distance: the foot of the perpendicular from each point to a surface,
// by Newton's method on |S(u,v) - p|^2 started from the nearest samples of a dense grid (nearest
// neighbours by FLANN), or from given parameters.

#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>
#include <functional>

namespace interlin {

// Any parametric surface, for the projections below (e.g. another library's B-spline surface,
// to measure it with the same code as ours).
//   domain       (u0, u1, v0, v1)
//   closed_u     u wraps around (the boundaries u0 and u1 coincide)
//   point        S(u, v)
//   derivatives  S and its first and second partial derivatives at (u, v)
struct ParametricSurface {
  Eigen::Vector4d domain;
  bool closed_u = false;
  std::function<Eigen::Vector3d(double u, double v)> point;
  std::function<SurfaceJet(double u, double v)> derivatives;
};

// The B-spline surface in explicit form as a ParametricSurface (S must outlive the result).
ParametricSurface parametric(const PiecewiseSurface& S);

// Inputs:
//   S          the surface (closed_u surfaces wrap in u)
//   P          #P by 3 query points
//   samples_u, samples_v  start grid; a few grid cells per feature of the surface is enough,
//              Newton converges quadratically from there
//   starts     Newton runs per point, from its nearest grid samples; the lowest foot wins. More
//              starts guard against the wrong sheet of a thin body (blade edges) when the point
//              is farther from the surface than the body is thick
// Outputs (#P each): parameters u, v of the closest point, its position foot (#P by 3) and the
//   distance |S(u,v) - p|. The foot is a local minimum to round-off: the residual is orthogonal
//   to S_u and S_v (or lies on a v boundary).
struct SurfaceProjection {
  Eigen::VectorXd u, v, distance;
  Eigen::MatrixXd foot;
};

SurfaceProjection project_to_surface(const PiecewiseSurface& S, const Eigen::MatrixXd& P,
                                     int samples_u = 512, int samples_v = 128, int starts = 4);
SurfaceProjection project_to_surface(const ParametricSurface& S, const Eigen::MatrixXd& P,
                                     int samples_u = 512, int samples_v = 128, int starts = 4);

// The same Newton iteration from given start parameters (u0, v0: #P each), one start per point:
// the foot of the local minimum that descent from S(u0, v0) reaches. For points whose
// parameters are known approximately, e.g. a withheld section at its corresponding (u, v)
// (leave-one-out, span_model.h); no start grid, so much cheaper than project_to_surface.
SurfaceProjection project_from(const PiecewiseSurface& S, const Eigen::MatrixXd& P,
                               const Eigen::VectorXd& u0, const Eigen::VectorXd& v0);
SurfaceProjection project_from(const ParametricSurface& S, const Eigen::MatrixXd& P,
                               const Eigen::VectorXd& u0, const Eigen::VectorXd& v0);

} // namespace interlin
