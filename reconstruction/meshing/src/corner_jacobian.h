#pragma once
// The corner scaled Jacobian of a hexahedron (Knupp; Verdict's hexahedral scaled Jacobian without
// its centre term): at corner j with edges u, v, w to the corners of corner_table(8) row j,
// alpha_j / (|u| |v| |w|), alpha_j = (u x v) . w (digest 003 §6.4); and the centre's principal
// axes and Jacobian (Verdict's centre term).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <limits>

namespace interlin::detail {

struct CornerJacobian {
  double min_scaled = std::numeric_limits<double>::infinity(); // 0 at a collapsed edge
  bool inverted = false; // a corner with alpha_j <= 0 (or NaN, which the minimum skips)
};

// p: the 8 corners (VTK order); T: corner_table(8); alpha: the 8 alpha_j when already known
// (corner_alphas), else nullptr.
inline CornerJacobian corner_scaled_jacobian(const Eigen::Vector3d p[8], const Eigen::MatrixXi& T,
                                             const double* alpha = nullptr) {
  CornerJacobian r;
  for (int j = 0; j < 8; ++j) {
    const Eigen::Vector3d u = p[T(j, 0)] - p[j], v = p[T(j, 1)] - p[j], w = p[T(j, 2)] - p[j];
    const double a = alpha != nullptr ? alpha[j] : u.cross(v).dot(w);
    const double l = u.norm() * v.norm() * w.norm();
    r.inverted = r.inverted || !(a > 0);
    r.min_scaled = std::min(r.min_scaled, l > 0 ? a / l : 0.0);
  }
  return r;
}

// The hexahedron's principal axes at its centre (Verdict), corners in VTK order: the trilinear
// map's derivatives there, times 4.
inline std::array<Eigen::Vector3d, 3> centre_axes(const Eigen::Vector3d p[8]) {
  return {(p[1] - p[0]) + (p[2] - p[3]) + (p[5] - p[4]) + (p[6] - p[7]),
          (p[3] - p[0]) + (p[2] - p[1]) + (p[7] - p[4]) + (p[6] - p[5]),
          (p[4] - p[0]) + (p[5] - p[1]) + (p[6] - p[2]) + (p[7] - p[3])};
}

// (x1 x x2) . x3 of the centre axes: <= 0, the element folds inside even where all 8 corners
// are convex.
inline double centre_jacobian(const Eigen::Vector3d p[8]) {
  const std::array<Eigen::Vector3d, 3> x = centre_axes(p);
  return x[0].cross(x[1]).dot(x[2]);
}

// Mean edge length of hexahedron e (C #C by 8, VTK order: its 12 edges).
inline double mean_edge(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, long e) {
  constexpr int kEdges[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                 {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  double sum = 0;
  for (const auto& edge : kEdges)
    sum += (V.row(C(e, edge[0])) - V.row(C(e, edge[1]))).norm();
  return sum / 12;
}

// The mean of the hexahedra's mean edge lengths.
inline double mean_edge(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
  double mean = 0;
  for (long e = 0; e < C.rows(); ++e)
    mean += mean_edge(V, C, e) / double(C.rows());
  return mean;
}

} // namespace interlin::detail
