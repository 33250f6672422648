#pragma once
// A point cloud: the input of the point cloud -> implicit job (scans of blades and other parts).

#include <Eigen/Core>

namespace interlin {

// points   #P by 3 positions
// normals  #P by 3 unit normals, or 0 by 3 when the cloud has none; oriented (pointing out of
//          the body) only after orient_normals or when the source says so
struct PointCloud {
  Eigen::MatrixX3d points;
  Eigen::MatrixX3d normals = Eigen::MatrixX3d(0, 3);
  bool has_normals() const { return normals.rows() > 0 && normals.rows() == points.rows(); }
};

} // namespace interlin
