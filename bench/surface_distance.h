#pragma once
// Exact point-to-mesh distances for the cloud benchmark (CGAL's AABB tree; CGAL's headers are
// seen only by surface_distance.cpp).

#include <Eigen/Core>
#include <memory>

namespace interlin::bench {

class MeshDistance {
public:
  // Inputs: V #V by 3, F #F by 3 (a triangle mesh; copied)
  MeshDistance(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);
  ~MeshDistance();
  // Distance from every row of P (#P by 3) to the nearest point of the mesh (2 threads).
  Eigen::VectorXd operator()(const Eigen::MatrixX3d& P) const;
  // The nearest point of the mesh to every row of P (#P by 3).
  Eigen::MatrixX3d closest(const Eigen::MatrixX3d& P) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Distances to a point set (CGAL's kd-tree), for the point-set Chamfer of a cloud.
class PointSetDistance {
public:
  // Inputs: S #S by 3 (copied)
  explicit PointSetDistance(const Eigen::MatrixX3d& S);
  ~PointSetDistance();
  // Distance from every row of P (#P by 3) to the nearest row of S.
  Eigen::VectorXd operator()(const Eigen::MatrixX3d& P) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace interlin::bench
