#pragma once
// The screened Poisson reconstructions a user would pick instead (baselines of the cloud
// benchmark): PCL's pcl::Poisson and Open3D's TriangleMesh::CreateFromPointCloudPoisson, given
// the same points and normals. Plain C++ interface; PCL's and Open3D's headers stay in
// poisson_pcl.cpp and poisson_open3d.cpp.

#include <Eigen/Core>

namespace interlin::bench {

// pcl::Poisson<pcl::PointNormal> at octree depth `depth` (PCL's defaults otherwise: degree 2,
// samples per node 1, scale 1.1), `threads` threads. Output: the triangle mesh V, F.
void pcl_poisson(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, int depth, int threads,
                 Eigen::MatrixXd& V, Eigen::MatrixXi& F);

// open3d::geometry::TriangleMesh::CreateFromPointCloudPoisson at depth `depth` (Open3D's
// defaults otherwise: scale 1.1, no linear fit), `threads` threads.
void open3d_poisson(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, int depth, int threads,
                    Eigen::MatrixXd& V, Eigen::MatrixXi& F);

} // namespace interlin::bench
