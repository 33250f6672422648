#include "nearest_neighbours.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <flann/flann.hpp>

namespace interlin::detail {

struct NeighbourIndex::Impl {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> P;
  std::unique_ptr<flann::Index<flann::L2<double>>> index;
};

NeighbourIndex::NeighbourIndex(const Eigen::MatrixX3d& P) : impl_(std::make_unique<Impl>()) {
  impl_->P = P;
  flann::Matrix<double> data(impl_->P.data(), static_cast<size_t>(P.rows()), 3);
  // A single kd-tree with leaves of up to 12 points: exact searches, the fastest build.
  impl_->index =
      std::make_unique<flann::Index<flann::L2<double>>>(data, flann::KDTreeSingleIndexParams(12));
  impl_->index->buildIndex();
}

NeighbourIndex::~NeighbourIndex() = default;

Eigen::Index NeighbourIndex::size() const {
  return impl_->P.rows();
}

void NeighbourIndex::knn(const Eigen::Vector3d& q, int k, std::vector<int>& idx,
                         std::vector<double>& d2) const {
  k = static_cast<int>(std::min<Eigen::Index>(k, impl_->P.rows()));
  idx.resize(static_cast<size_t>(k));
  d2.resize(static_cast<size_t>(k));
  double qq[3] = {q(0), q(1), q(2)};
  flann::Matrix<double> query(qq, 1, 3);
  flann::Matrix<int> I(idx.data(), 1, static_cast<size_t>(k));
  flann::Matrix<double> D(d2.data(), 1, static_cast<size_t>(k));
  flann::SearchParams sp(flann::FLANN_CHECKS_UNLIMITED);
  sp.sorted = true;
  impl_->index->knnSearch(query, I, D, static_cast<size_t>(k), sp);
}

void NeighbourIndex::radius(const Eigen::Vector3d& q, double r, std::vector<int>& idx,
                            std::vector<double>& d2) const {
  double qq[3] = {q(0), q(1), q(2)};
  flann::Matrix<double> query(qq, 1, 3);
  std::vector<std::vector<int>> I;
  std::vector<std::vector<double>> D;
  flann::SearchParams sp(flann::FLANN_CHECKS_UNLIMITED);
  sp.sorted = false;
  impl_->index->radiusSearch(query, I, D, static_cast<float>(r * r), sp);
  idx.swap(I[0]);
  d2.swap(D[0]);
}

Eigen::MatrixXi NeighbourIndex::knn_all(int k, int threads) const {
  const Eigen::Index n = impl_->P.rows();
  k = static_cast<int>(std::min<Eigen::Index>(k, n - 1));
  Eigen::MatrixXi out(n, k);
  parallel_for(static_cast<long>(n), resolve_threads(threads), [&](long i, int) {
    std::vector<int> idx;
    std::vector<double> d2;
    knn(impl_->P.row(i).transpose(), k + 1, idx, d2);
    int c = 0;
    for (int j : idx) // itself first (distance 0), unless a duplicate came first
      if (j != i && c < k)
        out(i, c++) = j;
    for (; c < k; ++c)
      out(i, c) = idx.back();
  });
  return out;
}

} // namespace interlin::detail
