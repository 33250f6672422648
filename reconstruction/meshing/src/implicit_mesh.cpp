#include "interlin/reconstruction/meshing/implicit_mesh.h"

#include "interlin/reconstruction/meshing/parallel_for.h"
#include "iso_block.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

namespace interlin {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Signed distance to the box's face planes, the nearest one: positive inside.
double box_value(const Eigen::Ref<const Eigen::RowVector3d>& p, const Eigen::AlignedBox3d& box) {
  double b = std::min(p(0) - box.min()(0), box.max()(0) - p(0));
  b = std::min(b, std::min(p(1) - box.min()(1), box.max()(1) - p(1)));
  return std::min(b, std::min(p(2) - box.min()(2), box.max()(2) - p(2)));
}

// min(v, b) keeping NaN (outside either way).
double clip(double v, double b) {
  return v > b ? b : v;
}

// The sign f.sign_on_box gives the block of grid nodes lo .. lo + n - 1 when marching cubes would
// find no triangle in it: -1 when F < 0 on it, +1 when F > 0 and it does not reach the grid's
// outer layer (where the mesh closes along the box); else 0.
int block_sign(const ImplicitFunction& f, const RegularGrid& grid, const Eigen::Array3i& lo,
               const Eigen::Array3i& n) {
  const Eigen::Array3i hi = lo + n - 1;
  const Eigen::AlignedBox3d B(grid.point(lo(0), lo(1), lo(2)), grid.point(hi(0), hi(1), hi(2)));
  const int sign = f.sign_on_box(B);
  // the block reaches the outer layer exactly when one of its two extreme corners lies on it
  if (sign > 0 && (grid.outer(lo(0), lo(1), lo(2)) || grid.outer(hi(0), hi(1), hi(2))))
    return 0;
  return sign;
}

// Blocks of at most this many cells per axis are sampled whole: a smaller one costs more in
// sign_on_box than its nodes in evaluations.
constexpr int kFinestBlock = 4;

// The nodes of a sub-box (local lo .. lo + n - 1 of the sub-box whose first node is `base`,
// node (i, j, k) at i + n0 (j + n1 k)) that must be sampled: those of a block without a sign.
// A block with a sign gives it to its nodes as their value (+-1) unless they are also in a
// sampled block: every cell that marching cubes cuts lies in a block without a sign, so its 8
// corners are sampled and the mesh is the same as from all nodes.
void mark_band(const ImplicitFunction& f, const RegularGrid& grid, const Eigen::Array3i& base,
               const Eigen::Array3i& dims, const Eigen::Array3i& lo, const Eigen::Array3i& n,
               int sign, std::vector<signed char>& mark) {
  auto each_node = [&](auto&& op) {
    for (int k = lo(2); k < lo(2) + n(2); ++k)
      for (int j = lo(1); j < lo(1) + n(1); ++j)
        for (int i = lo(0); i < lo(0) + n(0); ++i)
          op(mark[size_t(i + dims(0) * (j + dims(1) * k))]);
  };
  if (sign != 0) { // sampled marks (2) win over signs
    each_node([&](signed char& m) { m = m == 2 ? m : static_cast<signed char>(sign); });
    return;
  }
  if ((n - 1).maxCoeff() <= kFinestBlock) {
    each_node([](signed char& m) { m = 2; });
    return;
  }
  // halve the longer axes; children share their middle planes
  const Eigen::Array3i cells = n - 1;
  for (int c = 0; c < 8; ++c) {
    Eigen::Array3i clo = lo, cn = n;
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      const bool split = cells(a) > kFinestBlock;
      const int half = cells(a) / 2;
      const int upper = (c >> a) & 1;
      if (!split) {
        empty |= upper == 1;
        continue;
      }
      clo(a) = lo(a) + upper * half;
      cn(a) = (upper ? cells(a) - half : half) + 1;
    }
    if (empty)
      continue;
    mark_band(f, grid, base, dims, clo, cn, block_sign(f, grid, base + clo, cn), mark);
  }
}

} // namespace

double default_mesh_cell(const ImplicitFunction& f, const Eigen::AlignedBox3d& box,
                         double cells_per_spacing) {
  if (box.isEmpty() || !(cells_per_spacing > 0))
    throw std::invalid_argument("default_mesh_cell: empty box or cells per spacing <= 0");
  const double longest = box.sizes().maxCoeff();
  if (!(f.sample_spacing > 0))
    return longest / ImplicitMeshOptions{}.resolution;
  constexpr double kFewest = 32, kMost = 1024; // cells along the longest side
  return std::clamp(f.sample_spacing / cells_per_spacing, longest / kMost, longest / kFewest);
}

ImplicitFunction clip_to_box(const ImplicitFunction& f, const Eigen::AlignedBox3d& box) {
  if (!f.value)
    throw std::invalid_argument("clip_to_box: the implicit function has no value");
  ImplicitFunction g;
  g.box = box;
  g.value = [f, box](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    f.value(P, F);
    for (Eigen::Index r = 0; r < P.rows(); ++r)
      F(r) = clip(F(r), box_value(P.row(r), box));
  };
  if (f.gradient)
    g.gradient = [f, box](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F,
                          Eigen::Ref<Points3> G) {
      f.gradient(P, F, G);
      for (Eigen::Index r = 0; r < P.rows(); ++r) {
        const double b = box_value(P.row(r), box);
        if (!(F(r) > b))
          continue;
        F(r) = b;
        G.row(r).setZero(); // the gradient of the nearest face plane
        for (int a = 0; a < 3; ++a) {
          if (P(r, a) - box.min()(a) == b)
            G(r, a) = 1;
          else if (box.max()(a) - P(r, a) == b)
            G(r, a) = -1;
          else
            continue;
          break;
        }
      }
    };
  return g;
}

void implicit_mesh(const ImplicitFunction& f, const ImplicitMeshOptions& o, Eigen::MatrixXd& V,
                   Eigen::MatrixXi& F, ImplicitMeshInfo* info) {
  if (!f.value)
    throw std::invalid_argument("implicit_mesh: the implicit function has no value");
  const Eigen::AlignedBox3d box = o.box.isEmpty() ? f.box : o.box;
  if (box.isEmpty())
    throw std::invalid_argument("implicit_mesh: no box (neither given nor the function's)");
  const RegularGrid grid =
      o.cell > 0 ? grid_with_cell(box, o.cell) : grid_with_resolution(box, o.resolution);
  const Eigen::Array3i cells = grid.nodes - 1;
  // small sub-boxes when most can be skipped (narrow band), else few large ones
  const int max_cells = f.sign_on_box ? 16 : 64;
  Eigen::Array3i k;
  for (int a = 0; a < 3; ++a) {
    k(a) = o.subboxes(a) > 0 ? o.subboxes(a) : (cells(a) + max_cells - 1) / max_cells;
    if (o.subboxes(a) < 0 || k(a) > cells(a))
      throw std::invalid_argument("implicit_mesh: " + std::to_string(o.subboxes(a)) +
                                  " sub-boxes along axis " + std::to_string(a) + " for " +
                                  std::to_string(cells(a)) + " cells");
  }
  const int workers = detail::resolve_threads(o.threads);
  std::mutex progress_mutex;
  auto say = [&](const std::string& m) {
    if (o.progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      o.progress(m);
    }
  };
  ImplicitMeshInfo local;
  ImplicitMeshInfo& out = info ? *info : local;
  out = ImplicitMeshInfo{};
  out.grid = grid;
  out.subboxes = k;

  const long blocks_total = long(k(0)) * k(1) * k(2);
  say("grid " + std::to_string(grid.nodes(0)) + " x " + std::to_string(grid.nodes(1)) + " x " +
      std::to_string(grid.nodes(2)) + " nodes (cell " + std::to_string(grid.spacing(0)) + "), " +
      std::to_string(blocks_total) + " sub-boxes on " + std::to_string(workers) + " threads");
  std::vector<detail::BlockMesh> blocks(static_cast<size_t>(blocks_total));
  std::atomic<long> samples{0}, nonfinite{0}, clipped{0}, skipped{0}, done{0};
  std::atomic<long long> triangles{0};
  struct Scratch {
    std::vector<double> values;
    // per node: 2 sampled, else the sign of its block (0 until mark_band, which covers every
    // node, sets it; all 2 without sign_on_box)
    std::vector<signed char> mark;
    Points3 P;
    Eigen::VectorXd batch;
  };
  std::vector<Scratch> scratch(static_cast<size_t>(workers));
  // A sub-box done, sampled or skipped: a progress line every tenth of them.
  auto finished = [&] {
    const long d = ++done;
    if (blocks_total >= 10 && (d * 10) / blocks_total != ((d - 1) * 10) / blocks_total)
      say("sampled and triangulated " + std::to_string(d) + " of " + std::to_string(blocks_total) +
          " sub-boxes");
  };
  auto t0 = Clock::now();
  detail::parallel_for(blocks_total, workers, [&](long b, int w) {
    const int bx = int(b % k(0)), by = int((b / k(0)) % k(1)), bz = int(b / (long(k(0)) * k(1)));
    const int bi[3] = {bx, by, bz};
    Eigen::Array3i lo, n;
    for (int a = 0; a < 3; ++a) {
      const int c0 = int(long(cells(a)) * bi[a] / k(a)),
                c1 = int(long(cells(a)) * (bi[a] + 1) / k(a));
      lo(a) = c0;
      n(a) = c1 - c0 + 1;
    }
    Scratch& s = scratch[size_t(w)];
    const long slice = long(n(0)) * n(1);
    s.mark.assign(size_t(slice * n(2)), f.sign_on_box ? 0 : 2);
    if (f.sign_on_box) {
      const int sign = block_sign(f, grid, lo, n);
      if (sign != 0) {
        ++skipped;
        finished();
        return;
      }
      mark_band(f, grid, lo, n, Eigen::Array3i::Zero(), n, 0, s.mark);
    }
    s.values.resize(size_t(slice * n(2)));
    s.P.resize(slice, 3);
    long bad = 0, cut = 0, sampled = 0;
    // The sub-box owns its nodes except those on its upper planes shared with a neighbour.
    auto owns = [&](int i, int j, int kk) {
      const int local[3] = {i, j, kk};
      for (int a = 0; a < 3; ++a)
        if (local[a] == n(a) - 1 && bi[a] < k(a) - 1)
          return false;
      return true;
    };
    for (int kk = 0; kk < n(2); ++kk) {
      // the slice's marked nodes in one batch; the others take their block's sign
      const signed char* m = s.mark.data() + slice * kk;
      double* vals = s.values.data() + slice * kk;
      long rows = 0;
      for (int j = 0, r = 0; j < n(1); ++j)
        for (int i = 0; i < n(0); ++i, ++r)
          if (m[r] == 2)
            s.P.row(rows++) = grid.point(lo(0) + i, lo(1) + j, lo(2) + kk).transpose();
      Eigen::VectorXd& F = s.batch;
      F.resize(rows);
      f.value(s.P.topRows(rows), F);
      sampled += rows;
      const long gk = lo(2) + kk;
      for (int j = 0, r = 0, q = 0; j < n(1); ++j)
        for (int i = 0; i < n(0); ++i, ++r) {
          double& v = vals[r];
          if (m[r] != 2) {
            v = m[r];
            continue;
          }
          v = F(q);
          bad += !std::isfinite(v) && owns(i, j, kk); // a node on a shared plane counts once
          const long gi = lo(0) + i, gj = lo(1) + j;
          if (grid.outer(gi, gj, gk) && reaches_box(v)) {
            cut += owns(i, j, kk); // a node on a shared plane counts once
            v = 0;                 // never inside: the surface closes along the box
          }
          v = clip(v, box_value(s.P.row(q++), box));
        }
    }
    detail::extract_block(grid, s.values.data(), n(0), slice, lo, n, true, blocks[size_t(b)]);
    if ((triangles += long(blocks[size_t(b)].F.size() / 3)) > o.max_triangles)
      throw LimitError("the mesh has more triangles than the limit of " +
                           std::to_string(o.max_triangles),
                       "max-triangles");
    samples += sampled;
    nonfinite += bad;
    clipped += cut;
    finished();
  });
  out.seconds_extract = seconds_since(t0);
  out.samples = samples;
  out.nonfinite = nonfinite;
  out.clipped = clipped;
  out.skipped = skipped;

  t0 = Clock::now();
  std::vector<EdgeVertex> E;
  detail::merge_blocks(blocks, V, F, &E, workers);
  blocks.clear();
  blocks.shrink_to_fit();
  out.seconds_merge = seconds_since(t0);
  say("merged: " + std::to_string(V.rows()) + " vertices, " + std::to_string(F.rows()) +
      " triangles");

  if (o.project && V.rows() > 0) {
    t0 = Clock::now();
    say("projecting the vertices onto F = 0");
    const ImplicitFunction clipped_f = clip_to_box(f, box);
    std::atomic<long> evaluations{0};
    ImplicitFunction counted;
    counted.value = [&](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> Fv) {
      evaluations += long(P.rows());
      clipped_f.value(P, Fv);
    };
    RootOptions ro = o.root;
    ro.threads = o.threads;
    project_edge_vertices(counted, grid, E, V, ro);
    out.projection_evaluations = evaluations;
    out.seconds_project = seconds_since(t0);
  }
}

} // namespace interlin
