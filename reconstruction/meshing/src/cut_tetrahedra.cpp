// The background tetrahedra clipped at F = 0 (marching tetrahedra on the volume), the boundary of
// interlin's default tetrahedral mesh (seed 003 §6.2's grid and smoothing, without its projected
// layer).
#include "interlin/reconstruction/meshing/cut_tetrahedra.h"

#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/project_to_zero.h"

#include "parallel.h"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>
#include <vector>

namespace interlin {

namespace {

using Tet = std::array<long, 4>;    // extended ids: lattice node n, or N + e for the cut on edge e
using Edge = std::pair<long, long>; // (inside node, outside node)

// Node class: 1 inside, 0 on the surface, -1 outside.
int node_class(double s, double epsilon) {
  return s > epsilon ? 1 : s < -epsilon ? -1 : 0;
}

// The 3 tetrahedra of the prism with bottom p[0..2] and top p[3..5] (lateral edges p[i] p[i+3]):
// each quadrilateral is cut along the diagonal from its smallest id, so prisms that share a
// quadrilateral agree (Dompierre et al.; the rule never makes the three diagonals cyclic).
void split_prism(const long p[6], std::vector<Tet>& out) {
  const int m = int(std::min_element(p, p + 6) - p);
  const int base = m < 3 ? 0 : 3, other = 3 - base, r = m % 3;
  long v[6];
  for (int i = 0; i < 3; ++i) {
    v[i] = p[base + (r + i) % 3];
    v[3 + i] = p[other + (r + i) % 3];
  }
  // v[0] is the smallest: both its quadrilaterals are cut from it, leaving the top triangle with
  // v[0] and the pyramid v[0] + (v1 v2 v5 v4), cut from its own smallest corner.
  out.push_back({v[0], v[3], v[4], v[5]});
  if (std::min(v[1], v[5]) < std::min(v[2], v[4])) {
    out.push_back({v[0], v[1], v[2], v[5]});
    out.push_back({v[0], v[1], v[5], v[4]});
  } else {
    out.push_back({v[0], v[1], v[2], v[4]});
    out.push_back({v[0], v[4], v[2], v[5]});
  }
}

// The pieces of one background tetrahedron n[4] (grid nodes) with classes c[4] and at least one
// inside node. cut(a, b) is the id of the point on edge (a inside, b outside); a surface node is
// its own point on every edge to the outside.
template <class Cut>
void clip(const Tet& n, const int c[4], Cut&& cut, std::vector<Tet>& out) {
  int keep[4], drop[4], nk = 0, nd = 0;
  for (int j = 0; j < 4; ++j)
    (c[j] >= 0 ? keep[nk++] : drop[nd++]) = j;
  auto at = [&](int k, int d) { // the point on the edge from keep[k] to drop[d]
    return c[keep[k]] == 0 ? n[keep[k]] : cut(n[keep[k]], n[drop[d]]);
  };
  if (nk == 1) {
    out.push_back({n[keep[0]], at(0, 0), at(0, 1), at(0, 2)});
  } else if (nk == 2) {
    const long p[6] = {n[keep[0]], at(0, 0), at(0, 1), n[keep[1]], at(1, 0), at(1, 1)};
    split_prism(p, out);
  } else {
    const long p[6] = {n[keep[0]], n[keep[1]], n[keep[2]], at(0, 0), at(1, 0), at(2, 0)};
    split_prism(p, out);
  }
}

constexpr long kBatch = 8192; // edges or nodes per task

// The lattice: its nodes (grid nodes, then BCC's cube centres), background tetrahedra by cube
// layer, and the node layers that keep the cut edges sorted.
struct Background {
  const RegularGrid& g;
  const RegularGrid c; // the cube centres
  const bool bcc;
  const long nx, ny, cx, cy, cz, G, N; // G grid nodes, N lattice nodes

  Background(const RegularGrid& grid, Lattice l)
      : g(grid), c(cube_centres(grid)), bcc(l == Lattice::bcc), nx(g.nodes(0)), ny(g.nodes(1)),
        cx(nx - 1), cy(ny - 1), cz(g.nodes(2) - 1), G(g.size()), N(bcc ? G + c.size() : G) {}

  Eigen::Vector3d point(long n) const {
    if (n < G)
      return g.point(n % nx, (n / nx) % ny, n / (nx * ny));
    n -= G;
    return c.point(n % cx, (n / cx) % cy, n / (cx * cy));
  }
  // The list of cube layer k's cut edges that node n belongs to: grid nodes 0 (layer k) or 1
  // (k + 1), cube centres 2 (k) or 3 (k + 1).
  int list(long n, long k) const {
    return n < G ? int(n >= (k + 1) * nx * ny) : 2 + int(n - G >= (k + 1) * cx * cy);
  }
  // Isosurface stuffing's warp threshold on edge (a, b), a fraction of its length: BCC alpha_long
  // on edges of length h (grid-grid, centre-centre), alpha_short on centre-corner edges.
  double alpha(long a, long b) const { return !bcc ? 0.2 : (a < G) == (b < G) ? 0.24999 : 0.41189; }
  // The positive background tetrahedra of cube layer k with a node inside (by cls) among their
  // cube's corners (Kuhn) or their face's corners and two cube centres (BCC).
  template <class Class>
  std::vector<Tet> tetrahedra(long k, Class&& cls) const {
    return bcc ? bcc_tetrahedra(k, cls) : kuhn_tetrahedra(k, cls);
  }

  template <class Class>
  std::vector<Tet> kuhn_tetrahedra(long k, Class&& cls) const {
    std::vector<long> ids;
    for (long q = k * cx * cy; q < (k + 1) * cx * cy; ++q) {
      const long i = q % cx, j = (q / cx) % cy;
      bool any = false;
      for (int corner = 0; corner < 8 && !any; ++corner)
        any = cls(g.index(i + (corner & 1), j + ((corner >> 1) & 1), k + (corner >> 2))) > 0;
      for (long t = 0; any && t < 6; ++t)
        ids.push_back(6 * q + t);
    }
    const Eigen::MatrixXi T = background_cell_nodes(g, BackgroundCells::tetrahedra, ids);
    std::vector<Tet> out(size_t(T.rows()));
    for (long r = 0; r < T.rows(); ++r)
      out[size_t(r)] = {T(r, 0), T(r, 1), T(r, 2), T(r, 3)};
    return out;
  }

  // Cube (i, j, k) and its neighbour along axis d share the face at node i_d + 1, whose corners
  // a0..a3 run counter-clockwise about axis d: the tetrahedra (centre, centre', a_m, a_m+1) are
  // positive ((c' - c) x (a_m - c) . (a_m+1 - c) = h e_d . (a_m - p) x (a_m+1 - p) > 0).
  template <class Class>
  std::vector<Tet> bcc_tetrahedra(long k, Class&& cls) const {
    constexpr int kU[4] = {0, 1, 1, 0}, kV[4] = {0, 0, 1, 1};
    const long counts[3] = {cx, cy, cz};
    std::vector<Tet> out;
    for (long j = 0; j < cy; ++j)
      for (long i = 0; i < cx; ++i)
        for (int d = 0; d < 3; ++d) {
          long at[3] = {i, j, k};
          if (at[d] + 1 >= counts[d])
            continue;
          const long c0 = G + c.index(at[0], at[1], at[2]);
          ++at[d];
          const long c1 = G + c.index(at[0], at[1], at[2]);
          long a[4];
          bool any = cls(c0) > 0 || cls(c1) > 0;
          for (int m = 0; m < 4; ++m) {
            long p[3] = {at[0], at[1], at[2]};
            p[(d + 1) % 3] += kU[m], p[(d + 2) % 3] += kV[m];
            a[m] = g.index(p[0], p[1], p[2]);
            any = any || cls(a[m]) > 0;
          }
          for (int m = 0; any && m < 4; ++m)
            out.push_back({c0, c1, a[m], a[(m + 1) % 4]});
        }
    return out;
  }
};

// The cut edges sorted, without repeats, from each layer of cubes' edges by the node layer of their
// inside node (own: the cubes' lower layer, up: the upper one): each node layer's edges are sorted
// on their own (in parallel), and their concatenation is in order.
std::vector<Edge> layered_edges(std::vector<std::vector<Edge>>& own,
                                const std::vector<std::vector<Edge>>& up, int threads) {
  const long layers = long(own.size()) + 1;
  std::vector<std::vector<Edge>> in_layer(static_cast<size_t>(layers));
  detail::parallel_for(layers, threads, [&](long k, int) {
    std::vector<Edge>& l = in_layer[size_t(k)];
    if (k + 1 < layers)
      l = std::move(own[size_t(k)]);
    if (k > 0)
      l.insert(l.end(), up[size_t(k - 1)].begin(), up[size_t(k - 1)].end());
    std::sort(l.begin(), l.end());
    l.erase(std::unique(l.begin(), l.end()), l.end());
  });
  std::vector<Edge> E;
  for (const auto& l : in_layer)
    E.insert(E.end(), l.begin(), l.end());
  return E;
}

// The tetrahedra of `lists` in order, their ids (< ids) renumbered compactly in id order
// (used[r]: the id of node r); the lists are written at their row offsets in parallel.
Eigen::MatrixXi renumbered(const std::vector<const std::vector<Tet>*>& lists, long ids, int threads,
                           std::vector<long>& used) {
  std::vector<int> index(size_t(ids), -1);
  std::vector<long> first(lists.size() + 1, 0);
  for (size_t k = 0; k < lists.size(); ++k) {
    first[k + 1] = first[k] + long(lists[k]->size());
    for (const Tet& x : *lists[k])
      for (long id : x)
        index[size_t(id)] = 0;
  }
  used.clear();
  for (long id = 0; id < ids; ++id)
    if (index[size_t(id)] == 0)
      index[size_t(id)] = int(used.size()), used.push_back(id);
  Eigen::MatrixXi C(first.back(), 4);
  detail::parallel_for(long(lists.size()), threads, [&](long k, int) {
    long row = first[size_t(k)];
    for (const Tet& x : *lists[size_t(k)]) {
      for (int j = 0; j < 4; ++j)
        C(row, j) = index[size_t(x[size_t(j)])];
      ++row;
    }
  });
  return C;
}

double signed_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                     const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

} // namespace

CutTetrahedra cut_tetrahedra(const ImplicitFunction& f, const RegularGrid& g,
                             const Eigen::VectorXd& S, double epsilon, int threads,
                             Lattice lattice) {
  const Background bg(g, lattice);
  if (S.size() != bg.N)
    throw std::invalid_argument("cut_tetrahedra: S must hold one value per lattice node");
  if (!(epsilon >= 0))
    throw std::invalid_argument("cut_tetrahedra: epsilon must be >= 0");
  threads = detail::resolve_threads(threads);
  const long cz = bg.cz, N = bg.N;
  auto cls = [&](long n) { return node_class(S(n), epsilon); };
  // Pass 1, layers of cubes in parallel: the background tetrahedra with an inside node, whole
  // (no outside node) or mixed, and the edges to cut (lists by Background::list).
  std::vector<std::vector<Tet>> whole(size_t(std::max(cz, 0L))), mixed(whole.size());
  std::vector<std::vector<Edge>> edges[4];
  for (auto& l : edges)
    l.resize(whole.size());
  detail::parallel_for(cz, threads, [&](long k, int) {
    for (const Tet& t : bg.tetrahedra(k, cls)) {
      int c[4], inside = 0, outside = 0;
      for (int j = 0; j < 4; ++j)
        c[j] = cls(t[size_t(j)]), inside += c[j] > 0, outside += c[j] < 0;
      if (inside == 0)
        continue;
      (outside == 0 ? whole : mixed)[size_t(k)].push_back(t);
      for (int a = 0; outside > 0 && a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          if (c[a] > 0 && c[b] < 0)
            edges[bg.list(t[size_t(a)], k)][size_t(k)].push_back({t[size_t(a)], t[size_t(b)]});
    }
  });
  // Edges from grid nodes, then from cube centres: in order.
  std::vector<Edge> E = layered_edges(edges[0], edges[1], threads);
  const std::vector<Edge> from_centres = layered_edges(edges[2], edges[3], threads);
  E.insert(E.end(), from_centres.begin(), from_centres.end());
  auto point = [&](long n) { return bg.point(n); };
  // The cut points: roots of F on the edges, and (for orientation) of the linear interpolant.
  const long ne = long(E.size());
  Points3 A(ne, 3), B(ne, 3);
  Eigen::VectorXd FA(ne), FB(ne), lin(ne);
  detail::parallel_chunks(ne, kBatch, threads, [&](long, long e0, long e1) {
    for (long e = e0; e < e1; ++e) {
      A.row(e) = point(E[size_t(e)].first).transpose();
      B.row(e) = point(E[size_t(e)].second).transpose();
      FA(e) = S(E[size_t(e)].first), FB(e) = S(E[size_t(e)].second);
      lin(e) = FA(e) / (FA(e) - FB(e));
    }
  });
  RootOptions ro;
  ro.threads = threads;
  const Eigen::VectorXd t = ne > 0 ? roots_on_segments(f, A, B, FA, FB, ro) : Eigen::VectorXd();
  auto cut = [&](long a, long b) {
    return N + long(std::lower_bound(E.begin(), E.end(), Edge{a, b}) - E.begin());
  };
  auto reference = [&](long id) -> Eigen::Vector3d {
    if (id < N)
      return point(id);
    const long e = id - N;
    return A.row(e).transpose() + lin(e) * (B.row(e) - A.row(e)).transpose();
  };
  // Warping (Labelle and Shewchuk's isosurface stuffing): a node within alpha (Background::alpha)
  // of its edge from a cut point moves onto the nearest such point and becomes a surface node, so
  // that no piece is a sliver at a node. Along an edge of a Kuhn tetrahedron a node moves at most
  // 0.2 sqrt(3) h, less than the smallest height of the tetrahedra around it (h / sqrt 2): they
  // stay positive; the BCC thresholds are the paper's (its dihedral-angle bounds).
  std::vector<std::pair<long, std::pair<double, long>>> near; // node, (distance, edge)
  for (long e = 0; e < ne; ++e) {
    const double len = (B.row(e) - A.row(e)).norm();
    const double alpha = bg.alpha(E[size_t(e)].first, E[size_t(e)].second);
    if (t(e) < alpha)
      near.push_back({E[size_t(e)].first, {t(e) * len, e}});
    else if (t(e) > 1 - alpha)
      near.push_back({E[size_t(e)].second, {(1 - t(e)) * len, e}});
  }
  std::sort(near.begin(), near.end());
  std::vector<std::pair<long, long>> warp; // node, edge whose cut point it moves to
  for (size_t r = 0; r < near.size(); ++r)
    if (r == 0 || near[r].first != near[r - 1].first)
      warp.push_back({near[r].first, near[r].second.second});
  auto warped = [&](long n) {
    const auto it = std::lower_bound(warp.begin(), warp.end(), std::pair<long, long>{n, -1});
    return it != warp.end() && it->first == n ? it->second : -1L;
  };
  auto cls2 = [&](long n) { return warped(n) >= 0 ? 0 : cls(n); };
  // Pass 2: whole tetrahedra and the pieces of the cut ones, oriented by their reference shape
  // (grid positions, cut points of the linear interpolant, warped nodes as surface nodes there:
  // convex pieces), without the degenerate ones.
  std::vector<std::vector<Tet>> pieces(whole.size()), flat(whole.size());
  detail::parallel_for(cz, threads, [&](long k, int) {
    std::vector<Tet> local;
    std::vector<Tet>& kept = whole[size_t(k)];
    std::vector<Tet> all;
    all.swap(kept);
    all.insert(all.end(), mixed[size_t(k)].begin(), mixed[size_t(k)].end());
    for (const Tet& m : all) {
      const int c[4] = {cls2(m[0]), cls2(m[1]), cls2(m[2]), cls2(m[3])};
      if (std::max({c[0], c[1], c[2], c[3]}) < 1) {
        if (std::min({c[0], c[1], c[2], c[3]}) == 0) // all on F = 0: inside or not, see below
          flat[size_t(k)].push_back(m);
        continue;
      }
      if (std::min({c[0], c[1], c[2], c[3]}) >= 0) {
        kept.push_back(m);
        continue;
      }
      local.clear();
      clip(m, c, cut, local);
      for (Tet p : local) {
        std::array<long, 4> s = p;
        std::sort(s.begin(), s.end());
        if (std::adjacent_find(s.begin(), s.end()) != s.end())
          continue;
        if (signed_volume(reference(p[0]), reference(p[1]), reference(p[2]), reference(p[3])) < 0)
          std::swap(p[1], p[2]);
        pieces[size_t(k)].push_back(p);
      }
    }
  });
  // Tetrahedra with every node warped onto F = 0: kept where F > epsilon at the centroid of the
  // warped nodes (a wall about a cell thin), else the body does not fill them.
  auto position = [&](long n) -> Eigen::Vector3d {
    const long e = warped(n);
    return e < 0 ? point(n) : Eigen::Vector3d(A.row(e) + t(e) * (B.row(e) - A.row(e)));
  };
  std::vector<Tet> candidates;
  for (const auto& l : flat)
    candidates.insert(candidates.end(), l.begin(), l.end());
  Points3 centroid(long(candidates.size()), 3);
  for (size_t r = 0; r < candidates.size(); ++r) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (long n : candidates[r])
      c += position(n) / 4;
    centroid.row(long(r)) = c.transpose();
  }
  Eigen::VectorXd Fc(centroid.rows());
  if (centroid.rows() > 0)
    f.value(centroid, Fc);
  std::vector<Tet> filled;
  for (size_t r = 0; r < candidates.size(); ++r)
    if (Fc(long(r)) > epsilon)
      filled.push_back(candidates[r]);
  // Compact numbering: the used grid nodes in grid order, then the cut points in edge order.
  whole.push_back(std::move(filled));
  std::vector<const std::vector<Tet>*> lists;
  for (const auto& l : whole)
    lists.push_back(&l);
  for (const auto& l : pieces)
    lists.push_back(&l);
  CutTetrahedra out;
  std::vector<long> used;
  out.C = renumbered(lists, N + ne, threads, used);
  for (const auto& l : whole)
    out.whole += long(l.size());
  out.V.resize(long(used.size()), 3);
  std::vector<long> warped_in(size_t(detail::chunk_count(long(used.size()), kBatch)), 0);
  detail::parallel_chunks(long(used.size()), kBatch, threads, [&](long task, long r0, long r1) {
    for (long r = r0; r < r1; ++r) {
      const long id = used[size_t(r)], e = id - N;
      if (id < N) {
        out.V.row(r) = position(id).transpose();
        warped_in[size_t(task)] += warped(id) >= 0;
      } else {
        out.V.row(r) = A.row(e) + t(e) * (B.row(e) - A.row(e));
      }
    }
  });
  for (long w : warped_in)
    out.warped += w;
  out.cut_nodes = long(used.end() - std::lower_bound(used.begin(), used.end(), N));
  return out;
}

} // namespace interlin
