// Hoppe et al. 1992 §3.3: normal orientation by propagation along a minimum spanning tree.
#include "interlin/reconstruction/clouds/orient_normals.h"

#include "nearest_neighbours.h"
#include "orientation_tree.h"

#include <algorithm>
#include <cmath>
#include <queue>
#include <vector>

namespace interlin {

using Eigen::Index;

namespace {

// The cost of propagating the orientation along edge i-j (orient_normals.h).
double edge_cost(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, Index i, Index j) {
  const Eigen::RowVector3d d = P.row(j) - P.row(i);
  const double len = d.norm();
  const double off =
      len > 0 ? 0.5 * (std::abs(N.row(i).dot(d)) + std::abs(N.row(j).dot(d))) / len : 0.0;
  return 1 - std::abs(N.row(i).dot(N.row(j))) + off;
}

// The points reachable from `start` (breadth first).
std::vector<int> component(const std::vector<std::vector<int>>& g, int start,
                           std::vector<char>& seen) {
  std::vector<int> c{start};
  seen[static_cast<size_t>(start)] = 1;
  for (size_t h = 0; h < c.size(); ++h)
    for (int j : g[static_cast<size_t>(c[h])])
      if (!seen[static_cast<size_t>(j)]) {
        seen[static_cast<size_t>(j)] = 1;
        c.push_back(j);
      }
  return c;
}

// The root of a component: its extreme point along one of the six axis directions whose normal
// is most nearly parallel to that direction; its normal is made to point along it.
int root_of(const std::vector<int>& c, const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N,
            Index& flipped) {
  int best = c.front();
  double best_align = -1;
  Eigen::Vector3d best_dir = Eigen::Vector3d::UnitZ();
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {1.0, -1.0}) {
      int e = c.front();
      for (int i : c)
        if (s * P(i, axis) > s * P(e, axis))
          e = i;
      const double a = std::abs(N(e, axis));
      if (a > best_align) {
        best_align = a;
        best = e;
        best_dir = s * Eigen::Vector3d::Unit(axis);
      }
    }
  if (N.row(best).dot(best_dir) < 0) {
    N.row(best) *= -1;
    ++flipped;
  }
  return best;
}

} // namespace

namespace detail {

std::vector<std::vector<int>> neighbour_graph(const Eigen::MatrixXi& K) {
  std::vector<std::vector<int>> g(static_cast<size_t>(K.rows()));
  for (Index i = 0; i < K.rows(); ++i)
    for (Index c = 0; c < K.cols(); ++c) {
      const int j = K(i, c);
      if (j == i)
        continue;
      g[static_cast<size_t>(i)].push_back(j);
      g[static_cast<size_t>(j)].push_back(static_cast<int>(i));
    }
  for (auto& l : g) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  return g;
}

Index grow_orientation(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N,
                       const std::vector<std::vector<int>>& g, const std::vector<int>& seeds,
                       std::vector<char>& done) {
  using Edge = std::pair<double, std::pair<int, int>>; // cost, (from, to)
  std::priority_queue<Edge, std::vector<Edge>, std::greater<>> heap;
  auto push_edges = [&](int from) {
    for (int j : g[static_cast<size_t>(from)])
      if (!done[static_cast<size_t>(j)])
        heap.push({edge_cost(P, N, from, j), {from, j}});
  };
  for (int s : seeds)
    push_edges(s);
  Index flipped = 0;
  while (!heap.empty()) {
    const auto [from, to] = heap.top().second;
    heap.pop();
    if (done[static_cast<size_t>(to)])
      continue;
    done[static_cast<size_t>(to)] = 1;
    if (N.row(from).dot(N.row(to)) < 0) {
      N.row(to) *= -1;
      ++flipped;
    }
    push_edges(to);
  }
  return flipped;
}

} // namespace detail

void orient_normals(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N, int k, OrientationInfo* info) {
  OrientationInfo out;
  const Index n = P.rows();
  if (n < 2) {
    if (info)
      *info = out;
    return;
  }
  const detail::NeighbourIndex index(P);
  const std::vector<std::vector<int>> g = detail::neighbour_graph(index.knn_all(k));
  std::vector<char> seen(static_cast<size_t>(n), 0), done(static_cast<size_t>(n), 0);
  for (Index s = 0; s < n; ++s) {
    if (seen[static_cast<size_t>(s)])
      continue;
    const std::vector<int> c = component(g, static_cast<int>(s), seen);
    ++out.components;
    const int root = root_of(c, P, N, out.flipped);
    done[static_cast<size_t>(root)] = 1;
    out.flipped += detail::grow_orientation(P, N, g, {root}, done);
  }
  if (info)
    *info = out;
}

double orientation_disagreement(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N, int k) {
  if (P.rows() < 2)
    return 0;
  const detail::NeighbourIndex index(P);
  const Eigen::MatrixXi K = index.knn_all(k);
  const double tangent = std::sin(30.0 * M_PI / 180.0); // |n . e| below: edge near the plane
  long pairs = 0, opposite = 0;
  for (Index i = 0; i < K.rows(); ++i)
    for (Index c = 0; c < K.cols(); ++c) {
      const Index j = K(i, c);
      const Eigen::RowVector3d d = P.row(j) - P.row(i);
      const double len = d.norm();
      if (!(len > 0) || std::abs(N.row(i).dot(d)) > tangent * len ||
          std::abs(N.row(j).dot(d)) > tangent * len)
        continue;
      ++pairs;
      opposite += N.row(i).dot(N.row(j)) < 0;
    }
  return pairs > 0 ? double(opposite) / double(pairs) : 0.0;
}

} // namespace interlin
