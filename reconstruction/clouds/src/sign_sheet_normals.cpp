// Signs of sheet normals from oriented PCA normals: a local vote along each sheet
// (orient_normals.h).
#include "interlin/reconstruction/clouds/orient_normals.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include "nearest_neighbours.h"
#include "sheet_plane.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

namespace {

using Graph = std::vector<std::vector<int>>;

constexpr int kSheetGraph = 16; // nearest points, itself included
constexpr int kVoteHops = 30;

// Mutual nearest neighbours on each other's sheet plane with normals within 15 degrees.
Graph sheet_graph(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& S, double sigma, int threads) {
  const double kParallel = std::cos(15 * M_PI / 180);
  const Eigen::Index n = P.rows();
  const Eigen::MatrixXi K = detail::NeighbourIndex(P).knn_all(kSheetGraph - 1, threads);
  Eigen::VectorXd tol(n);
  for (Eigen::Index i = 0; i < n; ++i)
    tol(i) =
        detail::sheet_tolerance((P.row(K(i, detail::kSheetProposal - 2)) - P.row(i)).norm(), sigma);
  auto on_sheet_of = [&](Eigen::Index i, Eigen::Index j) {
    return std::abs((P.row(j) - P.row(i)).dot(S.row(i))) <= tol(i);
  };
  Graph g(static_cast<size_t>(n));
  detail::parallel_for(long(n), detail::resolve_threads(threads), [&](long i, int) {
    for (Eigen::Index c = 0; c < K.cols(); ++c) {
      const int j = K(i, c);
      if ((K.row(j).array() == int(i)).any() && std::abs(S.row(i).dot(S.row(j))) >= kParallel &&
          on_sheet_of(i, j) && on_sheet_of(j, i))
        g[size_t(i)].push_back(j);
    }
  });
  return g;
}

// Each connected part of g made consistent from its first point by breadth-first propagation.
Eigen::MatrixX3d propagate(const Graph& g, Eigen::MatrixX3d M) {
  std::vector<char> seen(g.size(), 0);
  std::vector<int> queue;
  for (size_t root = 0; root < g.size(); ++root) {
    if (seen[root])
      continue;
    seen[root] = 1;
    queue.assign(1, int(root));
    for (size_t h = 0; h < queue.size(); ++h)
      for (int j : g[size_t(queue[h])])
        if (!seen[size_t(j)]) {
          seen[size_t(j)] = 1;
          if (M.row(j).dot(M.row(queue[h])) < 0)
            M.row(j) *= -1;
          queue.push_back(j);
        }
  }
  return M;
}

// The votes averaged over each point and its graph neighbours, `hops` times.
Eigen::VectorXd diffuse(const Graph& g, Eigen::VectorXd v, int hops, int threads) {
  Eigen::VectorXd w(v.size());
  for (int h = 0; h < hops; ++h) {
    detail::parallel_for(long(v.size()), detail::resolve_threads(threads), [&](long i, int) {
      double sum = v(i);
      for (int j : g[size_t(i)])
        sum += v(j);
      w(i) = sum / double(1 + g[size_t(i)].size());
    });
    v.swap(w);
  }
  return v;
}

} // namespace

Eigen::MatrixX3d sign_sheet_normals(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& S,
                                    const Eigen::MatrixX3d& O, double sigma, int threads) {
  if (S.rows() != P.rows() || O.rows() != P.rows() || !(sigma >= 0))
    throw std::invalid_argument(
        "sheet normal signs: P, S and O must have as many rows; sigma >= 0");
  const double kReliable = std::cos(20 * M_PI / 180);
  const Eigen::Index n = P.rows();
  Eigen::MatrixX3d signed_S = S;
  for (Eigen::Index i = 0; i < n; ++i)
    if (S.row(i).dot(O.row(i)) < 0)
      signed_S.row(i) *= -1;
  if (n <= kSheetGraph)
    return signed_S;
  const Graph g = sheet_graph(P, S, sigma, threads);
  const Eigen::MatrixX3d M = propagate(g, signed_S);
  Eigen::VectorXd votes = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::abs(S.row(i).dot(O.row(i))) >= kReliable)
      votes(i) = M.row(i).dot(O.row(i)) > 0 ? 1 : -1;
  votes = diffuse(g, votes, kVoteHops, threads);
  for (Eigen::Index i = 0; i < n; ++i)
    if (votes(i) != 0)
      signed_S.row(i) = (votes(i) > 0 ? 1.0 : -1.0) * M.row(i);
  return signed_S;
}

} // namespace interlin
