#pragma once
// Local rebuilding of a triangle surface mesh by edge flips (seed 003 §5.4: the diagonal swap of
// two triangles that share an edge, to increase the smallest angle).

#include <Eigen/Core>

namespace interlin {

struct EdgeFlipOptions {
  // Only edges whose two triangles bend by at most this angle are flipped: flipping across a
  // crease would cut the corner of the body.
  double max_dihedral_deg = 20;
  int max_sweeps = 40; // seed 003 code: sweeps until no flip, at most 40
};

// Flips edges while that increases the smaller of the two triangles' smallest angles (by more
// than 1e-9 rad). A flip of edge (a, b) with opposite vertices c, d is taken only if (seed 003
// code's validity test) the new diagonal c-d crosses a-b strictly inside both segments (parameters
// in (0.01, 0.99)) seen along the mean normal, neither new triangle folds over (its normal agrees
// with the mean normal), c-d is not already an edge, and the dihedral limit holds. Vertices do not
// move; the topology stays a manifold with the same Euler characteristic and orientation.
// Inputs:  V #V by 3; o options
// In/out:  F #F by 3 (closed or with boundary; boundary edges are never flipped); throws
//          std::invalid_argument for an edge with more than two triangles or inconsistent
//          orientation across an edge
// Output:  number of flips
long flip_edges(const Eigen::MatrixXd& V, Eigen::MatrixXi& F, const EdgeFlipOptions& o = {});

} // namespace interlin
