// PCL's screened Poisson reconstruction (baseline of bench_clouds).
#include "poisson_baselines.h"

#include <pcl/PolygonMesh.h>
#include <pcl/conversions.h>
#include <pcl/point_types.h>
#include <pcl/surface/poisson.h>

namespace interlin::bench {

void pcl_poisson(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, int depth, int threads,
                 Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  // PCL works in float: coordinates relative to the centre keep far-off scans precise.
  const Eigen::RowVector3d o = 0.5 * (P.colwise().minCoeff() + P.colwise().maxCoeff());
  auto cloud = std::make_shared<pcl::PointCloud<pcl::PointNormal>>();
  cloud->resize(static_cast<size_t>(P.rows()));
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    pcl::PointNormal& q = (*cloud)[static_cast<size_t>(i)];
    q.x = float(P(i, 0) - o(0));
    q.y = float(P(i, 1) - o(1));
    q.z = float(P(i, 2) - o(2));
    q.normal_x = float(N(i, 0));
    q.normal_y = float(N(i, 1));
    q.normal_z = float(N(i, 2));
  }
  pcl::Poisson<pcl::PointNormal> poisson;
  poisson.setDepth(depth);
  poisson.setThreads(threads);
  poisson.setInputCloud(cloud);
  pcl::PolygonMesh mesh;
  poisson.reconstruct(mesh);
  pcl::PointCloud<pcl::PointXYZ> v;
  pcl::fromPCLPointCloud2(mesh.cloud, v);
  V.resize(static_cast<Eigen::Index>(v.size()), 3);
  for (size_t i = 0; i < v.size(); ++i)
    V.row(static_cast<Eigen::Index>(i)) = Eigen::RowVector3d(v[i].x, v[i].y, v[i].z) + o;
  F.resize(static_cast<Eigen::Index>(mesh.polygons.size()), 3);
  Eigen::Index t = 0;
  for (const pcl::Vertices& poly : mesh.polygons)
    if (poly.vertices.size() == 3) {
      for (int k = 0; k < 3; ++k)
        F(t, k) = static_cast<int>(poly.vertices[static_cast<size_t>(k)]);
      ++t;
    }
  F.conservativeResize(t, 3);
}

} // namespace interlin::bench
