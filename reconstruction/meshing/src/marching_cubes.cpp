#include "interlin/reconstruction/meshing/marching_cubes.h"

#include "interlin/reconstruction/meshing/parallel_for.h"
#include "iso_block.h"
#include "mc_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace interlin {

namespace detail {

namespace {

// Per x-row of a slice: the first and last crossed x-edge (nx and -1 when none) and the inside
// flags of its first and last node. Nodes up to xmin share the first flag, nodes after xmax the
// last one, so a pair (or quadruple) of rows can only have crossings in between (flying edges'
// trimming).
struct RowInfo {
  int xmin, xmax;
  std::uint8_t first, last;
};

// Node range [lo, hi] where rows a and b can differ.
void trim(const RowInfo& a, const RowInfo& b, int nx, int& lo, int& hi) {
  lo = a.first == b.first ? std::min(a.xmin, b.xmin) + 1 : 0;
  hi = a.last == b.last ? std::max(a.xmax, b.xmax) : nx - 1;
}

} // namespace

void extract_block(const RegularGrid& g, const double* s, long sy, long sz,
                   const Eigen::Array3i& lo, const Eigen::Array3i& n, bool ends, BlockMesh& out) {
  out.V.clear();
  out.F.clear();
  out.key.clear();
  out.ends.clear();
  out.shared.clear();
  const McTable& T = mc_table();
  const std::uint32_t* start = T.start.data();
  const std::uint32_t* first = T.first;
  const std::uint8_t* edges = T.edges.data();
  const int nx = n(0), ny = n(1), nz = n(2);
  const long slice = long(nx) * ny;
  bool shared_lo[3], shared_hi[3];
  for (int a = 0; a < 3; ++a) {
    shared_lo[a] = lo(a) > 0;
    shared_hi[a] = lo(a) + n(a) < g.nodes(a);
  }
  const long gnx = g.nodes(0), gnxy = gnx * g.nodes(1);
  auto row = [&](long j, long k) { return s + sy * j + sz * k; };

  // One vertex on the edge from local node (i, j, k) along `axis`.
  auto vertex = [&](int i, int j, int k, int axis, double f0, double f1) {
    double t = f0 / (f0 - f1);
    t = std::isfinite(t) ? std::clamp(t, kEdgeClamp, 1 - kEdgeClamp) : 0.5;
    const long gi = lo(0) + i, gj = lo(1) + j, gk = lo(2) + k;
    Eigen::Vector3d p = g.point(gi, gj, gk);
    p(axis) += t * g.spacing(axis);
    const int id = int(out.V.size() / 3);
    double* dst = out.V.extend(3);
    dst[0] = p(0), dst[1] = p(1), dst[2] = p(2);
    out.V.added(3);
    const long key = 3 * (gi + gnx * gj + gnxy * gk) + axis;
    if (ends) {
      out.key.push_back(key);
      out.ends.insert(out.ends.end(), {f0, f1});
    }
    const int c[3] = {i, j, k};
    bool shared = false;
    for (int b = 0; b < 3; ++b)
      if (b != axis)
        shared = shared || (c[b] == 0 && shared_lo[b]) || (c[b] == n(b) - 1 && shared_hi[b]);
    if (shared)
      out.shared.push_back({id, key});
    return id;
  };

  std::vector<std::uint8_t> in[2] = {std::vector<std::uint8_t>(static_cast<size_t>(slice)),
                                     std::vector<std::uint8_t>(static_cast<size_t>(slice))};
  std::vector<int> xid[2] = {std::vector<int>(static_cast<size_t>(slice)),
                             std::vector<int>(static_cast<size_t>(slice))};
  std::vector<int> yid[2] = {std::vector<int>(static_cast<size_t>(slice)),
                             std::vector<int>(static_cast<size_t>(slice))};
  std::vector<int> zid(static_cast<size_t>(slice));
  std::vector<RowInfo> rows[2] = {std::vector<RowInfo>(static_cast<size_t>(ny)),
                                  std::vector<RowInfo>(static_cast<size_t>(ny))};

  // Inside flags, row information and the x- and y-edge vertices of slice k into buffer b.
  auto fill_slice = [&](int k, int b) {
    std::uint8_t* f = in[b].data();
    for (int j = 0; j < ny; ++j) {
      const double* v = row(j, k);
      std::uint8_t* fr = f + long(nx) * j;
      int* xr = xid[b].data() + long(nx) * j;
      RowInfo info{nx, -1, 0, 0};
      std::uint8_t prev = v[0] > 0;
      fr[0] = prev;
      info.first = prev;
      for (int i = 1; i < nx; ++i) {
        const std::uint8_t c = v[i] > 0;
        fr[i] = c;
        if (c != prev) {
          xr[i - 1] = vertex(i - 1, j, k, 0, v[i - 1], v[i]);
          info.xmin = std::min(info.xmin, i - 1);
          info.xmax = i - 1;
        }
        prev = c;
      }
      info.last = prev;
      rows[b][size_t(j)] = info;
    }
    for (int j = 0; j + 1 < ny; ++j) {
      int i0, i1;
      trim(rows[b][size_t(j)], rows[b][size_t(j + 1)], nx, i0, i1);
      const std::uint8_t* fa = f + long(nx) * j;
      const std::uint8_t* fb = fa + nx;
      const double *va = row(j, k), *vb = row(j + 1, k);
      int* yr = yid[b].data() + long(nx) * j;
      for (int i = i0; i <= i1; ++i)
        if (fa[i] != fb[i])
          yr[i] = vertex(i, j, k, 1, va[i], vb[i]);
    }
  };

  fill_slice(0, 0);
  for (int k = 0; k + 1 < nz; ++k) {
    const int c = k & 1, d = c ^ 1;
    fill_slice(k + 1, d);
    const std::uint8_t* f0 = in[c].data();
    const std::uint8_t* f1 = in[d].data();
    const RowInfo* r0 = rows[c].data();
    const RowInfo* r1 = rows[d].data();
    for (int j = 0; j < ny; ++j) {
      int i0, i1;
      trim(r0[j], r1[j], nx, i0, i1);
      const long base = long(nx) * j;
      const double *va = row(j, k), *vb = row(j, k + 1);
      for (int i = i0; i <= i1; ++i)
        if (f0[base + i] != f1[base + i])
          zid[size_t(base + i)] = vertex(i, j, k, 2, va[i], vb[i]);
    }
    // Edge ids of cube (i, j): edge e of the cube at offset r = i + nx j is ids[e][r].
    const int* ids[12] = {xid[c].data(), xid[c].data() + nx, xid[d].data(),   xid[d].data() + nx,
                          yid[c].data(), yid[c].data() + 1,  yid[d].data(),   yid[d].data() + 1,
                          zid.data(),    zid.data() + 1,     zid.data() + nx, zid.data() + nx + 1};
    for (int j = 0; j + 1 < ny; ++j) {
      const RowInfo* q[4] = {&r0[j], &r0[j + 1], &r1[j], &r1[j + 1]};
      bool same_first = true, same_last = true;
      int xmin = nx, xmax = -1;
      for (const RowInfo* x : q) {
        same_first = same_first && x->first == q[0]->first;
        same_last = same_last && x->last == q[0]->last;
        xmin = std::min(xmin, x->xmin);
        xmax = std::max(xmax, x->xmax);
      }
      // Cubes left of every first crossing (right of every last) are all in or all out.
      const int i0 = same_first ? xmin : 0, i1 = same_last ? std::min(xmax, nx - 2) : nx - 2;
      for (int i = i0; i <= i1; ++i) {
        const long r = i + long(nx) * j;
        const int code = f0[r] | f0[r + 1] << 1 | f0[r + nx] << 2 | f0[r + nx + 1] << 3 |
                         f1[r] << 4 | f1[r + 1] << 5 | f1[r + nx] << 6 | f1[r + nx + 1] << 7;
        if (code == 0 || code == 255)
          continue;
        int sub = 0;
        if (const int amb = T.ambiguous[code]) { // rare: ambiguous faces
          int bit = 0;
          for (int face = 0; face < 6; ++face) {
            if (!((amb >> face) & 1))
              continue;
            double v[4];
            for (int q4 = 0; q4 < 4; ++q4) {
              const int cc = T.face_corner[face][q4];
              v[q4] = row(j + ((cc >> 1) & 1), k + (cc >> 2))[i + (cc & 1)];
            }
            // Asymptotic decider: inside corners connected iff their product is the larger.
            const bool first_inside = (code >> T.face_corner[face][0]) & 1;
            const double in_product = first_inside ? v[0] * v[2] : v[1] * v[3];
            const double out_product = first_inside ? v[1] * v[3] : v[0] * v[2];
            sub |= int(in_product > out_product) << bit++;
          }
        }
        const std::uint32_t s0 = start[first[code] + sub], s1 = start[first[code] + sub + 1];
        int* dst = out.F.extend(3 * (s1 - s0));
        for (std::uint32_t t = 3 * s0; t < 3 * s1; ++t)
          *dst++ = ids[edges[t]][r];
        out.F.added(3 * (s1 - s0));
      }
    }
  }
}

void merge_blocks(const std::vector<BlockMesh>& blocks, Eigen::MatrixXd& V, Eigen::MatrixXi& F,
                  std::vector<EdgeVertex>* E, int threads) {
  struct Shared {
    long key;
    int block, local;
  };
  std::vector<Shared> shared;
  for (size_t b = 0; b < blocks.size(); ++b)
    for (const auto& [l, key] : blocks[b].shared)
      shared.push_back({key, int(b), l});
  std::sort(shared.begin(), shared.end(), [](const Shared& x, const Shared& y) {
    return x.key != y.key ? x.key < y.key : x.block < y.block;
  });
  // Later copies of a shared vertex: (block, local) -> index in `shared` of the first copy.
  std::vector<std::vector<std::pair<int, long>>> copies(blocks.size());
  for (size_t s = 1, first = 0; s < shared.size(); ++s) {
    if (shared[s].key != shared[first].key)
      first = s;
    else
      copies[size_t(shared[s].block)].push_back({shared[s].local, long(first)});
  }
  // Global ids: each block's own vertices in order, offset by the blocks before it.
  const size_t nb = blocks.size();
  std::vector<long> vbase(nb + 1, 0), fbase(nb + 1, 0);
  std::vector<std::vector<int>> global(nb);
  for (size_t b = 0; b < nb; ++b) {
    std::sort(copies[b].begin(), copies[b].end());
    vbase[b + 1] = vbase[b] + blocks[b].vertices() - long(copies[b].size());
    fbase[b + 1] = fbase[b] + long(blocks[b].F.size() / 3);
  }
  const long nv = vbase[nb], nf = fbase[nb];
  if (nv >= (1L << 31) || nf >= (1L << 31))
    throw std::length_error("marching cubes: more than 2^31 vertices or triangles");
  V.resize(nv, 3);
  F.resize(nf, 3);
  if (E)
    E->resize(size_t(nv));
  // Pass 1 (parallel): own vertices get ids and are copied; copies get -1 for now.
  parallel_for(long(nb), threads, [&](long b, int) {
    const BlockMesh& m = blocks[size_t(b)];
    std::vector<int>& id = global[size_t(b)];
    id.resize(size_t(m.vertices()));
    const auto& cp = copies[size_t(b)];
    size_t next = 0;
    long g = vbase[size_t(b)];
    double* vx = V.data();
    const long nr = V.rows();
    for (size_t l = 0; l < size_t(m.vertices()); ++l) {
      if (next < cp.size() && cp[next].first == int(l)) {
        id[l] = -1;
        ++next;
        continue;
      }
      id[l] = int(g);
      vx[g] = m.V[3 * l], vx[nr + g] = m.V[3 * l + 1], vx[2 * nr + g] = m.V[3 * l + 2];
      if (E) {
        const long key = m.key[l];
        (*E)[size_t(g)] = {key / 3, int(key % 3), m.ends[2 * l], m.ends[2 * l + 1]};
      }
      ++g;
    }
  });
  for (size_t b = 0; b < nb; ++b)
    for (const auto& [local, first] : copies[b])
      global[b][size_t(local)] =
          global[size_t(shared[size_t(first)].block)][size_t(shared[size_t(first)].local)];
  // Pass 2 (parallel): triangles.
  parallel_for(long(nb), threads, [&](long b, int) {
    const BlockMesh& m = blocks[size_t(b)];
    const std::vector<int>& id = global[size_t(b)];
    int* fx = F.data();
    const long nr = F.rows();
    for (size_t t = 0, f = size_t(fbase[size_t(b)]); t < m.F.size(); t += 3, ++f) {
      fx[f] = id[size_t(m.F[t])];
      fx[nr + long(f)] = id[size_t(m.F[t + 1])];
      fx[2 * nr + long(f)] = id[size_t(m.F[t + 2])];
    }
  });
}

} // namespace detail

void marching_cubes(const RegularGrid& g, const Eigen::VectorXd& S, Eigen::MatrixXd& V,
                    Eigen::MatrixXi& F, std::vector<EdgeVertex>* E, int threads) {
  if ((g.nodes < 2).any())
    throw std::invalid_argument("marching_cubes: the grid needs at least 2 nodes per axis");
  if (S.size() != g.size())
    throw std::invalid_argument("marching_cubes: " + std::to_string(S.size()) +
                                " values for a grid of " + std::to_string(g.size()) + " nodes");
  const int workers = detail::resolve_threads(threads);
  // Slabs across the longer of y and z (x rows stay whole); several per worker balance slabs
  // that cut more surface than others.
  const int axis = g.nodes(1) > g.nodes(2) ? 1 : 2;
  const int cells = g.nodes(axis) - 1;
  const int slabs = workers == 1 ? 1 : std::min(cells, 4 * workers);
  const long stride = axis == 1 ? long(g.nodes(0)) : long(g.nodes(0)) * g.nodes(1);
  std::vector<detail::BlockMesh> blocks(static_cast<size_t>(slabs));
  detail::parallel_for(slabs, workers, [&](long b, int) {
    const int c0 = int(long(cells) * b / slabs), c1 = int(long(cells) * (b + 1) / slabs);
    Eigen::Array3i lo(0, 0, 0), n = g.nodes;
    lo(axis) = c0;
    n(axis) = c1 - c0 + 1;
    detail::extract_block(g, S.data() + stride * c0, g.nodes(0), long(g.nodes(0)) * g.nodes(1), lo,
                          n, E != nullptr, blocks[size_t(b)]);
  });
  detail::merge_blocks(blocks, V, F, E, workers);
}

} // namespace interlin
