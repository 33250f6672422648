// Points uniform by area on a triangle mesh (sample_mesh.h).
#include "interlin/reconstruction/clouds/sample_mesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

namespace interlin {

PointCloud sample_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int n, unsigned seed) {
  if (F.rows() == 0 || F.cols() != 3 || V.cols() != 3 || n < 0 || F.minCoeff() < 0 ||
      F.maxCoeff() >= V.rows())
    throw std::invalid_argument("sample_mesh: needs triangles indexing V (#V by 3) and n >= 0");
  std::vector<double> cum(static_cast<size_t>(F.rows())); // cumulative triangle areas
  double total = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    total += 0.5 * (p1 - p0).cross(p2 - p0).norm();
    cum[static_cast<size_t>(f)] = total;
  }
  if (!(total > 0))
    throw std::invalid_argument("sample_mesh: the mesh has no area");
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  PointCloud c;
  c.points.resize(n, 3);
  c.normals.resize(n, 3);
  for (int k = 0; k < n; ++k) {
    const Eigen::Index f = std::min<Eigen::Index>(
        std::lower_bound(cum.begin(), cum.end(), U(rng) * total) - cum.begin(), F.rows() - 1);
    double a = U(rng), b = U(rng);
    if (a + b > 1) // reflected into the triangle: the density stays uniform
      a = 1 - a, b = 1 - b;
    const Eigen::RowVector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    c.points.row(k) = p0 + a * (p1 - p0) + b * (p2 - p0);
    c.normals.row(k) = (p1 - p0).cross(p2 - p0).normalized();
  }
  return c;
}

} // namespace interlin
