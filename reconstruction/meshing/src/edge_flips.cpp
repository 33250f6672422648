#include "interlin/reconstruction/meshing/edge_flips.h"

#include "min_angle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace interlin {

namespace {

std::uint64_t key(int a, int b) {
  return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
}

Eigen::Vector3d normal(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                       const Eigen::Vector3d& c) {
  return (b - a).cross(c - a);
}

using EdgeFaces = std::unordered_map<std::uint64_t, std::array<int, 2>>;

void check_input(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("flip_edges: V and F must have 3 columns");
  for (long f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      if (F(f, j) < 0 || F(f, j) >= V.rows())
        throw std::invalid_argument("flip_edges: face " + std::to_string(f) +
                                    " has an index out of range");
}

// Edge -> its (up to) two faces.
EdgeFaces edge_faces(const Eigen::MatrixXi& F) {
  EdgeFaces edges;
  edges.reserve(size_t(3 * F.rows() / 2 + 1));
  for (int f = 0; f < int(F.rows()); ++f)
    for (int j = 0; j < 3; ++j) {
      auto [it, fresh] = edges.try_emplace(key(F(f, j), F(f, (j + 1) % 3)), std::array{f, -1});
      if (fresh)
        continue;
      if (it->second[1] >= 0)
        throw std::invalid_argument("flip_edges: an edge has more than two triangles");
      it->second[1] = f;
    }
  return edges;
}

// Position of the edge (a, b) in face f as the directed a -> b; -1 if f has it as b -> a.
int directed(const Eigen::MatrixXi& F, int f, int a, int b) {
  for (int j = 0; j < 3; ++j)
    if (F(f, j) == a && F(f, (j + 1) % 3) == b)
      return j;
  return -1;
}

// Whether (a, b, c), (b, a, d) -> (d, b, c), (c, a, d) raises the smaller minimum angle, between
// faces within the dihedral limit, with c-d crossing a-b inside both (seen along the mean
// normal) and no fold-over.
bool flip_improves(const Eigen::Vector3d& pa, const Eigen::Vector3d& pb, const Eigen::Vector3d& pc,
                   const Eigen::Vector3d& pd, double cos_limit) {
  const Eigen::Vector3d n0 = normal(pa, pb, pc), n1 = normal(pb, pa, pd);
  if (!(n0.norm() > 0) || !(n1.norm() > 0) || n0.normalized().dot(n1.normalized()) < cos_limit)
    return false;
  const double before = std::min(detail::min_angle(pa, pb, pc), detail::min_angle(pb, pa, pd));
  const double after = std::min(detail::min_angle(pd, pb, pc), detail::min_angle(pc, pa, pd));
  if (!(after > before + 1e-9))
    return false;
  const Eigen::Vector3d m = (n0.normalized() + n1.normalized()).normalized();
  const Eigen::Vector3d ex = (pb - pa - (pb - pa).dot(m) * m).normalized(), ey = m.cross(ex);
  auto flat = [&](const Eigen::Vector3d& p) {
    return Eigen::Vector2d((p - pa).dot(ex), (p - pa).dot(ey));
  };
  const Eigen::Vector2d A = flat(pa), B = flat(pb), C = flat(pc), D = flat(pd);
  const Eigen::Vector2d r = B - A, s = D - C, q = C - A;
  const double den = r.x() * s.y() - r.y() * s.x();
  if (den == 0)
    return false;
  const double t = (q.x() * s.y() - q.y() * s.x()) / den, v = (q.x() * r.y() - q.y() * r.x()) / den;
  if (!(t > 0.01 && t < 0.99 && v > 0.01 && v < 0.99))
    return false;
  return normal(pd, pb, pc).dot(m) > 0 && normal(pc, pa, pd).dot(m) > 0;
}

// Flip: (a, b, c) = f0, (b, a, d) = f1 -> (d, b, c), (c, a, d); the edge table follows.
void flip(Eigen::MatrixXi& F, EdgeFaces& edges, EdgeFaces::iterator ab, int f0, int f1, int a,
          int b, int c, int d) {
  F.row(f0) << d, b, c;
  F.row(f1) << c, a, d;
  edges.erase(ab);
  edges[key(c, d)] = {f0, f1};
  for (auto [x, y, from, to] : {std::array{b, d, f1, f0}, std::array{a, c, f0, f1}}) {
    auto& e = edges.at(key(x, y));
    for (int& g : e)
      if (g == from) {
        g = to;
        break;
      }
  }
}

} // namespace

long flip_edges(const Eigen::MatrixXd& V, Eigen::MatrixXi& F, const EdgeFlipOptions& o) {
  check_input(V, F);
  const double cos_limit = std::cos(o.max_dihedral_deg * M_PI / 180);
  EdgeFaces edges = edge_faces(F);
  auto vtx = [&](int i) -> Eigen::Vector3d { return V.row(i).transpose(); };
  std::vector<std::uint64_t> todo;
  for (const auto& e : edges)
    todo.push_back(e.first);
  std::sort(todo.begin(), todo.end()); // deterministic order
  long flips = 0;
  for (int sweep = 0; sweep < o.max_sweeps && !todo.empty(); ++sweep) {
    std::vector<std::uint64_t> next;
    for (const std::uint64_t k : todo) {
      const auto it = edges.find(k);
      if (it == edges.end() || it->second[1] < 0)
        continue;
      int f0 = it->second[0], f1 = it->second[1];
      const int a = int(k >> 32), b = int(k & 0xffffffffu);
      int j0 = directed(F, f0, a, b);
      if (j0 < 0) {
        std::swap(f0, f1);
        j0 = directed(F, f0, a, b);
      }
      const int j1 = directed(F, f1, b, a);
      if (j0 < 0 || j1 < 0)
        throw std::invalid_argument("flip_edges: inconsistent orientation across an edge");
      const int c = F(f0, (j0 + 2) % 3), d = F(f1, (j1 + 2) % 3);
      if (c == d || edges.count(key(c, d)) ||
          !flip_improves(vtx(a), vtx(b), vtx(c), vtx(d), cos_limit))
        continue;
      flip(F, edges, it, f0, f1, a, b, c, d);
      ++flips;
      for (const std::uint64_t nk : {key(a, c), key(c, b), key(b, d), key(d, a)})
        next.push_back(nk);
    }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    todo.swap(next);
  }
  return flips;
}

} // namespace interlin
