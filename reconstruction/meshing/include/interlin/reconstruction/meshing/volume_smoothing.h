#pragma once
// Seed 003's interior-node smoothing of solid meshes (digest §6.4, functionals (13)-(15) in 3D):
// every element corner j contributes exp(-t alpha_j), alpha_j the triple product of the three
// element edges leaving corner j (6 x the corner tetrahedron's volume: > 0 for a convex corner,
// <= 0 for a flat or inverted one); the mesh functional is the sum over all corners of all
// elements, minimised node by node (the seed's local algorithm) with the boundary fixed.

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace interlin {

struct VolumeSmoothingOptions {
  int sweeps = 8;        // seed 003: 8-10 sweeps are enough in practice
  double t = 0;          // exponent scale; 0: t = 1 / mean(alpha) over the mesh (digest [A])
  int newton_steps = 10; // Newton iterations per node and sweep (the per-node functional is
                         // convex: every alpha_j is affine in one node's position)
  int threads = 0;       // 0: all cores
  // A node move may not make a corner whose scaled Jacobian is below `keep` poorer, nor bring
  // another below it (0: only folding a corner is refused). exp(-t alpha) hardly tells a small
  // element's flat corner from a sound one, so without it the backtracking walks such corners
  // to alpha ~ 0 (docs/benchmarks.md, "Flat corners").
  double keep = 0;
};

struct VolumeSmoothingReport {
  double t = 0;               // the exponent scale used
  std::vector<double> energy; // functional (15) divided by the corner count: before, after each
                              // sweep (1 / e = 0.37 when every corner has alpha = mean alpha)
  std::vector<long> inverted; // elements with a corner alpha <= 0: before, after each sweep
  long moves = 0;             // node updates that lowered the node's functional
};

// The corners of element type `corners_per_element` (4 tetrahedron, 8 hexahedron): for each local
// corner j the three local vertices (a, b, c) with alpha_j = ((p_a - p_j) x (p_b - p_j)) . (p_c -
// p_j), positive for the reference element (digest §6.4 tables: tetrahedra with
// (p1 - p0) x (p2 - p0) . (p3 - p0) > 0; hexahedra in VTK order).
// Output: corners_per_element by 3.
Eigen::MatrixXi corner_table(int corners_per_element);

// alpha_j of every corner of every element. Inputs: V #V by 3, C #C by 4 or #C by 8, threads
// (0: all cores). Output: #C by 4 or #C by 8.
Eigen::MatrixXd corner_alphas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, int threads = 0);

// Minimises sum_e sum_j exp(-t alpha_j(e)) over the free nodes, one node at a time (Gauss-Seidel
// sweeps; nodes that share no element move at once, in colour classes, on `threads` threads;
// deterministic). Per node, Newton's method on its convex local functional (the sum over the
// corners of its elements) with backtracking, in place of the seed code's numerically
// differentiated conjugate gradients: the same minimiser, found exactly and cheaper.
// Inputs:
//   C      #C by 4 tetrahedra or #C by 8 hexahedra (orientation as in corner_table)
//   fixed  #V flags: nodes that stay (the boundary); empty: none
//   o      options (std::invalid_argument for sweeps < 0 or t < 0)
// In/out:  V #V by 3
VolumeSmoothingReport smooth_volume(Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                                    const std::vector<char>& fixed,
                                    const VolumeSmoothingOptions& o = {});

// A surface that boundary nodes may slide on, evaluated in batches: unit normals at the rows of P
// (#P by 3; a zero row where there is none), and P's rows moved onto the surface (per row whether
// that succeeded).
struct SlidingSurface {
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd& P)> normals;
  std::function<std::vector<char>(Eigen::MatrixXd& P)> project;
};

// Untangling at the boundary: the fixed nodes of elements that are inverted or nearly flat (a
// corner alpha <= flat x mean alpha) minimise the same local functional as smooth_volume over the
// surface: Newton steps in the tangent plane, each trial point projected onto the surface, accepted
// when the node's functional decreases. Run between interior sweeps: a boundary facet folded over
// by the projection cannot be repaired by the interior nodes alone.
// Inputs:  C, fixed (#V, the nodes on the surface), surface, t (> 0, as in smooth_volume),
//          flat (>= 0), threads for the corners (0: all cores; the result does not depend on it)
// In/out:  V
// Output:  the number of boundary nodes moved
inline constexpr double kSlideFlat = 0.05;
long slide_boundary_nodes(Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                          const std::vector<char>& fixed, const SlidingSurface& surface, double t,
                          double flat = kSlideFlat, int threads = 0);

// Seed 003's 2-D functional (13) on a surface mesh lying on `surface`: every facet corner p with
// neighbours next, prev contributes exp(-t alpha), alpha = ((next - p) x (prev - p)) . n(p) (twice
// the corner triangle's area in the tangent plane at p, negative where the facet is folded over),
// t = 1 / mean alpha. The nodes of facets with a corner alpha <= flat x mean |alpha| minimise
// their local sum over the surface (tangential Newton steps, projected, accepted on decrease),
// for `rounds` rounds or until no such facet is left. Used after projecting a boundary onto
// F = 0: normal projection folds facets over at concave creases.
// Inputs:  B #B by 3 or 4 facets (counter-clockwise seen from outside) into V, surface
// In/out:  V (only nodes of B move)
// Output:  facets still with a corner alpha <= 0 (folded) at the end
long untangle_surface(Eigen::MatrixXd& V, const Eigen::MatrixXi& B, const SlidingSurface& surface,
                      double flat = 0.05, int rounds = 10);

} // namespace interlin
