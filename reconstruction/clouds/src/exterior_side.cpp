// The outside of a closed scan by a voxel flood fill (exterior_side.h).
#include "exterior_side.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace interlin::detail {

namespace {

constexpr long kMaxVoxels = 1L << 26;
constexpr int kPadding = 2;        // free voxels around the shell on every side
constexpr double kMarchVoxels = 6; // how far a vote looks for a free voxel along the normal
using Grid = ExteriorGrid;
constexpr std::uint8_t kInside = Grid::kInside, kShell = Grid::kShell, kOutside = Grid::kOutside;

long index(const Grid& g, long x, long y, long z) {
  return (z * g.n[1] + y) * g.n[0] + x;
}
// The voxel (x, y, z) of storage index v (index's inverse).
std::array<long, 3> coords(const Grid& g, long v) {
  return {v % g.n[0], (v / g.n[0]) % g.n[1], v / (g.n[0] * g.n[1])};
}
std::array<long, 3> cell(const Grid& g, const Eigen::Array3d& p) {
  const Eigen::Array3d c = ((p - g.lo) / g.h).floor();
  return {long(c(0)), long(c(1)), long(c(2))};
}
bool inside_grid(const Grid& g, const std::array<long, 3>& c) {
  return c[0] >= 0 && c[1] >= 0 && c[2] >= 0 && c[0] < g.n[0] && c[1] < g.n[1] && c[2] < g.n[2];
}

// The grid around P, its voxels all free (kInside until the flood fill).
Grid empty_grid(const Eigen::MatrixX3d& P, double voxel) {
  Grid g;
  g.h = voxel;
  const Eigen::Array3d lo = P.colwise().minCoeff().transpose().array();
  const Eigen::Array3d hi = P.colwise().maxCoeff().transpose().array();
  for (;;) {
    g.lo = lo - (kPadding + 1) * g.h;
    long total = 1;
    for (int a = 0; a < 3; ++a) {
      g.n[size_t(a)] = long(std::ceil((hi(a) - lo(a)) / g.h)) + 2 * (kPadding + 1) + 1;
      total *= g.n[size_t(a)];
    }
    if (total <= kMaxVoxels) {
      g.state.assign(size_t(total), kInside);
      return g;
    }
    g.h *= 2;
  }
}

// Every voxel within one voxel (26-neighbourhood) of a point's voxel becomes shell.
void mark_shell(Grid& g, const Eigen::MatrixX3d& P) {
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const auto c = cell(g, P.row(i).transpose().array());
    for (long dz = -1; dz <= 1; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx)
          g.state[size_t(index(g, c[0] + dx, c[1] + dy, c[2] + dz))] = kShell;
  }
}

// From the voxels in the queue (already set to `to`), every voxel of state `from` reached through
// face neighbours is set to `to` and appended to the queue.
void flood(Grid& g, std::vector<long>& queue, std::uint8_t from, std::uint8_t to) {
  auto visit = [&](long x, long y, long z) {
    std::uint8_t& s = g.state[size_t(index(g, x, y, z))];
    if (s == from) {
      s = to;
      queue.push_back(index(g, x, y, z));
    }
  };
  for (size_t head = 0; head < queue.size(); ++head) {
    const auto [x, y, z] = coords(g, queue[head]);
    if (x > 0)
      visit(x - 1, y, z);
    if (x + 1 < g.n[0])
      visit(x + 1, y, z);
    if (y > 0)
      visit(x, y - 1, z);
    if (y + 1 < g.n[1])
      visit(x, y + 1, z);
    if (z > 0)
      visit(x, y, z - 1);
    if (z + 1 < g.n[2])
      visit(x, y, z + 1);
  }
}

// The free voxels reached from the grid's border through face neighbours become kOutside.
void flood_outside(Grid& g) {
  std::vector<long> queue;
  for (long z = 0; z < g.n[2]; ++z)
    for (long y = 0; y < g.n[1]; ++y)
      for (long x = 0; x < g.n[0]; ++x)
        if ((x == 0 || y == 0 || z == 0 || x == g.n[0] - 1 || y == g.n[1] - 1 || z == g.n[2] - 1) &&
            g.state[size_t(index(g, x, y, z))] == kInside) {
          g.state[size_t(index(g, x, y, z))] = kOutside;
          queue.push_back(index(g, x, y, z));
        }
  flood(g, queue, kInside, kOutside);
}

Eigen::Vector3d centre(const Grid& g, long v) {
  const auto [x, y, z] = coords(g, v);
  return (g.lo + g.h * (Eigen::Array3d(double(x), double(y), double(z)) + 0.5)).matrix();
}

// The state of the first non-shell voxel from p along d (kShell when none within kMarchVoxels).
std::uint8_t first_free(const Grid& g, const Eigen::Array3d& p, const Eigen::Array3d& d) {
  for (double t = 0.5 * g.h; t <= kMarchVoxels * g.h; t += 0.5 * g.h) {
    const auto c = cell(g, p + t * d);
    if (!inside_grid(g, c))
      return kOutside;
    const std::uint8_t s = g.state[size_t(index(g, c[0], c[1], c[2]))];
    if (s != kShell)
      return s;
  }
  return kShell;
}

} // namespace

ExteriorGrid exterior_grid(const Eigen::MatrixX3d& P, double voxel) {
  Grid g = empty_grid(P, voxel);
  mark_shell(g, P);
  flood_outside(g);
  return g;
}

int exterior_side(const ExteriorGrid& g, const Eigen::Vector3d& x) {
  const auto c = cell(g, x.array());
  if (!inside_grid(g, c))
    return 1;
  const std::uint8_t s = g.state[size_t(index(g, c[0], c[1], c[2]))];
  return s == kOutside ? 1 : s == kInside ? -1 : 0;
}

long open_pockets(ExteriorGrid& g, const std::function<double(const Eigen::Vector3d&)>& winding,
                  int threads) {
  constexpr std::uint8_t kKept = 3; // an inside component read as inside, until the end
  constexpr size_t kSamples = 64;
  long opened = 0;
  std::vector<long> part;
  std::vector<double> w;
  for (long v = 0; v < long(g.state.size()); ++v) {
    if (g.state[size_t(v)] != kInside)
      continue;
    g.state[size_t(v)] = kKept;
    part.assign(1, v);
    flood(g, part, kInside, kKept);
    const size_t step = std::max<size_t>(1, part.size() / kSamples);
    w.assign((part.size() + step - 1) / step, 0);
    parallel_for(long(w.size()), resolve_threads(threads),
                 [&](long t, int) { w[size_t(t)] = winding(centre(g, part[size_t(t) * step])); });
    std::nth_element(w.begin(), w.begin() + std::ptrdiff_t(w.size() / 2), w.end());
    if (w[w.size() / 2] < 0.5) {
      for (long u : part)
        g.state[size_t(u)] = kOutside;
      opened += long(part.size());
    }
  }
  std::replace(g.state.begin(), g.state.end(), kKept, kInside);
  return opened;
}

ExteriorSamples shell_neighbours(const ExteriorGrid& g, long most) {
  std::vector<long> found;
  const long step[3] = {1, g.n[0], g.n[0] * g.n[1]};
  for (long z = 1; z + 1 < g.n[2]; ++z)
    for (long y = 1; y + 1 < g.n[1]; ++y)
      for (long x = 1; x + 1 < g.n[0]; ++x) {
        const long v = index(g, x, y, z);
        if (g.state[size_t(v)] == kShell)
          continue;
        bool next = false;
        for (long s : step)
          next = next || g.state[size_t(v + s)] == kShell || g.state[size_t(v - s)] == kShell;
        if (next)
          found.push_back(v);
      }
  const size_t k =
      std::max<size_t>(1, (found.size() + size_t(most) - 1) / size_t(std::max(most, 1L)));
  ExteriorSamples r;
  r.X.resize(Eigen::Index((found.size() + k - 1) / k), 3);
  for (size_t i = 0; i < found.size(); i += k) {
    r.X.row(Eigen::Index(i / k)) = centre(g, found[i]).transpose();
    r.side.push_back(g.state[size_t(found[i])] == kOutside ? 1 : -1);
  }
  return r;
}

std::vector<signed char> exterior_votes(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                                        double voxel) {
  std::vector<signed char> vote(size_t(P.rows()), 0);
  if (P.rows() == 0 || !(voxel > 0))
    return vote;
  const Grid g = exterior_grid(P, voxel);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Array3d p = P.row(i).transpose().array(), n = N.row(i).transpose().array();
    const std::uint8_t ahead = first_free(g, p, n), behind = first_free(g, p, -n);
    if (ahead == kOutside && behind == kInside)
      vote[size_t(i)] = 1;
    else if (ahead == kInside && behind == kOutside)
      vote[size_t(i)] = -1;
  }
  return vote;
}

} // namespace interlin::detail
