// Seed 003, digest §5.1: the projection method. Cells inside the body, cleanup of touching
// configurations, boundary facets, projection of the boundary nodes along smoothed normals.
#include "interlin/reconstruction/meshing/boundary_mesh.h"

#include "interlin/reconstruction/meshing/project_to_zero.h"

#include "parallel.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

namespace {

struct UnionFind {
  std::vector<long> parent;
  explicit UnionFind(long n) : parent(static_cast<size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0L);
  }
  long find(long x) {
    while (parent[size_t(x)] != x)
      x = parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
    return x;
  }
  void unite(long a, long b) {
    a = find(a), b = find(b);
    if (a != b)
      parent[size_t(std::max(a, b))] = std::min(a, b);
  }
};

// Cube corner c = x + 2y + 4z. Kuhn split: tetrahedron t follows the axis order kPerm[t] from
// corner 0 to corner 7; all six share the diagonal 0-7, and neighbouring cubes match.
constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

struct CellShapes {
  std::array<std::array<int, 4>, 6> tet; // corners, positively oriented
  // Outward facets of a tetrahedron (local vertex positions 0..3) and of a cube (corners).
  static constexpr int tet_face[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::array<std::array<int, 4>, 6> cube_face; // face 2a + s, outward, counter-clockwise
  CellShapes() {
    auto pt = [](int c) { return Eigen::Vector3d(c & 1, (c >> 1) & 1, c >> 2); };
    for (int t = 0; t < 6; ++t) {
      const int c1 = 1 << kPerm[t][0], c2 = c1 | 1 << kPerm[t][1];
      tet[size_t(t)] = {0, c1, c2, 7};
      if ((pt(c1) - pt(0)).cross(pt(c2) - pt(0)).dot(pt(7) - pt(0)) < 0)
        std::swap(tet[size_t(t)][1], tet[size_t(t)][2]);
    }
    const int cyc[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int f = 0; f < 6; ++f) {
      const int a = f / 2, s = f & 1, b = a == 0 ? 1 : 0, d = a == 2 ? 1 : 2;
      std::array<int, 4> q;
      for (int i = 0; i < 4; ++i)
        q[size_t(i)] = (s << a) | (cyc[i][0] << b) | (cyc[i][1] << d);
      const Eigen::Vector3d n = (pt(q[1]) - pt(q[0])).cross(pt(q[3]) - pt(q[0]));
      if (n(a) * (2 * s - 1) < 0)
        std::swap(q[1], q[3]);
      cube_face[size_t(f)] = q;
    }
  }
};

const CellShapes& shapes() {
  static const CellShapes s;
  return s;
}

// The background: cells, their nodes, the cells at a node.
struct Background {
  const RegularGrid& g;
  bool tets;
  long cx, cy, cz; // cubes per axis
  Background(const RegularGrid& grid, bool t)
      : g(grid), tets(t), cx(grid.nodes(0) - 1), cy(grid.nodes(1) - 1), cz(grid.nodes(2) - 1) {}
  long cubes() const { return cx * cy * cz; }
  long cells() const { return tets ? 6 * cubes() : cubes(); }
  int corners() const { return tets ? 4 : 8; }
  // Grid node of corner c of cube q.
  long cube_node(long q, int c) const {
    const long i = q % cx, j = (q / cx) % cy, k = q / (cx * cy);
    return g.index(i + (c & 1), j + ((c >> 1) & 1), k + (c >> 2));
  }
  long node(long cell, int v) const {
    return tets ? cube_node(cell / 6, shapes().tet[size_t(cell % 6)][size_t(v)])
                : cube_node(cell, v);
  }
  // Cells containing grid node n.
  void cells_at(long n, std::vector<long>& out) const {
    out.clear();
    const long nx = g.nodes(0), ny = g.nodes(1);
    const long i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
    for (int c = 0; c < 8; ++c) {
      const long qi = i - (c & 1), qj = j - ((c >> 1) & 1), qk = k - (c >> 2);
      if (qi < 0 || qj < 0 || qk < 0 || qi >= cx || qj >= cy || qk >= cz)
        continue;
      const long q = qi + cx * (qj + cy * qk);
      if (!tets) {
        out.push_back(q);
        continue;
      }
      for (int t = 0; t < 6; ++t)
        for (int v = 0; v < 4; ++v)
          if (shapes().tet[size_t(t)][size_t(v)] == c)
            out.push_back(6 * q + t);
    }
  }
};

struct Facet {
  std::array<long, 4> v; // grid nodes, outward; v[3] = -1 for triangles
};

// Facets of exactly one alive cell. Only facets with a node next to a dead cell (or the grid
// border) can be such facets; `edge_node` marks those nodes. Layers of cubes in parallel, output
// in cube order.
std::vector<Facet> boundary_facets(const Background& bg, const std::vector<char>& alive,
                                   const std::vector<char>& edge_node, int threads) {
  const CellShapes& sh = shapes();
  auto touches = [&](long cell) {
    for (int v = 0; v < bg.corners(); ++v)
      if (edge_node[size_t(bg.node(cell, v))])
        return true;
    return false;
  };
  const long layer = bg.cx * bg.cy;
  std::vector<std::vector<Facet>> per_layer(static_cast<size_t>(bg.cz));
  if (!bg.tets) {
    detail::parallel_for(bg.cz, threads, [&](long k, int) {
      std::vector<Facet>& out = per_layer[size_t(k)];
      for (long q = k * layer; q < (k + 1) * layer; ++q) {
        if (!alive[size_t(q)] || !touches(q))
          continue;
        const long i = q % bg.cx, j = (q / bg.cx) % bg.cy;
        const long c[3] = {i, j, k}, n[3] = {bg.cx, bg.cy, bg.cz};
        const long stride[3] = {1, bg.cx, bg.cx * bg.cy};
        for (int f = 0; f < 6; ++f) {
          const int a = f / 2, s = f & 1;
          const long nb = c[a] + (s ? 1 : -1);
          if (nb >= 0 && nb < n[a] && alive[size_t(q + (s ? 1 : -1) * stride[a])])
            continue;
          Facet x;
          for (int m = 0; m < 4; ++m)
            x.v[size_t(m)] = bg.cube_node(q, sh.cube_face[size_t(f)][size_t(m)]);
          out.push_back(x);
        }
      }
    });
    std::vector<Facet> out;
    for (const auto& l : per_layer)
      out.insert(out.end(), l.begin(), l.end());
    return out;
  }
  // Tetrahedra: facets of the candidate cells keyed by their sorted nodes; facets seen once.
  struct Keyed {
    std::array<long, 3> key;
    Facet f;
  };
  std::vector<std::vector<Keyed>> keyed(static_cast<size_t>(bg.cz));
  detail::parallel_for(bg.cz, threads, [&](long k, int) {
    for (long t = 6 * k * layer; t < 6 * (k + 1) * layer; ++t) {
      if (!alive[size_t(t)] || !touches(t))
        continue;
      for (const auto& tf : CellShapes::tet_face) {
        Facet x{{bg.node(t, tf[0]), bg.node(t, tf[1]), bg.node(t, tf[2]), -1}};
        if (!edge_node[size_t(x.v[0])] && !edge_node[size_t(x.v[1])] && !edge_node[size_t(x.v[2])])
          continue; // all cells at these nodes are alive: an interior facet
        std::array<long, 3> key = {x.v[0], x.v[1], x.v[2]};
        std::sort(key.begin(), key.end());
        keyed[size_t(k)].push_back({key, x});
      }
    }
  });
  std::vector<Keyed> all;
  for (const auto& l : keyed)
    all.insert(all.end(), l.begin(), l.end());
  std::sort(all.begin(), all.end(), [](const Keyed& a, const Keyed& b) { return a.key < b.key; });
  std::vector<Facet> out;
  for (size_t s = 0; s < all.size();) {
    size_t e = s;
    while (e < all.size() && all[e].key == all[s].key)
      ++e;
    if (e - s == 1)
      out.push_back(all[s].f);
    s = e;
  }
  return out;
}

// Nodes where the facets are not a 2-manifold: an edge with more than two facets (both ends), or
// a node whose facets form more than one fan.
std::vector<long> nonmanifold_nodes(const std::vector<Facet>& facets) {
  struct Spoke {
    long v, w, corner;
  };
  std::vector<Spoke> spokes;
  long corners = 0;
  for (const Facet& f : facets) {
    const int n = f.v[3] < 0 ? 3 : 4;
    for (int j = 0; j < n; ++j, ++corners) {
      spokes.push_back({f.v[size_t(j)], f.v[size_t((j + 1) % n)], corners});
      spokes.push_back({f.v[size_t(j)], f.v[size_t((j + n - 1) % n)], corners});
    }
  }
  std::sort(spokes.begin(), spokes.end(), [](const Spoke& a, const Spoke& b) {
    return a.v != b.v ? a.v < b.v : a.w != b.w ? a.w < b.w : a.corner < b.corner;
  });
  UnionFind fans(corners);
  std::vector<long> bad;
  for (size_t s = 0; s < spokes.size();) {
    size_t e = s;
    while (e < spokes.size() && spokes[e].v == spokes[s].v && spokes[e].w == spokes[s].w)
      ++e;
    if (e - s == 2)
      fans.unite(spokes[s].corner, spokes[s + 1].corner);
    else if (e - s > 2) // the edge (v, w) has e - s facets; w is recorded from its own spokes
      bad.push_back(spokes[s].v);
    s = e;
  }
  for (size_t s = 0; s < spokes.size();) {
    size_t e = s;
    std::vector<long> roots;
    while (e < spokes.size() && spokes[e].v == spokes[s].v)
      roots.push_back(fans.find(spokes[e++].corner));
    std::sort(roots.begin(), roots.end());
    if (std::unique(roots.begin(), roots.end()) - roots.begin() > 1)
      bad.push_back(spokes[s].v);
    s = e;
  }
  std::sort(bad.begin(), bad.end());
  bad.erase(std::unique(bad.begin(), bad.end()), bad.end());
  return bad;
}

// Whether two boundary facets at grid node n face opposite ways (unit normals with a dot product
// below -0.8, i.e. more than 143 degrees apart): the alive cells are one cell thin there.
// Hexahedral facets meet at 90 or 180 degrees, Kuhn tetrahedra's also at 135 (a wedge one
// diagonal thick, which a boundary layer still handles).
bool two_sided(const Background& bg, const std::vector<char>& alive, long n,
               std::vector<long>& at) {
  constexpr double kOpposite = -0.8;
  bg.cells_at(n, at);
  std::vector<Eigen::Vector3d> normals;
  const RegularGrid& g = bg.g;
  const long nx = g.nodes(0), ny = g.nodes(1);
  auto point = [&](long m) { return g.point(m % nx, (m / nx) % ny, m / (nx * ny)); };
  if (!bg.tets) {
    const long i = n % nx, j = (n / nx) % ny, k = n / (nx * ny);
    const long node_c[3] = {i, j, k}, cubes[3] = {bg.cx, bg.cy, bg.cz};
    for (long q : at) {
      if (!alive[size_t(q)])
        continue;
      const long qc[3] = {q % bg.cx, (q / bg.cx) % bg.cy, q / (bg.cx * bg.cy)};
      const long stride[3] = {1, bg.cx, bg.cx * bg.cy};
      for (int a = 0; a < 3; ++a) {
        const int s = node_c[a] == qc[a] ? 0 : 1; // the face of q through n along axis a
        const long nb = qc[a] + (s ? 1 : -1);
        if (nb >= 0 && nb < cubes[a] && alive[size_t(q + (s ? 1 : -1) * stride[a])])
          continue;
        normals.push_back(Eigen::Vector3d::Unit(a) * (s ? 1.0 : -1.0));
      }
    }
  } else {
    struct Face {
      std::array<long, 3> key;
      Eigen::Vector3d normal;
    };
    std::vector<Face> faces;
    for (long t : at) {
      if (!alive[size_t(t)])
        continue;
      for (const auto& tf : CellShapes::tet_face) {
        const long a = bg.node(t, tf[0]), b = bg.node(t, tf[1]), c = bg.node(t, tf[2]);
        if (a != n && b != n && c != n)
          continue;
        std::array<long, 3> key = {a, b, c};
        std::sort(key.begin(), key.end());
        faces.push_back({key, (point(b) - point(a)).cross(point(c) - point(a)).normalized()});
      }
    }
    std::sort(faces.begin(), faces.end(),
              [](const Face& x, const Face& y) { return x.key < y.key; });
    for (size_t f = 0; f < faces.size(); ++f) // faces of one alive tetrahedron only
      if ((f == 0 || faces[f - 1].key != faces[f].key) &&
          (f + 1 == faces.size() || faces[f + 1].key != faces[f].key))
        normals.push_back(faces[f].normal);
  }
  for (size_t a = 0; a < normals.size(); ++a)
    for (size_t b = a + 1; b < normals.size(); ++b)
      if (normals[a].dot(normals[b]) < kOpposite)
        return true;
  return false;
}

// Removes the alive cells at two-sided nodes, rechecking the nodes of removed cells until none
// is left (the one-cell-thin parts erode away). Returns the number of cells removed.
long erode_thin_parts(const Background& bg, std::vector<char>& alive,
                      const std::vector<char>& edge_node) {
  std::vector<long> work, at, at2;
  std::vector<char> queued(edge_node.size(), 0);
  for (size_t n = 0; n < edge_node.size(); ++n)
    if (edge_node[n])
      work.push_back(long(n)), queued[n] = 1;
  long removed = 0;
  while (!work.empty()) {
    const long n = work.back();
    work.pop_back();
    queued[size_t(n)] = 0;
    if (!two_sided(bg, alive, n, at))
      continue;
    bg.cells_at(n, at2);
    for (long c : at2) {
      if (!alive[size_t(c)])
        continue;
      alive[size_t(c)] = 0;
      ++removed;
      for (int v = 0; v < bg.corners(); ++v) {
        const long m = bg.node(c, v);
        if (!queued[size_t(m)])
          work.push_back(m), queued[size_t(m)] = 1;
      }
    }
  }
  return removed;
}

} // namespace

BoundaryMesh boundary_mesh(const RegularGrid& g, const Eigen::VectorXd& S,
                           const BoundaryMeshOptions& o) {
  if ((g.nodes < 2).any())
    throw std::invalid_argument("boundary_mesh: the grid needs at least 2 nodes per axis");
  if (S.size() != g.size())
    throw std::invalid_argument("boundary_mesh: " + std::to_string(S.size()) +
                                " values for a grid of " + std::to_string(g.size()) + " nodes");
  if (!(o.epsilon >= 0))
    throw std::invalid_argument("boundary_mesh: epsilon must be >= 0");
  const Background bg(g, o.cells == BackgroundCells::tetrahedra);
  const int threads = detail::resolve_threads(o.threads);
  BoundaryMesh out;
  std::vector<char> in(size_t(g.size()));
  for (long n = 0; n < g.size(); ++n) {
    in[size_t(n)] = o.rule == ZeroRule::strict ? S(n) > o.epsilon : S(n) >= -o.epsilon;
    out.inside_nodes += in[size_t(n)];
  }
  // Stage 1: cells with all nodes inside (seed 003 §8.2 step 2: parts of the background in
  // parallel, here layers of cubes).
  std::vector<char> alive(size_t(bg.cells()));
  const long per_layer = bg.cells() / bg.cz;
  detail::parallel_for(bg.cz, threads, [&](long k, int) {
    for (long c = k * per_layer; c < (k + 1) * per_layer; ++c) {
      bool all = true;
      for (int v = 0; v < bg.corners() && all; ++v)
        all = in[size_t(bg.node(c, v))] != 0;
      alive[size_t(c)] = all;
    }
  });
  std::vector<long> around;
  std::vector<char> edge_node(size_t(g.size()), 0);
  std::vector<Facet> facets;
  const long slice = long(g.nodes(0)) * g.nodes(1);
  for (;;) {
    // Nodes next to a dead cell or the grid border.
    detail::parallel_for(g.nodes(2), threads, [&](long k, int) {
      std::vector<long> at;
      for (long n = k * slice; n < (k + 1) * slice; ++n) {
        if (!in[size_t(n)]) {
          edge_node[size_t(n)] = 0;
          continue;
        }
        bg.cells_at(n, at);
        bool dead = long(at.size()) < (bg.tets ? 24 : 8);
        for (long c : at)
          dead = dead || !alive[size_t(c)];
        edge_node[size_t(n)] = dead;
      }
    });
    facets = boundary_facets(bg, alive, edge_node, threads);
    // Stage 2: touching configurations.
    const std::vector<long> bad = nonmanifold_nodes(facets);
    if (bad.empty()) {
      const long thinned = o.thin_cleanup ? erode_thin_parts(bg, alive, edge_node) : 0;
      out.thinned += thinned;
      if (thinned == 0)
        break;
      continue;
    }
    std::vector<long> remove;
    for (long n : bad) {
      bg.cells_at(n, around);
      long best = -1, best_power = 0;
      for (long c : around) {
        if (!alive[size_t(c)])
          continue;
        long power = 0;
        std::vector<long> at;
        for (int v = 0; v < bg.corners(); ++v) {
          bg.cells_at(bg.node(c, v), at);
          for (long x : at)
            power += alive[size_t(x)];
        }
        if (best < 0 || power < best_power)
          best = c, best_power = power;
      }
      if (best >= 0)
        remove.push_back(best);
    }
    std::sort(remove.begin(), remove.end());
    remove.erase(std::unique(remove.begin(), remove.end()), remove.end());
    if (remove.empty())
      throw std::logic_error("boundary_mesh: a non-manifold node without alive cells");
    for (long c : remove)
      alive[size_t(c)] = 0;
    out.removed += long(remove.size());
  }
  for (long c = 0; c < bg.cells(); ++c)
    if (alive[size_t(c)])
      out.kept.push_back(c);
  out.cells = long(out.kept.size());
  // Vertices: the facets' nodes in increasing order.
  std::vector<long> nodes;
  for (const Facet& f : facets)
    for (long v : f.v)
      if (v >= 0)
        nodes.push_back(v);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  out.V.resize(long(nodes.size()), 3);
  out.node.resize(long(nodes.size()));
  const long nx = g.nodes(0), ny = g.nodes(1);
  for (size_t r = 0; r < nodes.size(); ++r) {
    const long n = nodes[r];
    out.V.row(long(r)) = g.point(n % nx, (n / nx) % ny, n / (nx * ny)).transpose();
    out.node(long(r)) = int(n);
  }
  const int per = bg.tets ? 3 : 4;
  out.P.resize(long(facets.size()), per);
  for (size_t f = 0; f < facets.size(); ++f)
    for (int j = 0; j < per; ++j)
      out.P(long(f), j) =
          int(std::lower_bound(nodes.begin(), nodes.end(), facets[f].v[size_t(j)]) - nodes.begin());
  return out;
}

BoundaryMesh boundary_mesh(const ImplicitFunction& f, const RegularGrid& g,
                           const BoundaryMeshOptions& o) {
  Eigen::VectorXd S;
  sample_grid(f, g, S, o.threads);
  BoundaryMesh m = boundary_mesh(g, S, o);
  if (o.project)
    project_boundary_nodes(f, g, S, m, o);
  return m;
}

void project_boundary_nodes(const ImplicitFunction& f, const RegularGrid& g,
                            const Eigen::VectorXd& S, BoundaryMesh& m,
                            const BoundaryMeshOptions& o) {
  if (m.V.rows() == 0)
    return;
  const long nv = m.V.rows(), per = m.P.cols();
  // Vertex normals: unit facet normals at each corner, summed (seed 003 code).
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(nv, 3);
  std::vector<std::vector<int>> nbr(static_cast<size_t>(nv));
  for (long f = 0; f < m.P.rows(); ++f)
    for (long j = 0; j < per; ++j) {
      const int a = m.P(f, j), next = m.P(f, (j + 1) % per), prev = m.P(f, (j + per - 1) % per);
      const Eigen::Vector3d e1 = (m.V.row(next) - m.V.row(a)).transpose(),
                            e2 = (m.V.row(prev) - m.V.row(a)).transpose();
      const Eigen::Vector3d n = e1.cross(e2);
      if (n.norm() > 0)
        N.row(a) += n.normalized().transpose();
      nbr[size_t(a)].push_back(next);
      nbr[size_t(a)].push_back(prev);
    }
  for (auto& l : nbr) {
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  }
  auto normalised = [](Eigen::RowVector3d r) -> Eigen::RowVector3d {
    const double len = r.norm();
    return len > 0 ? Eigen::RowVector3d(r / len) : r;
  };
  for (long v = 0; v < nv; ++v)
    N.row(v) = normalised(N.row(v));
  const int sweeps = o.normal_sweeps >= 0 ? o.normal_sweeps : per == 3 ? 10 : 4;
  for (int s = 0; s < sweeps; ++s)
    for (long v = 0; v < nv; ++v) { // in place, as the seed code does
      Eigen::RowVector3d sum = N.row(v);
      for (int w : nbr[size_t(v)])
        sum += N.row(w);
      N.row(v) = normalised(sum);
    }
  // Nodes already on the surface (|F| <= epsilon) stay.
  std::vector<long> move;
  for (long v = 0; v < nv; ++v)
    if (!(std::abs(S(m.node(v))) <= o.epsilon))
      move.push_back(v);
  Eigen::MatrixXd P(long(move.size()), 3), D(long(move.size()), 3);
  for (size_t r = 0; r < move.size(); ++r) {
    P.row(long(r)) = m.V.row(move[r]);
    D.row(long(r)) = N.row(move[r]);
  }
  const Eigen::VectorXd h =
      Eigen::VectorXd::Constant(long(move.size()), 0.5 * g.spacing.minCoeff());
  RootOptions ro;
  ro.threads = o.threads;
  std::vector<char> ok;
  project_along(f, P, D, h, ro, &ok, o.reach, o.scan_step);
  // Nodes whose normal scan found nothing: the gradient walk, in steps of h, as far.
  std::vector<long> missed;
  for (size_t r = 0; r < move.size(); ++r)
    if (!ok[r])
      missed.push_back(long(r));
  if (!missed.empty()) {
    Eigen::MatrixXd Q(long(missed.size()), 3);
    for (size_t k = 0; k < missed.size(); ++k)
      Q.row(long(k)) = P.row(missed[k]);
    const int steps = int(std::max(1.0, std::min(o.reach, 1e6)));
    m.unprojected = project_by_gradient_walk(
        f, Q, Eigen::VectorXd::Constant(Q.rows(), h.size() ? h(0) : 1), steps, ro);
    for (size_t k = 0; k < missed.size(); ++k)
      P.row(missed[k]) = Q.row(long(k));
  }
  for (size_t r = 0; r < move.size(); ++r)
    m.V.row(move[r]) = P.row(long(r));
}

Eigen::MatrixXi background_cell_nodes(const RegularGrid& g, BackgroundCells cells,
                                      const std::vector<long>& ids) {
  const Background bg(g, cells == BackgroundCells::tetrahedra);
  // Cube corner c = x + 2y + 4z in VTK hexahedron order.
  constexpr int kVtkCorner[8] = {0, 1, 3, 2, 4, 5, 7, 6};
  Eigen::MatrixXi C(long(ids.size()), bg.corners());
  for (size_t r = 0; r < ids.size(); ++r) {
    if (ids[r] < 0 || ids[r] >= bg.cells())
      throw std::invalid_argument("background_cell_nodes: cell id out of range");
    for (int v = 0; v < bg.corners(); ++v)
      C(long(r), v) = int(bg.tets ? bg.node(ids[r], v) : bg.cube_node(ids[r], kVtkCorner[v]));
  }
  return C;
}

Eigen::MatrixXi triangulate_quads(const Eigen::MatrixXd& V, const Eigen::MatrixXi& Q) {
  if (Q.cols() != 4 || V.cols() != 3)
    throw std::invalid_argument("triangulate_quads: Q must be #Q by 4 and V #V by 3");
  Eigen::MatrixXi T(2 * Q.rows(), 3);
  for (long q = 0; q < Q.rows(); ++q) {
    for (int j = 0; j < 4; ++j)
      if (Q(q, j) < 0 || Q(q, j) >= V.rows())
        throw std::invalid_argument("triangulate_quads: index out of range in quad " +
                                    std::to_string(q));
    const int a = Q(q, 0), b = Q(q, 1), c = Q(q, 2), d = Q(q, 3);
    if ((V.row(a) - V.row(c)).squaredNorm() <= (V.row(b) - V.row(d)).squaredNorm())
      T.row(2 * q) << a, b, c, T.row(2 * q + 1) << a, c, d;
    else
      T.row(2 * q) << a, b, d, T.row(2 * q + 1) << b, c, d;
  }
  return T;
}

} // namespace interlin
