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

} // namespace

long flip_edges(const Eigen::MatrixXd& V, Eigen::MatrixXi& F, const EdgeFlipOptions& o) {
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("flip_edges: V and F must have 3 columns");
  for (long f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      if (F(f, j) < 0 || F(f, j) >= V.rows())
        throw std::invalid_argument("flip_edges: face " + std::to_string(f) +
                                    " has an index out of range");
  const double cos_limit = std::cos(o.max_dihedral_deg * M_PI / 180);
  // Edge -> its (up to) two faces.
  std::unordered_map<std::uint64_t, std::array<int, 2>> edges;
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
  auto vtx = [&](int i) -> Eigen::Vector3d { return V.row(i).transpose(); };
  // Position of the edge (a, b) in face f as the directed a -> b; -1 if f has it as b -> a.
  auto directed = [&](int f, int a, int b) {
    for (int j = 0; j < 3; ++j)
      if (F(f, j) == a && F(f, (j + 1) % 3) == b)
        return j;
    return -1;
  };
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
      const int u = int(k >> 32), w = int(k & 0xffffffffu);
      int j0 = directed(f0, u, w);
      if (j0 < 0) {
        std::swap(f0, f1);
        j0 = directed(f0, u, w);
      }
      const int j1 = directed(f1, w, u);
      if (j0 < 0 || j1 < 0)
        throw std::invalid_argument("flip_edges: inconsistent orientation across an edge");
      const int a = u, b = w, c = F(f0, (j0 + 2) % 3), d = F(f1, (j1 + 2) % 3);
      if (c == d || edges.count(key(c, d)))
        continue;
      const Eigen::Vector3d pa = vtx(a), pb = vtx(b), pc = vtx(c), pd = vtx(d);
      const Eigen::Vector3d n0 = normal(pa, pb, pc), n1 = normal(pb, pa, pd);
      if (!(n0.norm() > 0) || !(n1.norm() > 0) || n0.normalized().dot(n1.normalized()) < cos_limit)
        continue;
      const double before = std::min(detail::min_angle(pa, pb, pc), detail::min_angle(pb, pa, pd));
      const double after = std::min(detail::min_angle(pd, pb, pc), detail::min_angle(pc, pa, pd));
      if (!(after > before + 1e-9))
        continue;
      // Validity: c-d crosses a-b inside both, seen along the mean normal; no fold-over.
      const Eigen::Vector3d m = (n0.normalized() + n1.normalized()).normalized();
      const Eigen::Vector3d ex = (pb - pa - (pb - pa).dot(m) * m).normalized(), ey = m.cross(ex);
      auto flat = [&](const Eigen::Vector3d& p) {
        return Eigen::Vector2d((p - pa).dot(ex), (p - pa).dot(ey));
      };
      const Eigen::Vector2d A = flat(pa), B = flat(pb), C = flat(pc), D = flat(pd);
      const Eigen::Vector2d r = B - A, s = D - C, q = C - A;
      const double den = r.x() * s.y() - r.y() * s.x();
      if (den == 0)
        continue;
      const double t = (q.x() * s.y() - q.y() * s.x()) / den,
                   v = (q.x() * r.y() - q.y() * r.x()) / den;
      if (!(t > 0.01 && t < 0.99 && v > 0.01 && v < 0.99))
        continue;
      if (normal(pd, pb, pc).dot(m) <= 0 || normal(pc, pa, pd).dot(m) <= 0)
        continue;
      // Flip: (a, b, c), (b, a, d) -> (d, b, c), (c, a, d).
      F.row(f0) << d, b, c;
      F.row(f1) << c, a, d;
      edges.erase(it);
      edges[key(c, d)] = {f0, f1};
      for (auto [x, y, from, to] : {std::array{b, d, f1, f0}, std::array{a, c, f0, f1}}) {
        auto& e = edges.at(key(x, y));
        for (int& g : e)
          if (g == from) {
            g = to;
            break;
          }
      }
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
