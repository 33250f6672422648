// Theorem 4: interlineation on a plane region and the implicit equation of its boundary
// (operators/region_interlineation.h).
#include "interlin/interflatation/operators/region_interlineation.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::Vector2d;

namespace {

// Chord ends closer than this (relative to the cell) to a grid line are on the grid line; chords
// shorter are points (a triangle's apex).
constexpr double kRelativeTolerance = 1e-12;
// Where dG touches a grid line (a tangency), chord ends within the tolerance of the line make a
// sliver piece of width sqrt(2 tol R); pieces narrower than this (relative to the cell) are
// merged away, which covers radii of curvature R up to (1e-4)^2 / (2 1e-12) = 5000 cells.
constexpr double kSliverWidth = 1e-4;
// Bisection steps that locate a change of the chord structure inside a cell (2^-50 of a cell).
constexpr int kChangeBisections = 50;
// Changes of the chord structure located between two probes at most (a smooth boundary makes
// one or two: a region's end and a crossing of a grid line).
constexpr int kMaxChanges = 8;

Vector2d point(int axis, double c, double s) {
  Vector2d p;
  p(axis) = c;
  p(1 - axis) = s;
  return p;
}

// The chord of G on line {p(axis) = c} holding s, as (lo, hi); false when s is on none.
bool chord_at(const PlaneBoundary& b, int axis, double c, double s, double& lo, double& hi) {
  const std::vector<double> ch = b.chords(axis, c);
  for (size_t k = 0; k + 1 < ch.size(); k += 2)
    if (ch[k] <= s && s <= ch[k + 1]) {
      lo = ch[k];
      hi = ch[k + 1];
      return true;
    }
  return false;
}

// One chord of a cell: its ends clipped to the cell's range [y0, y1] of the mapping axis, and
// whether each end is a grid line (else dG).
struct Clipped {
  double lo, hi;
  bool lo_grid, hi_grid;
};

std::vector<Clipped> clipped_chords(const PlaneBoundary& b, int mapping, double c, double y0,
                                    double y1) {
  const double tol = kRelativeTolerance * (y1 - y0);
  std::vector<Clipped> out;
  const std::vector<double> ch = b.chords(1 - mapping, c);
  for (size_t k = 0; k + 1 < ch.size(); k += 2) {
    const double lo = std::max(ch[k], y0), hi = std::min(ch[k + 1], y1);
    if (hi - lo > tol)
      out.push_back({lo, hi, ch[k] <= y0 + tol, ch[k + 1] >= y1 - tol});
  }
  return out;
}

bool same_structure(const std::vector<Clipped>& a, const std::vector<Clipped>& b) {
  if (a.size() != b.size())
    return false;
  for (size_t k = 0; k < a.size(); ++k)
    if (a[k].lo_grid != b[k].lo_grid || a[k].hi_grid != b[k].hi_grid)
      return false;
  return true;
}

CellKind kind_of(int mapping, const Clipped& c, bool degenerate_side) {
  if (c.lo_grid && c.hi_grid)
    return CellKind::rectangle;
  if (!c.lo_grid && !c.hi_grid)
    return CellKind::lens;
  if (degenerate_side)
    return CellKind::triangle;
  if (mapping == 1)
    return c.hi_grid ? CellKind::curved_bottom : CellKind::curved_top;
  return c.hi_grid ? CellKind::curved_left : CellKind::curved_right;
}

// The cuts x0 < c_1 < ... < x1 of a cell without the pieces narrower than kSliverWidth: a sliver
// at a side of the cell joins its neighbouring piece; inside the cell both of its cuts go when the
// chord structure is the same on either side (dG touches a grid line there), else one cut at its
// middle stays. Otherwise a piece's side would be a line near, not on, the grid line, and the
// operator off by the sliver's width.
template <class Structure>
std::vector<double> without_slivers(const std::vector<double>& cuts, const Structure& structure) {
  const double x0 = cuts.front(), x1 = cuts.back();
  const double width = kSliverWidth * (x1 - x0);
  std::vector<double> kept{x0};
  for (size_t i = 1; i < cuts.size(); ++i) {
    if (cuts[i] - kept.back() >= width) {
      kept.push_back(cuts[i]);
    } else if (i + 1 == cuts.size()) { // at x1: the previous piece reaches x1
      if (kept.size() > 1)
        kept.pop_back();
      kept.push_back(x1);
    } else if (kept.size() > 1) { // inside: a touch, or a change located in the middle
      const double left = 0.5 * (kept[kept.size() - 2] + kept.back());
      const double right = 0.5 * (cuts[i] + cuts[i + 1]);
      if (same_structure(structure(left), structure(right)))
        kept.pop_back();
      else
        kept.back() = 0.5 * (kept.back() + cuts[i]);
    } // at x0: the next piece starts at x0
  }
  return kept;
}

// The pieces of a cell [x0, x1] (piece axis) x [y0, y1] (mapping axis) for one mapping axis.
// The chord structure is probed at `samples` + 1 equally spaced positions, the cell's sides and
// where dG crosses the cell's other two sides (so that slivers at a side are not missed); each
// change between probes is located by bisection, and again between the change and the next
// probe when the structure there differs (several changes between two probes).
std::vector<CellPiece> cell_pieces(const PlaneBoundary& b, int mapping, double x0, double x1,
                                   double y0, double y1, int samples) {
  auto structure = [&](double c) { return clipped_chords(b, mapping, c, y0, y1); };
  std::vector<double> probes;
  for (int k = 0; k <= samples; ++k)
    probes.push_back(x0 + (x1 - x0) * k / samples);
  for (const double side : {y0, y1})
    for (const double c : b.chords(mapping, side))
      if (c > x0 && c < x1)
        probes.push_back(c);
  std::sort(probes.begin(), probes.end());
  std::vector<double> cuts{x0};
  for (size_t k = 0; k + 1 < probes.size(); ++k) {
    double lo = probes[k];
    const std::vector<Clipped> end = structure(probes[k + 1]);
    std::vector<Clipped> from = structure(lo);
    for (int change = 0; change < kMaxChanges && !same_structure(from, end); ++change) {
      double hi = probes[k + 1];
      for (int it = 0; it < kChangeBisections; ++it) {
        const double m = 0.5 * (lo + hi);
        (same_structure(structure(m), from) ? lo : hi) = m;
      }
      cuts.push_back(hi);
      lo = hi;
      from = structure(hi);
      if (!(hi < probes[k + 1]))
        break;
    }
  }
  cuts.push_back(x1);
  cuts = without_slivers(cuts, structure);
  std::vector<CellPiece> pieces;
  const double tol = kRelativeTolerance * (y1 - y0);
  std::vector<std::vector<Clipped>> mids;
  for (size_t seg = 0; seg + 1 < cuts.size(); ++seg)
    mids.push_back(structure(0.5 * (cuts[seg] + cuts[seg + 1])));
  // A side is an apex (a triangle's degenerate side) when its line holds fewer chords, or a
  // shorter one, than the piece: the cell's own sides are probed, a change point compares the
  // neighbouring segment (the region ends there: the chord shrinks to a point of dG).
  const auto apex = [&](size_t seg, size_t k, bool right) {
    const size_t next = right ? seg + 1 : seg - 1;
    const bool cell_side = right ? seg + 2 == cuts.size() : seg == 0;
    const std::vector<Clipped> at = cell_side ? structure(right ? x1 : x0) : mids[next];
    return at.size() != mids[seg].size() || at[k].hi - at[k].lo <= tol;
  };
  for (size_t seg = 0; seg < mids.size(); ++seg)
    for (size_t k = 0; k < mids[seg].size(); ++k) {
      CellPiece p;
      p.mapping_axis = mapping;
      p.a = cuts[seg];
      p.b = cuts[seg + 1];
      p.chord = static_cast<int>(k);
      p.apex_a = apex(seg, k, false);
      p.apex_b = apex(seg, k, true);
      p.kind = kind_of(mapping, mids[seg][k], p.apex_a || p.apex_b);
      pieces.push_back(p);
    }
  return pieces;
}

size_t segment_count(const std::vector<CellPiece>& pieces) {
  size_t n = 0;
  for (size_t i = 0; i < pieces.size(); ++i)
    n += (i == 0 || pieces[i].a != pieces[i - 1].a) ? 1 : 0;
  return n;
}

// The trace on a side line {p(q) = c} of a piece, at mapped height t on its chord k (0 when the
// side is an apex).
struct Side {
  bool apex = true;
  double lo = 0, hi = 0;
};

Side side_chord(const RegionInterlineation& O, const CellPiece& p, bool right, double y0,
                double y1) {
  Side s;
  if (right ? p.apex_b : p.apex_a)
    return s;
  const std::vector<Clipped> at =
      clipped_chords(O.boundary, p.mapping_axis, right ? p.b : p.a, y0, y1);
  const auto k = static_cast<size_t>(p.chord);
  if (k < at.size()) {
    s.apex = false;
    s.lo = at[k].lo;
    s.hi = at[k].hi;
  }
  return s;
}

} // namespace

double line_trace(const RegionInterlineation& O, int axis, double c, double s) {
  double lo = 0, hi = 0;
  if (!chord_at(O.boundary, axis, c, s, lo, hi) || !(hi > lo))
    return 0;
  // Zero substitution on dG: subtract the linear interpolant of u at the chord's ends.
  const double ulo = O.u(point(axis, c, lo)), uhi = O.u(point(axis, c, hi));
  return O.u(point(axis, c, s)) - (ulo * (hi - s) + uhi * (s - lo)) / (hi - lo);
}

RegionInterlineation region_interlineation(const PlaneBoundary& boundary, const Eigen::VectorXd& x,
                                           const Eigen::VectorXd& y,
                                           std::function<double(const Vector2d&)> u, int samples) {
  const auto increasing = [](const Eigen::VectorXd& v) {
    for (Eigen::Index i = 1; i < v.size(); ++i)
      if (!(v(i) > v(i - 1)))
        return false;
    return v.size() >= 2;
  };
  if (!increasing(x) || !increasing(y) || samples < 1)
    throw std::invalid_argument("region_interlineation: need >= 2 increasing lines per axis");
  if (x(0) > boundary.box.min()(0) || x(x.size() - 1) < boundary.box.max()(0) ||
      y(0) > boundary.box.min()(1) || y(y.size() - 1) < boundary.box.max()(1))
    throw std::invalid_argument("region_interlineation: the grid lines must cover the region");
  RegionInterlineation O;
  O.boundary = boundary;
  O.x = x;
  O.y = y;
  O.u = std::move(u);
  for (Eigen::Index j = 0; j + 1 < y.size(); ++j)
    for (Eigen::Index i = 0; i + 1 < x.size(); ++i) {
      // Mapping along y (chords of vertical lines) unless along x needs fewer pieces.
      std::vector<CellPiece> py = cell_pieces(boundary, 1, x(i), x(i + 1), y(j), y(j + 1), samples);
      std::vector<CellPiece> px = cell_pieces(boundary, 0, y(j), y(j + 1), x(i), x(i + 1), samples);
      O.pieces.push_back(segment_count(px) < segment_count(py) ? std::move(px) : std::move(py));
    }
  return O;
}

bool piece_frame(const RegionInterlineation& O, const Vector2d& p, PieceFrame& f) {
  const auto cell = [](const Eigen::VectorXd& v, double s) -> Eigen::Index {
    if (!(s >= v(0) && s <= v(v.size() - 1)))
      return -1;
    const auto it = std::upper_bound(v.data(), v.data() + v.size(), s);
    return std::min<Eigen::Index>(it - v.data() - 1, v.size() - 2);
  };
  const Eigen::Index i = cell(O.x, p(0)), j = cell(O.y, p(1));
  if (i < 0 || j < 0)
    return false;
  const std::vector<CellPiece>& pieces = O.pieces[static_cast<size_t>(i + (O.x.size() - 1) * j)];
  for (const CellPiece& pc : pieces) {
    const int m = pc.mapping_axis, q = 1 - m;
    const Eigen::VectorXd& lines_m = m == 1 ? O.y : O.x;
    const Eigen::Index cm = m == 1 ? j : i;
    const double y0 = lines_m(cm), y1 = lines_m(cm + 1);
    if (!(pc.a <= p(q) && p(q) <= pc.b))
      continue;
    const std::vector<Clipped> at = clipped_chords(O.boundary, m, p(q), y0, y1);
    const auto k = static_cast<size_t>(pc.chord);
    if (k >= at.size() || !(at[k].lo <= p(m) && p(m) <= at[k].hi))
      continue;
    const Clipped& c = at[k];
    f.piece = pc;
    f.y0 = y0;
    f.y1 = y1;
    f.t = (p(m) - c.lo) / (c.hi - c.lo);
    f.s = (p(q) - pc.a) / (pc.b - pc.a);
    f.chord = {false, c.lo, c.hi, c.lo_grid, c.hi_grid};
    for (const bool right : {false, true}) {
      const Side sd = side_chord(O, pc, right, y0, y1);
      f.side[right ? 1 : 0] = {sd.apex, sd.lo, sd.hi, true, true};
    }
    return true;
  }
  return false;
}

double evaluate(const RegionInterlineation& O, const Vector2d& p) {
  PieceFrame f;
  if (!piece_frame(O, p, f))
    return 0;
  const CellPiece& pc = f.piece;
  const int m = pc.mapping_axis, q = 1 - m;
  const double s = f.s, t = f.t;
  // Side traces L (at a), R (at b) on their chords; grid-line traces B (at lo), T (at hi).
  const auto side = [&](int k, double tt) {
    const PieceFrame::Chord& sd = f.side[static_cast<size_t>(k)];
    return sd.apex ? 0.0 : line_trace(O, q, k == 0 ? pc.a : pc.b, sd.lo + tt * (sd.hi - sd.lo));
  };
  const double L0 = side(0, 0), L1 = side(0, 1), Lt = side(0, t);
  const double R0 = side(1, 0), R1 = side(1, 1), Rt = side(1, t);
  const double B = f.chord.lo_grid ? line_trace(O, m, f.y0, p(q)) : 0.0;
  const double T = f.chord.hi_grid ? line_trace(O, m, f.y1, p(q)) : 0.0;
  return (1 - s) * Lt + s * Rt + (1 - t) * B + t * T -
         ((1 - s) * (1 - t) * L0 + s * (1 - t) * R0 + (1 - s) * t * L1 + s * t * R1);
}

} // namespace interlin
