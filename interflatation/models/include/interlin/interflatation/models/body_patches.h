#pragma once
// The closed boundary of a body lofted from sections: the loft surface S(u, v) (closed around in
// u, clamped along the span v) and two ruled caps that close its end loops. Each cap joins the
// end loop's two sides between its edge points u_a (leading) and u_b (trailing):
//   C(s, t) = (1 - t) S(u_a + s (u_b - u_a), v_e) + t S(u_a - s (1 - (u_b - u_a)), v_e),
// s, t in [0, 1]: side one runs from u_a up to u_b, side two from u_a down (through the seam) to
// u_b, and the rulings go across the profile, like the flat fills of `interlin loft --cap`. The
// boundary of C is exactly the end loop S(., v_e), so side and caps form a closed surface.
// Signed distances to it (positive inside) by Newton from given starts (surface_foot).

#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>
#include <array>

namespace interlin {

// A start for the foot search: patch 0 (side), 1 (cap at v0) or 2 (cap at v1) and parameters.
struct PatchSeed {
  int patch = 0;
  double u = 0, v = 0;
};

// The three patches in explicit form with their outward orientations.
//   patches      side (degree p x q, closed_u), cap at v0, cap at v1 (degree p x 1 on [0,1]^2)
//   orientation  +1 or -1 per patch: sign * (P_u x P_v) points out of the body
//   edge_u       per end (v0, v1): (u_a, u_b), the cap's edge parameters, 0 <= u_a < u_b < 1
//   cap_normal   per end: the cap's mean outward unit normal
//   fold_zone    per end: where the side folds back next to the end loop (a span spline that
//                overshoots between close sections and returns, S_v against the span chord:
//                Rotor 37's tip by 5e-4 cm), twice the largest distance of the fold's turning
//                line from the loop; 0 without a fold. Side feet that close to an end loop count
//                as feet on the loop (edge feet) for the sign.
//   fold_v       per end: the fold region is v <= fold_v[0], v >= fold_v[1] (outside the
//                domain without a fold)
// Outward is decided by the loop's winding around the span direction (end loop minus start
// loop, means over u) for the side, by that direction for the caps: S_v at an end can point
// backwards (a span spline that overshoots between close sections, Rotor 37's tip).
struct BodyPatches {
  std::array<PiecewiseSurface, 3> patches;
  std::array<double, 3> orientation{1, 1, 1};
  std::array<Eigen::Vector2d, 2> edge_u;
  std::array<Eigen::Vector3d, 2> cap_normal;
  std::array<double, 2> fold_zone{0, 0}, fold_v{0, 0};
};

// Inputs: side (clamped, closed_u, check_surface-valid, u on [0,1]); edge_u per end with
// 0 <= u_a < u_b < 1 (std::invalid_argument otherwise).
BodyPatches body_patches(const BSplineSurface& side, const std::array<Eigen::Vector2d, 2>& edge_u);

// The signed distance from p to the boundary (positive inside) through the nearest of the feet
// found from the starts.
//   distance   signed distance (0 on the boundary)
//   gradient   its gradient: the unit vector from the foot towards p, times -1 outside; within
//              1e-7 x (|p| + 1) of the boundary the inward (pseudo-)normal, its limit
//   foot, seed the foot and where it lies (patch, u, v)
// The sign is that of the pseudo-normal at the foot: the patch's outward normal inside a patch,
// the sum of the side's and the cap's unit normals on an end loop (the convex edge between side
// and cap; the cap's mean normal where its own vanishes, at the edge points u_a, u_b) and in its
// fold zone. The side's normal uses the span chord for S_v (unchanged where the side is regular,
// the unfolded sheet's normal in a fold). Found == false when no start converged to a finite foot.
struct BodyDistance {
  double distance = 0;
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero(), foot = Eigen::Vector3d::Zero();
  PatchSeed seed;
  bool found = false;
};

BodyDistance body_distance(const BodyPatches& b, const Eigen::Vector3d& p, const PatchSeed* seeds,
                           int count, int max_iterations = 50);

// A point of a patch.
Eigen::Vector3d evaluate(const BodyPatches& b, const PatchSeed& at);

} // namespace interlin
