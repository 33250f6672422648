// Theorem 5: interflatation on a body and the implicit equation of its boundary
// (operators/solid_interflatation.h).
#include "interlin/interflatation/operators/solid_interflatation.h"

#include "interlin/interflatation/operators/region_interlineation.h"
#include "sign_runs.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>

namespace interlin {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// Chord ends closer than this (relative to the cell) to a plane are on the plane; chords shorter
// are points of dG.
constexpr double kRelativeTolerance = 1e-12;
// Offset (relative to a piece) at which the point of a side that shrinks to an apex is located.
constexpr double kApexOffset = 1e-9;
// Probes per side of a cross-section when the mapping axis is chosen.
constexpr int kAxisProbes = 5;

// One chord of a cell along the mapping axis: its ends clipped to the cell and whether each end
// is a grid plane (else dG).
struct Chord {
  double lo, hi;
  bool lo_grid, hi_grid;
};

// The chord structure of a cross-section point: the ends' kinds of every chord, in order.
using Structure = std::vector<std::pair<bool, bool>>;

// The two axes other than m, in increasing order.
std::array<int, 2> others(int m) {
  return {m == 0 ? 1 : 0, m == 2 ? 1 : 2};
}

Vector3d lift(int m, const Vector2d& c, double z) {
  const std::array<int, 2> q = others(m);
  Vector3d p;
  p(q[0]) = c(0);
  p(q[1]) = c(1);
  p(m) = z;
  return p;
}

std::vector<Chord> cell_chords(const SolidBoundary& b, int m, const Vector2d& c, double z0,
                               double z1) {
  const double tol = kRelativeTolerance * (z1 - z0);
  std::vector<Chord> out;
  const std::vector<double> ch = b.chords(m, lift(m, c, z0), z0, z1);
  for (size_t k = 0; k + 1 < ch.size(); k += 2)
    if (ch[k + 1] - ch[k] > tol)
      out.push_back({ch[k], ch[k + 1], ch[k] <= z0 + tol, ch[k + 1] >= z1 - tol});
  return out;
}

Structure structure_of(const std::vector<Chord>& ch) {
  Structure s;
  for (const Chord& c : ch)
    s.emplace_back(c.lo_grid, c.hi_grid);
  return s;
}

int fewest_structures_axis(const SolidBoundary& b, const std::array<Eigen::VectorXd, 3>& nodes,
                           const std::array<Eigen::Index, 3>& index);

} // namespace

struct SolidInterflatation::Cache {
  std::mutex mutex;
  std::map<size_t, int> mapping;
  std::map<std::pair<size_t, Structure>, std::shared_ptr<const RegionInterlineation>> sections;
};

namespace {

int mapping_of(const SolidInterflatation& O, size_t id, const std::array<Eigen::Index, 3>& index) {
  if (O.mapping_axis >= 0)
    return O.mapping_axis;
  {
    const std::lock_guard<std::mutex> lock(O.cache->mutex);
    const auto it = O.cache->mapping.find(id);
    if (it != O.cache->mapping.end())
      return it->second;
  }
  const int m = fewest_structures_axis(O.boundary, O.nodes, index);
  const std::lock_guard<std::mutex> lock(O.cache->mutex);
  return O.cache->mapping.emplace(id, m).first->second;
}

// A cell and the frame of its mapping axis.
struct CellFrame {
  std::array<Eigen::Index, 3> index{};
  size_t id = 0;
  int m = 2;
  double z0 = 0, z1 = 0;
  Eigen::AlignedBox2d rect;
};

Eigen::Index cell_of(const Eigen::VectorXd& v, double s) {
  if (!(s >= v(0) && s <= v(v.size() - 1)))
    return -1;
  const auto it = std::upper_bound(v.data(), v.data() + v.size(), s);
  return std::min<Eigen::Index>(it - v.data() - 1, v.size() - 2);
}

bool locate(const SolidInterflatation& O, const Vector3d& p, CellFrame& f) {
  for (int a = 0; a < 3; ++a) {
    f.index[static_cast<size_t>(a)] = cell_of(O.nodes[static_cast<size_t>(a)], p(a));
    if (f.index[static_cast<size_t>(a)] < 0)
      return false;
  }
  const Eigen::Index nx = O.nodes[0].size() - 1, ny = O.nodes[1].size() - 1;
  f.id = static_cast<size_t>(f.index[0] + nx * (f.index[1] + ny * f.index[2]));
  f.m = mapping_of(O, f.id, f.index);
  const auto range = [&](int a) {
    const Eigen::Index i = f.index[static_cast<size_t>(a)];
    return std::make_pair(O.nodes[static_cast<size_t>(a)](i),
                          O.nodes[static_cast<size_t>(a)](i + 1));
  };
  std::tie(f.z0, f.z1) = range(f.m);
  const std::array<int, 2> q = others(f.m);
  const auto [a0, a1] = range(q[0]);
  const auto [b0, b1] = range(q[1]);
  f.rect = Eigen::AlignedBox2d(Vector2d(a0, b0), Vector2d(a1, b1));
  return true;
}

// The cross-section D of a piece: the points of the cell's face rectangle with the same chord
// structure, as a plane region, and its operator of Theorem 4 (for the frames of its pieces).
RegionInterlineation cross_section(const SolidBoundary& b, const CellFrame& f, const Structure& s,
                                   int samples) {
  const auto same = [b, f, s](const Vector2d& c) {
    return structure_of(cell_chords(b, f.m, c, f.z0, f.z1)) == s ? 1.0 : -1.0;
  };
  const PlaneBoundary D = implicit_boundary(same, f.rect, samples);
  Eigen::VectorXd x(2), y(2);
  x << f.rect.min()(0), f.rect.max()(0);
  y << f.rect.min()(1), f.rect.max()(1);
  return region_interlineation(
      D, x, y, [](const Vector2d&) { return 0.0; }, samples);
}

std::shared_ptr<const RegionInterlineation> section_of(const SolidInterflatation& O,
                                                       const CellFrame& f, const Structure& s) {
  const auto key = std::make_pair(f.id, s);
  {
    const std::lock_guard<std::mutex> lock(O.cache->mutex);
    const auto it = O.cache->sections.find(key);
    if (it != O.cache->sections.end())
      return it->second;
  }
  auto D = std::make_shared<const RegionInterlineation>(cross_section(O.boundary, f, s, O.samples));
  const std::lock_guard<std::mutex> lock(O.cache->mutex);
  return O.cache->sections.emplace(key, std::move(D)).first->second;
}

// Where p is: its cell, chord (index k) and the frame of its cross-section piece.
struct PointFrame {
  CellFrame cell;
  size_t chord = 0;
  Chord own{};
  std::shared_ptr<const RegionInterlineation> section;
  PieceFrame piece;
};

bool point_frame(const SolidInterflatation& O, const Vector3d& p, PointFrame& f) {
  if (!locate(O, p, f.cell))
    return false;
  const std::array<int, 2> q = others(f.cell.m);
  const Vector2d c(p(q[0]), p(q[1]));
  const std::vector<Chord> ch = cell_chords(O.boundary, f.cell.m, c, f.cell.z0, f.cell.z1);
  const double z = p(f.cell.m);
  for (f.chord = 0; f.chord < ch.size(); ++f.chord)
    if (ch[f.chord].lo <= z && z <= ch[f.chord].hi)
      break;
  if (f.chord == ch.size())
    return false;
  f.own = ch[f.chord];
  f.section = section_of(O, f.cell, structure_of(ch));
  return piece_frame(*f.section, c, f.piece);
}

// The cross-section point of mapped coordinates (s, t2) in the piece of f.
Vector2d section_point(const PointFrame& f, double s, double t2) {
  const CellPiece& pc = f.piece.piece;
  const int m2 = pc.mapping_axis, q2 = 1 - m2;
  PieceFrame::Chord ch = f.piece.chord;
  double at = pc.a + s * (pc.b - pc.a);
  if (s == 0 || s == 1) {
    ch = f.piece.side[s == 0 ? 0 : 1];
    if (ch.apex) {
      // The side is a point: the limit of the chords next to it.
      at = s == 0 ? pc.a + kApexOffset * (pc.b - pc.a) : pc.b - kApexOffset * (pc.b - pc.a);
      const Eigen::VectorXd& lines = m2 == 1 ? f.section->y : f.section->x;
      std::vector<double> runs = f.section->boundary.chords(q2, at);
      const auto k = static_cast<size_t>(pc.chord);
      const double mid = 2 * k + 1 < runs.size() ? 0.5 * (runs[2 * k] + runs[2 * k + 1])
                                                 : 0.5 * (lines(0) + lines(1));
      ch.lo = ch.hi = mid;
      at = s == 0 ? pc.a : pc.b;
    }
  }
  Vector2d c;
  c(q2) = at;
  c(m2) = ch.lo + t2 * (ch.hi - ch.lo);
  return c;
}

// The trace on chord k of the cross-section point c at mapped height t3: u with the zero
// substitution at the chord's ends on dG (seed 001, Theorem 5: traces zero on dG).
double chord_trace(const SolidInterflatation& O, int m, const Vector2d& c, const Chord& k,
                   double t3) {
  double v = O.u(lift(m, c, k.lo + t3 * (k.hi - k.lo)));
  if (!k.lo_grid)
    v -= (1 - t3) * O.u(lift(m, c, k.lo));
  if (!k.hi_grid)
    v -= t3 * O.u(lift(m, c, k.hi));
  return v;
}

// The trace at mapped (s, t2, t3) of the piece of f.
double mapped_trace(const SolidInterflatation& O, const PointFrame& f, double s, double t2,
                    double t3) {
  const CellFrame& cf = f.cell;
  const Vector2d c = section_point(f, s, t2);
  const std::vector<Chord> ch = cell_chords(O.boundary, cf.m, c, cf.z0, cf.z1);
  if (f.chord >= ch.size())
    return 0; // the chord shrank to a point of dG
  return chord_trace(O, cf.m, c, ch[f.chord], t3);
}

int fewest_structures_axis(const SolidBoundary& b, const std::array<Eigen::VectorXd, 3>& nodes,
                           const std::array<Eigen::Index, 3>& index) {
  int best = 2;
  size_t best_count = 0;
  for (int m = 2; m >= 0; --m) {
    const std::array<int, 2> q = others(m);
    const auto lo = [&](int a) {
      return nodes[static_cast<size_t>(a)](index[static_cast<size_t>(a)]);
    };
    const auto hi = [&](int a) {
      return nodes[static_cast<size_t>(a)](index[static_cast<size_t>(a)] + 1);
    };
    std::set<Structure> seen;
    for (int i = 0; i < kAxisProbes; ++i)
      for (int j = 0; j < kAxisProbes; ++j) {
        const Vector2d c(lo(q[0]) + (hi(q[0]) - lo(q[0])) * i / (kAxisProbes - 1),
                         lo(q[1]) + (hi(q[1]) - lo(q[1])) * j / (kAxisProbes - 1));
        seen.insert(structure_of(cell_chords(b, m, c, lo(m), hi(m))));
      }
    if (m == 2 || seen.size() < best_count) {
      best = m;
      best_count = seen.size();
    }
    if (best_count == 1) // one structure: the cell is a box or a curved box along m
      break;
  }
  return best;
}

} // namespace

SolidBoundary implicit_solid(std::function<double(const Vector3d&)> g,
                             const Eigen::AlignedBox3d& box, int samples) {
  if (samples < 2 || box.isEmpty())
    throw std::invalid_argument("implicit_solid: need samples >= 2 and a non-empty box");
  SolidBoundary b;
  b.box = box;
  b.chords = [g = std::move(g), samples](int axis, const Vector3d& p, double lo, double hi) {
    Vector3d x = p;
    return detail::sign_runs(
        [&](double s) {
          x(axis) = s;
          return g(x) > 0;
        },
        lo, hi, samples);
  };
  return b;
}

SolidInterflatation solid_interflatation(const SolidBoundary& boundary,
                                         const std::array<Eigen::VectorXd, 3>& nodes,
                                         std::function<double(const Vector3d&)> u, int mapping_axis,
                                         int samples) {
  for (int a = 0; a < 3; ++a) {
    const Eigen::VectorXd& v = nodes[static_cast<size_t>(a)];
    bool ok = v.size() >= 2;
    for (Eigen::Index i = 1; ok && i < v.size(); ++i)
      ok = v(i) > v(i - 1);
    if (!ok)
      throw std::invalid_argument("solid_interflatation: need >= 2 increasing planes per axis");
    if (v(0) > boundary.box.min()(a) || v(v.size() - 1) < boundary.box.max()(a))
      throw std::invalid_argument("solid_interflatation: the planes must cover the body's box");
  }
  if (mapping_axis < -1 || mapping_axis > 2 || samples < 2)
    throw std::invalid_argument("solid_interflatation: mapping axis -1..2, samples >= 2");
  SolidInterflatation O;
  O.boundary = boundary;
  O.nodes = nodes;
  O.u = std::move(u);
  O.samples = samples;
  O.mapping_axis = mapping_axis;
  O.cache = std::make_shared<SolidInterflatation::Cache>();
  return O;
}

double evaluate(const SolidInterflatation& O, const Vector3d& p) {
  PointFrame f;
  if (!point_frame(O, p, f)) {
    // p on the side of its cross-section piece (round-off): the operator equals the trace there.
    CellFrame cf;
    if (!locate(O, p, cf))
      return 0;
    const std::array<int, 2> q = others(cf.m);
    const Vector2d c(p(q[0]), p(q[1]));
    for (const Chord& k : cell_chords(O.boundary, cf.m, c, cf.z0, cf.z1))
      if (k.lo <= p(cf.m) && p(cf.m) <= k.hi)
        return chord_trace(O, cf.m, c, k, (p(cf.m) - k.lo) / (k.hi - k.lo));
    return 0;
  }
  const double s = f.piece.s, t2 = f.piece.t;
  const double t3 = (p(f.cell.m) - f.own.lo) / (f.own.hi - f.own.lo);
  // seed 001, Theorem 5, cell operator: the Boolean sum P1 + P2 + P3 - P1P2 - P1P3 - P2P3 +
  // P1P2P3 in (s, t2, t3) (digest §5 item 4), over the non-empty subsets of the projectors: each
  // subset interpolates linearly between the faces in its coordinates, sign (-1)^(|S|+1).
  const std::array<double, 3> x{s, t2, t3};
  double sum = 0;
  for (int mask = 1; mask < 8; ++mask) {
    const int bits = (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1);
    const double sign = bits % 2 == 1 ? 1.0 : -1.0;
    for (int corner = 0; corner < 8; ++corner) {
      if ((corner & ~mask) != 0)
        continue;
      std::array<double, 3> at = x;
      double w = 1;
      for (int a = 0; a < 3; ++a)
        if (mask & (1 << a)) {
          const bool one = (corner >> a) & 1;
          at[static_cast<size_t>(a)] = one ? 1.0 : 0.0;
          w *= one ? x[static_cast<size_t>(a)] : 1 - x[static_cast<size_t>(a)];
        }
      if (w != 0)
        sum += sign * w * mapped_trace(O, f, at[0], at[1], at[2]);
    }
  }
  return sum;
}

SolidCellKind cell_kind(const SolidInterflatation& O, const Vector3d& p) {
  PointFrame f;
  if (!point_frame(O, p, f))
    return SolidCellKind::split;
  const bool one_curved = f.own.lo_grid != f.own.hi_grid;
  const bool full = f.section->pieces.size() == 1 && f.section->pieces[0].size() == 1 &&
                    f.section->pieces[0][0].kind == CellKind::rectangle;
  if (full && f.own.lo_grid && f.own.hi_grid)
    return SolidCellKind::box;
  if (full && one_curved)
    return SolidCellKind::curved_box;
  if (!one_curved)
    return SolidCellKind::split;
  // A pyramid: the cross-section's curved side is where the chord shrinks to a point of dG (not
  // a change between two chord structures).
  const PieceFrame::Chord& c2 = f.piece.chord;
  const int m2 = f.piece.piece.mapping_axis;
  for (const bool hi : {false, true}) {
    if (hi ? c2.hi_grid : c2.lo_grid)
      continue;
    Vector2d end = section_point(f, f.piece.s, hi ? 1.0 : 0.0);
    // Just outside D: the structure there has fewer chords when the chord shrank.
    end(m2) += (hi ? 1 : -1) * kApexOffset * (f.cell.rect.max()(m2) - f.cell.rect.min()(m2));
    if (cell_chords(O.boundary, f.cell.m, end, f.cell.z0, f.cell.z1).size() <= f.chord)
      return SolidCellKind::pyramid;
  }
  return SolidCellKind::split;
}

} // namespace interlin
