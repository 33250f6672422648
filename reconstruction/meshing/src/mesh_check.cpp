#include "interlin/reconstruction/meshing/mesh_check.h"

#include "min_angle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

namespace {

struct UnionFind {
  std::vector<long> parent;
  explicit UnionFind(long n) : parent(std::size_t(n)) {
    std::iota(parent.begin(), parent.end(), 0L);
  }
  long find(long x) {
    while (parent[std::size_t(x)] != x) {
      parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
      x = parent[std::size_t(x)];
    }
    return x;
  }
  bool unite(long a, long b) {
    a = find(a);
    b = find(b);
    if (a == b)
      return false;
    parent[std::size_t(std::max(a, b))] = std::min(a, b);
    return true;
  }
};

std::uint64_t edge_key(long a, long b) {
  return (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
}

// The shapes and the face indices (each in [0, #V)).
void check_mesh_input(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if (V.cols() != 3 || F.cols() != 3)
    throw std::invalid_argument("check_mesh: V and F must have 3 columns, got " +
                                std::to_string(V.cols()) + " and " + std::to_string(F.cols()));
  const long nv = long(V.rows()), nf = long(F.rows());
  if (nv >= (1L << 32))
    throw std::invalid_argument("check_mesh: too many vertices");
  for (long f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j)
      if (F(f, j) < 0 || F(f, j) >= nv)
        throw std::invalid_argument("check_mesh: face " + std::to_string(f) + " has vertex index " +
                                    std::to_string(F(f, j)) + " outside [0, " + std::to_string(nv) +
                                    ")");
}

// Geometry: area, volume (divergence theorem about the box centre), angles, aspect ratios,
// degenerate faces.
void measure_faces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, MeshReport& r) {
  const Eigen::RowVector3d origin =
      V.rows() > 0 ? Eigen::RowVector3d(0.5 * (V.colwise().minCoeff() + V.colwise().maxCoeff()))
                   : Eigen::RowVector3d::Zero();
  double min_angle = M_PI, max_aspect = 0, volume = 0, area = 0;
  bool any_good = false;
  for (long f = 0; f < long(F.rows()); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)) - origin, b = V.row(F(f, 1)) - origin,
                          c = V.row(F(f, 2)) - origin;
    volume += a.dot(b.cross(c));
    const double twice_area = (b - a).cross(c - a).norm();
    area += 0.5 * twice_area;
    const double l2max =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const bool repeated = F(f, 0) == F(f, 1) || F(f, 1) == F(f, 2) || F(f, 2) == F(f, 0);
    if (repeated || !(twice_area > 1e-12 * l2max)) {
      ++r.degenerate_faces;
      continue;
    }
    any_good = true;
    max_aspect = std::max(max_aspect, std::sqrt(3.0) * l2max / (2.0 * twice_area));
    min_angle = std::min(min_angle, detail::min_angle(a, b, c));
  }
  r.area = area;
  r.volume = volume / 6.0;
  r.min_angle_deg = any_good ? min_angle * 180.0 / M_PI : 0.0;
  r.max_aspect_ratio = any_good ? max_aspect : 0.0;
}

// Edges: boundary and non-manifold edges, orientation, Euler characteristic and connected
// components, from the half-edges (key, direction) sorted; a direction bit of 0 means the face
// runs min -> max.
void count_edges(const Eigen::MatrixXi& F, long nv, MeshReport& r) {
  const long nf = long(F.rows());
  std::vector<std::uint64_t> half(std::size_t(3 * nf));
  for (long f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j) {
      const long a = F(f, j), b = F(f, (j + 1) % 3);
      half[std::size_t(3 * f + j)] = (edge_key(a, b) << 1) | std::uint64_t(a > b);
    }
  std::sort(half.begin(), half.end());
  long edges = 0;
  bool consistent = true;
  UnionFind graph(nv);
  for (std::size_t s = 0; s < half.size();) {
    std::size_t e = s;
    long forward = 0;
    while (e < half.size() && (half[e] >> 1) == (half[s] >> 1)) {
      forward += (half[e] & 1) == 0;
      ++e;
    }
    const long count = long(e - s);
    ++edges;
    if (count == 1)
      ++r.boundary_edges;
    else if (count > 2)
      ++r.nonmanifold_edges;
    if (count > 2 || (count == 2 && forward != 1))
      consistent = false;
    const std::uint64_t key = half[s] >> 1;
    graph.unite(long(key >> 32), long(key & 0xffffffffu));
    s = e;
  }
  r.consistently_oriented = consistent && nf > 0;
  r.euler = nv - edges + nf;
  for (long i = 0; i < nv; ++i)
    r.components += graph.find(i) == i;
}

// Vertex fans: corners (f, j) at the same vertex are linked across each edge (v, w) that has
// exactly two faces; a vertex is non-manifold when its corners form more than one fan.
long count_nonmanifold_vertices(const Eigen::MatrixXi& F) {
  const long nf = long(F.rows());
  struct Spoke {
    long v, w, corner;
  };
  std::vector<Spoke> spokes;
  spokes.reserve(std::size_t(6 * nf));
  for (long f = 0; f < nf; ++f)
    for (int j = 0; j < 3; ++j) {
      spokes.push_back({F(f, j), F(f, (j + 1) % 3), 3 * f + j});
      spokes.push_back({F(f, j), F(f, (j + 2) % 3), 3 * f + j});
    }
  std::sort(spokes.begin(), spokes.end(), [](const Spoke& x, const Spoke& y) {
    return x.v != y.v ? x.v < y.v : x.w != y.w ? x.w < y.w : x.corner < y.corner;
  });
  UnionFind corners(3 * nf);
  for (std::size_t s = 0; s < spokes.size();) {
    std::size_t e = s;
    while (e < spokes.size() && spokes[e].v == spokes[s].v && spokes[e].w == spokes[s].w)
      ++e;
    if (e - s == 2)
      corners.unite(spokes[s].corner, spokes[s + 1].corner);
    s = e;
  }
  long nonmanifold = 0;
  for (std::size_t s = 0; s < spokes.size();) {
    std::size_t e = s;
    long last_root = -1;
    std::vector<long> roots;
    while (e < spokes.size() && spokes[e].v == spokes[s].v) {
      const long root = corners.find(spokes[e].corner);
      if (root != last_root)
        roots.push_back(root);
      last_root = root;
      ++e;
    }
    std::sort(roots.begin(), roots.end());
    nonmanifold += std::unique(roots.begin(), roots.end()) - roots.begin() > 1;
    s = e;
  }
  return nonmanifold;
}

} // namespace

bool MeshReport::watertight() const {
  return faces > 0 && boundary_edges == 0 && nonmanifold_edges == 0 && nonmanifold_vertices == 0 &&
         consistently_oriented && degenerate_faces == 0;
}

MeshReport check_mesh(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  check_mesh_input(V, F);
  MeshReport r;
  r.vertices = long(V.rows());
  r.faces = long(F.rows());
  measure_faces(V, F, r);
  count_edges(F, r.vertices, r);
  r.nonmanifold_vertices = count_nonmanifold_vertices(F);
  std::vector<char> used(std::size_t(r.vertices), 0);
  for (Eigen::Index i = 0; i < F.size(); ++i)
    used[std::size_t(F.data()[i])] = 1;
  const bool all_used = std::all_of(used.begin(), used.end(), [](char c) { return c != 0; });
  // Genus from Euler's formula V - E + F = 2 (C - g), only for closed oriented 2-manifolds.
  if (r.boundary_edges == 0 && r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0 &&
      r.consistently_oriented && all_used)
    r.genus = (2 * r.components - r.euler) / 2;
  return r;
}

} // namespace interlin
