#pragma once
// Consistent orientation of unoriented normals (signs), pointing out of the body.

#include <Eigen/Core>

namespace interlin {

struct OrientationInfo {
  Eigen::Index components = 0; // connected parts of the neighbour graph, each oriented alone
  Eigen::Index flipped = 0;    // normals whose sign was changed
};

// Hoppe, DeRose, Duchamp, McDonald, Stuetzle, "Surface reconstruction from unorganized points",
// SIGGRAPH 1992, §3.3: a minimum spanning tree of the neighbour graph, traversed from a root
// whose orientation is known, flips each normal to agree with its parent. The graph joins every
// point to its k nearest neighbours (FLANN); an edge ij costs
//   1 - |n_i . n_j| + (|n_i . e| + |n_j . e|) / 2,   e = (p_j - p_i) / |p_j - p_i|,
// Hoppe's cost plus a term for leaving the tangent planes: neighbours across a thin wall (the
// two sides of a blade near its edges) have parallel normals, which Hoppe's cost alone treats as
// the cheapest edges, but they lie along the normal, so the tree avoids them. Each connected
// part is rooted at its extreme point along +-x, +-y or +-z whose normal is most nearly parallel
// to that axis; the outward normal of a closed surface at its extreme point is that axis.
// Inputs:  P #P by 3, N #P by 3 unit normals (any signs), k >= 1 (clamped to #P - 1)
// Outputs: N with signs made consistent; info (optional)
void orient_normals(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N, int k,
                    OrientationInfo* info = nullptr);

// Repairs an orientation that propagation got wrong on whole regions (the MST crosses a thin
// wall's noisy rim and flips one side of a blade). The cloud is cut into patches: neighbours
// whose normals agree within 30 degrees along an edge within 30 degrees (+ 2 noise sigmas) of
// both tangent planes, inside one cell of a grid 8 cells to the bounding-box diagonal, points on
// sharp rims (normals not all within 30 degrees of their 8 nearest, up to sign) left out. The
// signs of the up to 256 largest (each >= 0.2 % of the points) minimise, by steepest descent
// over single flips, sum min(|w(q)|, 1) over probes q = p_i + d n_i outside up to 40 points of
// each (d = 2 point spacings + 3 x the estimated noise): the generalized winding number w of the
// oriented cloud (Barill et al. 2018) is 0 outside a closed surface with outward normals, while
// a flipped side makes it about +-1 or 1/2 there. Before the descent, a voxel flood fill reads
// the outside from the points' positions alone (exterior_side.h: voxels of 1.5 point spacings,
// those within one voxel of a point the shell, the free voxels reached from the border outside):
// a point votes +1 when the first free voxel along +n is outside and along -n inside, -1 for the
// reverse; a patch where at least 20 % of the points vote and 90 % of the votes agree keeps the
// votes' sign (walls thinner than about 5 spacings, and clouds with holes, give no votes). The
// other points take the sign change of the nearest decided point along the neighbour graph; the
// global sign makes the enclosed volume (divergence theorem) positive. The result is kept only
// if its mean min(|w|, 1) at 4000 such outside probes of the whole cloud is lower than the
// input's (never worse by that measure), or if the votes turned a patch (a narrow slot's sides
// make that measure prefer a wrong side: docs/benchmarks.md "Orientation by a flood fill").
// thin_walls (prepare_cloud's default): the points outside the decided patches (rims, thin
// walls' edges, sharp edges) are instead oriented again from all decided patches at once by
// Hoppe's propagation (the minimum spanning tree grown from every decided point), so each
// follows its own side's patch along the sheet. Then, after the check (whether the repair was
// kept or not), each such point is also turned when (1) its 32 nearest points within 45 degrees
// of its normal line and more than 4 noise sigmas along it lie in front of it on the whole (the
// other side of a thin wall is behind a point), (2) the decided patches' winding number is larger
// in front of it than behind it (probes at 0.25, 0.5, 1 point spacings), and (3) it lies on a
// wall, not by a narrow gap or slot, whose facing sides look the same to (1): among its 16
// nearest points, pairs with antiparallel normals each more than half a point spacing behind
// the other outnumber the pairs each in front of the other. The tests are repeated on the
// normals each pass leaves until a pass turns none (at most 10 passes). docs/benchmarks.md
// "Thin-wall sides" and "Thin walls by default".
// Inputs:  P #P by 3, N #P by 3 unit normals oriented by orient_normals, k neighbours (>= 8 used)
// Outputs: N with the chosen normals negated; returns how many normals were negated.
Eigen::Index orient_by_winding_number(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N, int k,
                                      bool thin_walls = true);

// Signs for sheet normals S (estimate_sheet_normals) from oriented PCA normals O of the same
// points. Where S and O agree within 20 degrees (reliable: one sheet, where the PCA normal is
// right and oriented), O's sign is right; where they do not (edges, gaps, thin walls), O's sign
// may belong to the other sheet. The sheet graph joins mutual 16-nearest neighbours that lie on
// each other's sheet plane (detail::sheet_tolerance) with normals within 15 degrees; each of its
// connected parts is made consistent by breadth-first propagation. Each point then takes the
// sign of the reliable points' votes (+1 where the propagated normal agrees with O, -1 where not)
// averaged over itself and its graph neighbours 30 times (the votes within about 30 hops along
// its sheet, nearest weighted most): a local vote, as a part's edges can leak onto another sheet
// and one vote per part then turns whole regions (the noisy blade's edges). Points without a
// vote keep O's sign. docs/benchmarks.md "Normals that keep to one sheet".
// Inputs: P #P by 3, S #P by 3 unit normals (any signs), O #P by 3 unit normals oriented outward
//         (orient_normals, orient_by_winding_number), sigma >= 0 the noise, threads (0: all)
// Output: S with signs, #P by 3.
// See also: estimate_sheet_normals (cloud_filters.h)
Eigen::MatrixX3d sign_sheet_normals(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& S,
                                    const Eigen::MatrixX3d& O, double sigma, int threads = 0);

// The fraction of k-nearest-neighbour pairs lying on one sheet (edge within 30 degrees of both
// tangent planes) whose normals point to opposite sides (n_i . n_j < 0): about 0 for
// consistently oriented normals, near 0.5 for random signs.
double orientation_disagreement(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, int k);

} // namespace interlin
