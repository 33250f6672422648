#pragma once
// Private to reconstruction/clouds: nearest-neighbour queries on a point set through FLANN's
// kd-tree (the project's neighbour search; PCL's KdTreeFLANN wraps the same index).

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace interlin::detail {

class NeighbourIndex {
public:
  // Indexes the rows of P (#P by 3); P is copied.
  explicit NeighbourIndex(const Eigen::MatrixX3d& P);
  ~NeighbourIndex();
  NeighbourIndex(const NeighbourIndex&) = delete;
  NeighbourIndex& operator=(const NeighbourIndex&) = delete;

  // The k nearest indexed points of q (k clamped to #P), nearest first: indices and squared
  // distances. Exact search; safe to call from several threads at once.
  void knn(const Eigen::Vector3d& q, int k, std::vector<int>& idx, std::vector<double>& d2) const;
  // All indexed points within distance r of q (unordered).
  void radius(const Eigen::Vector3d& q, double r, std::vector<int>& idx,
              std::vector<double>& d2) const;
  // The k nearest neighbours of every indexed point (itself excluded): #P by k indices, in
  // parallel over `threads` threads (0: all cores).
  Eigen::MatrixXi knn_all(int k, int threads = 0) const;
  Eigen::Index size() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace interlin::detail
