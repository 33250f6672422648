#pragma once
// Internal: the smallest corner angle of a triangle, the quality that the marching-cubes loop
// triangulation and the edge flips maximise and that check_mesh reports.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace interlin::detail {

// Smallest corner angle of the triangle (a, b, c) in radians; atan2(|e1 x e2|, e1 . e2) stays
// accurate near 0 and pi.
inline double min_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) {
  const Eigen::Vector3d p[3] = {a, b, c};
  double m = M_PI;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d e1 = p[(j + 1) % 3] - p[j], e2 = p[(j + 2) % 3] - p[j];
    m = std::min(m, std::atan2(e1.cross(e2).norm(), e1.dot(e2)));
  }
  return m;
}

} // namespace interlin::detail
