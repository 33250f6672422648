#pragma once
// Seed 003's boundary-node smoothing (digest §5.3, functional (12)): every vertex slides over the
// implicit surface to minimise
//   E_i = kappa * sum_{k adjacent to i} |V_k - V_i|^2 + (1 - kappa) * sum_{faces q at i} |C_q -
//   proj(C_q)|^2
// (C_q the centroid of face q, proj its projection onto F = 0): the second term measures how far
// the flat triangles stand off the surface and pulls vertices onto creases, the first keeps a
// minimum. Vertices stay on F = 0.

#include "interlin/interflatation/implicit_function.h"

#include <Eigen/Core>
#include <vector>

namespace interlin {

struct SurfaceSmoothingOptions {
  int iterations = 4;    // sweeps; seed 003: >= 4 captures the features, > 8 changes little
  double kappa = 0.001;  // seed 003 code's value
  bool laplacian = true; // a Laplacian pass with re-projection before the sweeps (seed code)
  // Angle floor (degrees) of the descent: no move takes a face from above it to below it or
  // shrinks its star's smallest angle below it (0: the seed's rule, which refuses only turned-over
  // faces and leaves slivers on creases; 5 costs the fit at most 5 % rms on the shipped models).
  double min_angle_deg = 5;
  int threads = 0; // projections; 0: all cores
};

struct SurfaceSmoothingReport {
  // Sum over the faces of |C_q - proj(C_q)|^2 before the first sweep and after each sweep.
  std::vector<double> fit;
  long moves = 0; // accepted coordinate-descent moves
};

// Coordinate descent per vertex as in the seed code: towards each neighbour and each opposite
// edge's midpoint in turn, trial V_i + s (p - V_i) projected onto F = 0 (gradient walk: steps of
// 0.25 |p - V_i| along -grad F until F changes sign, then the bracket narrowed), accepted when E_i
// decreases, else s divided by 10; s starts at 0.1, at most 10 trials per target, stop when s <
// 0.001. Centroids are projected by the same walk with step 0.25 min(|AB|, |AC|)
// (project_by_gradient_walk, at most 100 steps). The Laplacian pass ("comes first" in the seed
// code) moves every vertex to the mean of its neighbours and projects it (walk step 0.1 x its mean
// edge length); it runs once, before the first sweep: repeated before every sweep it rounds the
// creases off again each time and the fit stops improving. Cost: about 3000 evaluations of F per
// vertex and sweep (trials x centroid projections). Vertices whose projection finds no surface stay
// where they were; moves that would turn a triangle over are rejected, and descent moves that
// break the angle floor (o.min_angle_deg, not in the seed) too. Vertices that share no face
// are independent, so the vertices are coloured and each colour class moves in lock-step with
// batched evaluations (the result is a Gauss-Seidel sweep in colour order). Inputs:  f (value;
// gradient if available, else central differences), F #F by 3, o In/out:  V #V by 3 (on or near F =
// 0)
SurfaceSmoothingReport smooth_on_surface(const ImplicitFunction& f, Eigen::MatrixXd& V,
                                         const Eigen::MatrixXi& F,
                                         const SurfaceSmoothingOptions& o = {});

} // namespace interlin
