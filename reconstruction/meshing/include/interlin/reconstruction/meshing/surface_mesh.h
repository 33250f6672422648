#pragma once
// Triangle mesh of a B-spline surface, optionally capped into a watertight solid.

#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>
#include <vector>

namespace interlin {

struct SurfaceMeshOptions {
  int nu = 400;                   // samples around u; for closed_u surfaces the seam is shared
  int nv = 120;                   // uniform samples along v (span), merged with required_v
  std::vector<double> required_v; // v values that must be vertex rows exactly (input sections)
  bool cap = false;               // close both v-boundary loops (closed_u only) -> solid
};

// Samples the surface on a u x v grid and triangulates it.
//
// u samples (nu of them): distributed by a mix of arc length and turning angle of the u-curves
//   S(., v) on five v rows (averaged), plus a 1% share uniform in u, so that thin
//   high-curvature edges (blade leading/trailing edges) get enough vertices. Closed_u: u(0) = u0
//   and the samples lie in [u0, u1) (the seam is one column of vertices); otherwise u(0) = u0 and
//   u(nu-1) = u1. Deterministic.
// v samples: nv uniform values in [v0, v1] merged with required_v; a uniform value closer than a
//   quarter spacing to a required value is dropped, so that the rows at required_v are evaluated
//   exactly at those parameters.
// Quads are split along their shorter diagonal. With cap, each v-boundary loop is triangulated by
// triangulate_loop (constrained Delaunay in the loop's best-fit plane), sharing the loop vertices.
// Orientation: consistent; faces point along S_u x S_v for open-u surfaces; closed_u meshes are
// oriented outward (positive signed volume, counting the caps, or for an uncapped mesh the
// virtual fans from each boundary loop's centroid).
//
// Inputs:
//   s  surface (check_surface-valid, converted with to_piecewise)
//   o  options; std::invalid_argument for nu < 3, nv < 2, cap without closed_u, or a
//      required_v value that is not finite or lies outside the v domain
// Outputs:
//   V          #V by 3, #V = nu * #v: row i + nu * k is S(u_samples(i), v_samples(k)) (u fastest,
//              the layout of evaluate_grid)
//   F          #F by 3 vertex indices: 2 * (nu or nu-1) * (#v - 1) grid triangles, then with cap
//              (nu - 2) triangles for the loop at v0 and (nu - 2) for the loop at v1
//   u_samples  optional, nu increasing u values
//   v_samples  optional, #v increasing v values (#v >= nv unless required values replace
//              uniform ones)
void surface_mesh(const PiecewiseSurface& s, const SurfaceMeshOptions& o, Eigen::MatrixXd& V,
                  Eigen::MatrixXi& F, Eigen::VectorXd* u_samples = nullptr,
                  Eigen::VectorXd* v_samples = nullptr);

// Triangulates one closed polygon in 3D (a simple loop, possibly non-planar and non-convex) by
// ear clipping in its best-fit plane (Newell normal through the centroid), clipping the ear with
// the largest smallest angle first, then Lawson edge flips to the constrained Delaunay
// triangulation of the projected polygon (the largest smallest angle of all triangulations on
// the loop's vertices, in that plane). When no valid ear exists (a projection that self-overlaps,
// degenerate loops) the most convex vertex is clipped and only flips that keep both triangles
// counter-clockwise in the plane are taken, so the result is always a topological disk on the
// loop vertices.
// Inputs:  P  #P by 3 loop vertices in order (#P >= 3, last not repeating the first)
// Outputs: T  (#P - 2) by 3 row indices into P; each triangle (a, b, c) runs in the loop's
//             direction, so T's boundary is the loop traversed as given.
Eigen::MatrixXi triangulate_loop(const Eigen::MatrixXd& P);

} // namespace interlin
