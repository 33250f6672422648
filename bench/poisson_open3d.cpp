// Open3D's screened Poisson reconstruction (baseline of bench_clouds). Built as C++17: Open3D
// 0.16's headers predate C++20.
#include "poisson_baselines.h"

#include <open3d/geometry/PointCloud.h>
#include <open3d/geometry/TriangleMesh.h>

namespace interlin::bench {

void open3d_poisson(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, int depth, int threads,
                    Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  open3d::geometry::PointCloud pc;
  pc.points_.reserve(static_cast<size_t>(P.rows()));
  pc.normals_.reserve(static_cast<size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    pc.points_.push_back(P.row(i).transpose());
    pc.normals_.push_back(N.row(i).transpose());
  }
  auto [mesh, density] = open3d::geometry::TriangleMesh::CreateFromPointCloudPoisson(
      pc, static_cast<size_t>(depth), 0.0f, 1.1f, false, threads);
  (void)density;
  V.resize(static_cast<Eigen::Index>(mesh->vertices_.size()), 3);
  for (size_t i = 0; i < mesh->vertices_.size(); ++i)
    V.row(static_cast<Eigen::Index>(i)) = mesh->vertices_[i].transpose();
  F.resize(static_cast<Eigen::Index>(mesh->triangles_.size()), 3);
  for (size_t t = 0; t < mesh->triangles_.size(); ++t)
    F.row(static_cast<Eigen::Index>(t)) = mesh->triangles_[t].transpose();
}

} // namespace interlin::bench
