#include "interlin/reconstruction/implicit/body_projection.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <flann/flann.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin {

using RowPoints = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

// Approximate nearest samples: the k-th returned is within (1 + kEps) of the true k-th. An
// exact search from far points (every sample of a thin blade about equally far) costs ~6e5
// instructions a query; starts need only be near the nearest foot, and Newton and the choice of
// the nearest foot do the rest (checked against exhaustive sampling in the tests).
constexpr float kEps = 0.5f;

// The samples of one patch and their tree.
struct BodyProjection::Tree {
  std::vector<PatchSeed> where;
  RowPoints data; // FLANN keeps a pointer to it
  std::unique_ptr<flann::Index<flann::L2<double>>> tree;
  double du = 0, dv = 0; // parameter distances within which two samples are one start

  Tree(const BodyPatches& b, std::vector<PatchSeed> w, double du_, double dv_)
      : where(std::move(w)), data(static_cast<Eigen::Index>(where.size()), 3), du(du_), dv(dv_) {
    for (size_t i = 0; i < where.size(); ++i)
      data.row(static_cast<Eigen::Index>(i)) = evaluate(b, where[i]).transpose();
    tree = std::make_unique<flann::Index<flann::L2<double>>>(
        flann::Matrix<double>(data.data(), static_cast<size_t>(data.rows()), 3),
        flann::KDTreeSingleIndexParams(12));
    tree->buildIndex();
  }

  // One start per group of neighbouring samples among the k nearest of each point, with the
  // sample's distance.
  std::vector<std::vector<std::pair<PatchSeed, double>>> starts(RowPoints& Q, int k) const {
    std::vector<std::vector<size_t>> nn;
    std::vector<std::vector<double>> d2;
    tree->knnSearch(flann::Matrix<double>(Q.data(), static_cast<size_t>(Q.rows()), 3), nn, d2,
                    std::min<int>(k, static_cast<int>(where.size())),
                    flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED, kEps));
    std::vector<std::vector<std::pair<PatchSeed, double>>> out(nn.size());
    for (size_t i = 0; i < nn.size(); ++i)
      for (size_t j = 0; j < nn[i].size(); ++j) {
        const PatchSeed& w = where[nn[i][j]];
        const bool near = std::any_of(out[i].begin(), out[i].end(), [&](const auto& o) {
          return std::abs(o.first.u - w.u) < du && std::abs(o.first.v - w.v) < dv;
        });
        if (!near)
          out[i].push_back({w, std::sqrt(d2[i][j])});
      }
    return out;
  }

  // The largest distance of a patch point from its nearest sample: half the longest diagonal
  // of the sample grid's cells (rows of `per_row` samples).
  void set_reach(size_t per_row) {
    for (size_t i = 0; i + per_row + 1 < where.size(); ++i)
      if ((i + 1) % per_row != 0)
        reach = std::max({reach,
                          0.5 * (data.row(static_cast<Eigen::Index>(i)) -
                                 data.row(static_cast<Eigen::Index>(i + per_row + 1)))
                                    .norm(),
                          0.5 * (data.row(static_cast<Eigen::Index>(i + 1)) -
                                 data.row(static_cast<Eigen::Index>(i + per_row)))
                                    .norm()});
  }
  double reach = 0;
};

namespace {

// The sample trees of the three patches: the side's samples_u x samples_v grid (u wrapping), the
// caps' (samples_u + 1) x (cap_v + 1) grids. Caps' foot searches run in s alone (the nearest
// point of each ruling is explicit), so samples along one ruling are one start.
void make_trees(const BodyPatches& b, int samples_u, int samples_v, int cap_v,
                std::array<std::unique_ptr<BodyProjection::Tree>, 3>& trees);

} // namespace

BodyProjection::BodyProjection(const BodyPatches& patches, int samples_u, int samples_v, int starts)
    : patches_(patches), starts_(starts) {
  if (samples_u < 64 || samples_v < 32 || starts < 1)
    throw std::invalid_argument("BodyProjection: too few samples or starts");
  make_trees(patches_, samples_u, samples_v, 16, trees_);
  make_trees(patches_, 64, 32, 4, coarse_);
}

namespace {

void make_trees(const BodyPatches& b, int samples_u, int samples_v, int cap_v,
                std::array<std::unique_ptr<BodyProjection::Tree>, 3>& trees) {
  const Eigen::Vector4d side = domain(b.patches[0]);
  std::vector<PatchSeed> w;
  for (int j = 0; j < samples_v; ++j)
    for (int i = 0; i < samples_u; ++i)
      w.push_back({0, side(0) + (side(1) - side(0)) * i / samples_u,
                   side(2) + (side(3) - side(2)) * j / (samples_v - 1)});
  trees[0] = std::make_unique<BodyProjection::Tree>(b, std::move(w), 2.0 / samples_u,
                                                    2.0 * (side(3) - side(2)) / (samples_v - 1));
  trees[0]->set_reach(static_cast<size_t>(samples_u));
  for (int k = 1; k < 3; ++k) {
    std::vector<PatchSeed> c;
    for (int j = 0; j <= cap_v; ++j)
      for (int i = 0; i <= samples_u; ++i)
        c.push_back({k, double(i) / samples_u, double(j) / cap_v});
    trees[static_cast<size_t>(k)] =
        std::make_unique<BodyProjection::Tree>(b, std::move(c), 2.0 / samples_u, 2.0);
    trees[static_cast<size_t>(k)]->set_reach(static_cast<size_t>(samples_u) + 1);
  }
}

// Starts for the rows `rows` of Q from the trees of the patches searched (all, or `patch`):
// a start whose sample is farther than the nearest sample of all plus twice its patch's reach
// cannot lead to the nearest foot (every patch point is within `reach` of a sample).
std::vector<std::vector<PatchSeed>>
tree_starts(const std::array<std::unique_ptr<BodyProjection::Tree>, 3>& trees, RowPoints& Q, int k,
            int patch, std::vector<double>* nearest_out = nullptr) {
  std::vector<std::vector<std::pair<PatchSeed, double>>> found(static_cast<size_t>(Q.rows()));
  for (int t = 0; t < 3; ++t)
    if (patch < 0 || patch == t) {
      const auto s = trees[static_cast<size_t>(t)]->starts(Q, k);
      for (size_t i = 0; i < s.size(); ++i)
        found[i].insert(found[i].end(), s[i].begin(), s[i].end());
    }
  std::vector<std::vector<PatchSeed>> starts(found.size());
  if (nearest_out)
    nearest_out->assign(found.size(), INFINITY);
  for (size_t i = 0; i < found.size(); ++i) {
    double nearest = INFINITY;
    for (const auto& [at, d] : found[i])
      nearest = std::min(nearest, d);
    for (const auto& [at, d] : found[i])
      if (d <= nearest + 2 * trees[static_cast<size_t>(at.patch)]->reach)
        starts[i].push_back(at);
    if (nearest_out)
      (*nearest_out)[i] = nearest;
  }
  return starts;
}

} // namespace

BodyProjection::~BodyProjection() = default;

std::vector<BodyDistance> BodyProjection::distances(const Eigen::MatrixXd& P, int threads,
                                                    int patch) const {
  if (P.cols() != 3)
    throw std::invalid_argument("BodyProjection: points must be #P by 3");
  if (patch < -1 || patch > 2)
    throw std::invalid_argument("BodyProjection: patch must be -1, 0, 1 or 2");
  std::vector<BodyDistance> out(static_cast<size_t>(P.rows()));
  if (P.rows() == 0)
    return out;
  // Starts from the coarse trees; points near the boundary (within eight coarse reaches, where
  // a coarse start may sit in the wrong basin) take them from the fine trees instead. Far
  // points are the expensive queries of the fine trees and the easy ones for Newton.
  RowPoints Q = P;
  std::vector<double> nearest;
  std::vector<std::vector<PatchSeed>> starts = tree_starts(coarse_, Q, starts_, patch, &nearest);
  double reach = 0;
  for (const auto& t : coarse_)
    reach = std::max(reach, t->reach);
  std::vector<Eigen::Index> near;
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    if (nearest[static_cast<size_t>(i)] <= 8 * reach)
      near.push_back(i);
  RowPoints N(static_cast<Eigen::Index>(near.size()), 3);
  for (size_t j = 0; j < near.size(); ++j)
    N.row(static_cast<Eigen::Index>(j)) = Q.row(near[j]);
  std::vector<std::vector<PatchSeed>> fine = tree_starts(trees_, N, starts_, patch);
  for (size_t j = 0; j < near.size(); ++j)
    starts[static_cast<size_t>(near[j])] = std::move(fine[j]);
  const long chunk = 256;
  detail::parallel_for(
      (P.rows() + chunk - 1) / chunk, detail::resolve_threads(threads), [&](long task, int) {
        const Eigen::Index end = std::min<Eigen::Index>(P.rows(), (task + 1) * chunk);
        for (Eigen::Index i = task * chunk; i < end; ++i) {
          const std::vector<PatchSeed>& s = starts[static_cast<size_t>(i)];
          out[static_cast<size_t>(i)] =
              body_distance(patches_, P.row(i).transpose(), s.data(), static_cast<int>(s.size()));
        }
      });
  return out;
}

} // namespace interlin
