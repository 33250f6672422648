#pragma once
// Sparse scans -> implicit function: Hermite radial basis function interpolation (Macêdo, Gois,
// Velho, "Hermite radial basis functions implicits", Computer Graphics Forum 30(1), 2011, §3):
//
//   F(x) = sum_j a_j phi(x - p_j) - b_j . grad phi(x - p_j) + g . x + c,   phi(v) = |v|^3,
//
// with F(p_i) = 0 and grad F(p_i) = -n_i at every point (n_i the outward normal, so F > 0
// inside) and the side conditions sum_j a_j = 0, sum_j (a_j p_j + b_j) = 0. The 4 #P + 4 unknowns
// solve a symmetric system whose matrix is conditionally positive definite (phi = r^3 is of
// order 2): positive definite on the null space of the linear polynomials' conditions, solved
// there by Cholesky. One global function of all the points: where the cloud is sparse (a few
// hundred points, e.g. a CMM or a thinned scan) it fills the gaps far more smoothly than local
// fits of a few points each (docs/benchmarks.md, "Sparse clouds: the Hermite RBF"), at O(#P^3)
// fitting and O(#P) work per evaluated point.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/clouds/point_cloud.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>

namespace interlin {

// The fitted interpolant in normalised coordinates xh = (x - centre) / scale; F(x) = scale x
// Fh(xh), so |grad F| = 1 at the points and F is about the signed distance near them.
//   points  #P by 3 centres p_j (normalised);  a  #P;  b  #P by 3;  g, c  the linear part
//   box     the function's box (the points' box with a margin);  spacing  median point spacing
struct HermiteRbf {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double scale = 1;
  Eigen::MatrixX3d points = Eigen::MatrixX3d(0, 3), b = Eigen::MatrixX3d(0, 3);
  Eigen::VectorXd a;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  double c = 0;
  Eigen::AlignedBox3d box;
  double spacing = 0;
};

// The most points fit_hermite_rbf takes: its dense system has 4 #P + 4 unknowns (128 MB and
// about 21 GFlop of Cholesky at this size).
constexpr Eigen::Index kHermiteRbfMaxPoints = 1000;

struct HermiteRbfInfo {
  bool flipped = false; // the normals pointed inward and were flipped (divergence theorem)
  double spacing = 0;   // median point spacing
  double seconds = 0;
};

// Interpolates a cloud with oriented unit normals (orient_normals; inward normals are detected
// and flipped like fit_cloud_implicit does). Throws std::invalid_argument for a cloud without
// normals, fewer than 4 or more than kHermiteRbfMaxPoints points, two points closer than 1e-9 of
// the diagonal (the system is singular), or a system that is not positive definite.
HermiteRbf fit_hermite_rbf(const PointCloud& c, HermiteRbfInfo* info = nullptr);

// The interpolant as an ImplicitFunction (value and exact gradient, box = model.box,
// sample_spacing = model.spacing). Safe for concurrent calls.
ImplicitFunction hermite_rbf_function(std::shared_ptr<const HermiteRbf> model);

} // namespace interlin
