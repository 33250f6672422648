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

// The fraction of k-nearest-neighbour pairs lying on one sheet (edge within 30 degrees of both
// tangent planes) whose normals point to opposite sides (n_i . n_j < 0): about 0 for
// consistently oriented normals, near 0.5 for random signs.
double orientation_disagreement(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, int k);

} // namespace interlin
