#pragma once
// Noisy scan points moved onto their local surface, each with its own neighbourhood size.

#include <Eigen/Core>

namespace interlin {

struct SmoothedPoints {
  Eigen::MatrixX3d P, N; // the moved points and their normals (#P by 3)
  Eigen::VectorXi k;     // the neighbourhood size chosen at each point (0: the point kept)
  long on_edges = 0;     // points moved onto edge sheets (edges)
};

// Local quadric projection with a bandwidth chosen point by point (Lepski's method: Lepski,
// Mammen & Spokoiny 1997, Ann. Statist. 25(3), "Optimal spatial adaptation to inhomogeneous
// smoothness"). At each point p with oriented normal n, the height function
// h(u, v) = c0 u^2 + c1 u v + c2 v^2 + c3 u + c4 v + c5 over the tangent plane of n is fitted by
// least squares to its k nearest neighbours whose normals lie within 60 degrees of n (the other
// side of a thin wall is not the same sheet), for k = 16, 32, ..., k_max. Its value at p,
// h_k = c5, has the standard deviation s_k = sigma sqrt((A^T A)^-1_55). The chosen k is the
// largest whose h_k lies within kappa s_j of every smaller rung's h_j: the rungs agree while the
// quadric's bias is below their noise, and the first disagreement marks the scale where the shape
// (an edge, a bend) outgrows the quadric. p moves to p + h_k n, and n becomes the quadric's
// normal there. Fewer than 12 points on the sheet at k = 16: p and n are kept.
// For speed every 8th point in Z-order is an anchor with its own rungs; another point is
// moved along its anchor's normal onto the quadric of its nearest anchor on the same
// sheet when that quadric holds at least 128 points and reaches 4 times the distance, and gets
// its own rungs otherwise (near edges and thin walls, where the rungs stop early).
// Edges (after Fleishman, Cohen-Or & Silva 2005, "Robust moving least-squares fitting with sharp
// features"): a point whose 48 nearest same-side neighbours' normals split into two groups at
// least 20 degrees apart, whose two quadrics joined (min at a convex edge, max at a concave one)
// miss them by at most 0.9 times one quadric's rms, and whose own quadric would take in the
// other face's points (normals within 60 degrees of n: estimated normals turn across an edge),
// moves onto that join instead, and n becomes the normal of the sheet it lands on.
// Inputs: P #P by 3, N #P by 3 unit normals oriented consistently, sigma > 0 the scan noise
//   (estimate_scan_noise), 16 <= k_max, kappa > 0, edges: the edge projection on,
//   threads (0: all cores)
// Output: P and N moved; k the rung chosen at each point (for a projected point its anchor's);
//   on_edges the points moved onto edge sheets.
// Throws std::invalid_argument for bad inputs (sizes, sigma <= 0, k_max < 16, NaN).
// See also: estimate_scan_noise (noise_level.h), fit_cloud_implicit (cloud_implicit.h)
SmoothedPoints smooth_scan_points(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                                  double sigma, int k_max = 512, double kappa = 1.5,
                                  bool edges = true, int threads = 0);

} // namespace interlin
