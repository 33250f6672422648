// seed 001 §2.5 (surface through sections and user lines); digest 001 §5.1 [SUPPLEMENT] (Gordon).
#include "interlin/reconstruction/loft/guided_loft.h"

#include "cross_validate_span.h"
#include "section_curves.h"

#include "interlin/interlineation/gordon_bspline.h"
#include "interlin/interlineation/spline_space.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knots.h"
#include "interlin/splines/parameterization.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

// Thresholds, each a fraction of the quantity it is compared with.
// A crossing closer than this to a section point (fraction of the parameter spacing there) is
// that point: inserting it would create a sliver interval in the section's parameters.
constexpr double kSnapFraction = 0.01;
// Samples per parameter interval of the section curve around its point nearest to a guide: at
// 16 per interval the distance to the guide is unimodal between neighbouring samples, so the
// golden-section search that follows converges to the closest approach.
constexpr int kApproachSamples = 16;
// Golden-section steps: 80 shrink the bracket by 0.618^80 ~ 2e-17, below double resolution.
constexpr int kGoldenSteps = 80;
// Largest move of a feature between neighbouring sections, as a fraction of the loop: beyond
// half the loop it has crossed another guide or the line of start points.
constexpr double kMaxFeatureMove = 0.5;
// Interior knots of different span curves closer than this fraction of the section spacing are
// made equal, so the surface's knot union has no span below ~1e-3 of its neighbours, where the
// explicit basis is exact to round-off (docs/formulas.md, span ratios).
constexpr double kSpanKnotGap = 1e-3;
// Samples per span of each guide curve in the exactness check.
constexpr int kCurveCheckSamples = 64;
// gordon_bspline's compatibility tolerance |C_k(u_l) - G_l(v_k)| / max(1, |Q_kl|): the
// crossings are section rows, so the curves meet to round-off.
constexpr double kGordonTolerance = 1e-10;

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

// Closest point of the polyline G (#G by 3) to X: its position m + s (segment m, fraction s).
double closest_on_polyline(const MatrixXd& G, const Vector3d& X, Vector3d& foot) {
  double best = INFINITY, pos = 0;
  for (Index m = 0; m + 1 < G.rows(); ++m) {
    const Vector3d a = G.row(m).transpose(), d = G.row(m + 1).transpose() - a;
    const double s = std::clamp((X - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const Vector3d f = a + s * d;
    if ((f - X).squaredNorm() < best) {
      best = (f - X).squaredNorm();
      pos = static_cast<double>(m) + s;
      foot = f;
    }
  }
  return pos;
}

// Where a guide polyline G passes closest to a closed section curve C (its points P at the
// parameters s, s(#P) = 1): the section point nearest to the polyline, then dense samples of the
// curve on the two intervals either side, then golden-section search of the distance between
// the neighbouring samples (the distance is unimodal there).
struct Approach {
  double pos = 0, u = 0, distance = 0;
  Vector3d point;
};

Approach closest_approach(const MatrixXd& G, const PiecewiseCurve& C, const MatrixXd& P,
                          const VectorXd& s) {
  const Index n = P.rows();
  const auto dist = [&](double u) {
    Vector3d foot;
    const Vector3d c = evaluate(C, VectorXd::Constant(1, u), 0).row(0).transpose();
    closest_on_polyline(G, c, foot);
    return (foot - c).norm();
  };
  Index best_i = 0;
  double best = INFINITY;
  for (Index i = 0; i < n; ++i) {
    Vector3d foot;
    closest_on_polyline(G, P.row(i).transpose(), foot);
    const double d = (foot - P.row(i).transpose()).norm();
    if (d < best)
      best = d, best_i = i;
  }
  // Samples on the intervals [s(i-2), s(i+2)] around the best point (wrapping around).
  const auto site = [&](Index i) {
    const Index w = ((i % n) + n) % n;
    return s(w) + static_cast<double>((i - w) / n);
  };
  const int per = kApproachSamples;
  double u_best = s(best_i), h = 0;
  for (Index i = best_i - 2; i < best_i + 2; ++i) {
    const double a = site(i), b = site(i + 1);
    for (int q = 0; q < per; ++q) {
      const double u = a + (b - a) * q / per, d = dist(u);
      if (d < best)
        best = d, u_best = u, h = (b - a) / per;
    }
  }
  if (h == 0) // the data point itself was best: search the neighbouring sample spacing
    h = std::min(site(best_i + 1) - site(best_i), site(best_i) - site(best_i - 1)) / per;
  // Golden section on [u_best - h, u_best + h].
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double a = u_best - h, b = u_best + h, x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = dist(x1), f2 = dist(x2);
  for (int it = 0; it < kGoldenSteps && b - a > 1e-16; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = dist(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = dist(x2);
    }
  }
  Approach r;
  r.u = f1 < f2 ? x1 : x2;
  if (std::min(f1, f2) > best)
    r.u = u_best;
  r.u -= std::floor(r.u);
  r.point = evaluate(C, VectorXd::Constant(1, r.u), 0).row(0).transpose();
  Vector3d foot;
  r.pos = closest_on_polyline(G, r.point, foot);
  r.distance = (foot - r.point).norm();
  return r;
}

// A feature that must sit at one parameter u around all sections: a guide, or the opposite edge
// of aligned sections. rows[k]: its row in section k (after insertions).
struct Feature {
  std::string name;
  long line = 0; // guide's first line, 0 for the edge
  std::vector<Index> rows;
  int guide = -1;
};

// The interval [s(i), s(i+1)] of the closed parameters s (#P + 1 values) that holds u.
Index interval_of(const VectorXd& s, double u) {
  const Index n = s.size() - 1;
  return std::min<Index>(std::upper_bound(s.data(), s.data() + n + 1, u) - s.data() - 1, n - 1);
}

// Step 1. The crossing of every guide with every section: its closest approach to the section's
// provisional curve (periodic interpolation at the section's own chord parameters own_u[k]).
// Output cross[l][k]. Throws InputError naming the guide's line where a guide misses a section by
// more than tol.
std::vector<std::vector<Approach>> find_crossings(const std::vector<PreparedSection>& sections,
                                                  const GuideSet& gs, const LoftOptions& o,
                                                  double tol, double tolerance_fraction,
                                                  std::vector<VectorXd>& own_u) {
  std::vector<std::vector<Approach>> cross(gs.guides.size());
  own_u.resize(sections.size());
  for (size_t k = 0; k < sections.size(); ++k) {
    const MatrixXd& P = sections[k].points;
    own_u[k] = chord_parameters(P, true, o.section_exponent);
    const PiecewiseCurve C = to_piecewise(interpolate_closed(P, own_u[k], o.degree));
    for (size_t l = 0; l < gs.guides.size(); ++l) {
      const Guide& g = gs.guides[l];
      const Approach a = closest_approach(g.points, C, P, own_u[k]);
      if (!(a.distance <= tol))
        throw_input_error(gs.path, g.lines[static_cast<size_t>(std::lround(a.pos))],
                          "guide " + g.id + " passes " + fmt(a.distance) + " from section " +
                              sections[k].id + " (more than the tolerance " + fmt(tol) + " = " +
                              fmt(tolerance_fraction) +
                              " x bounding-box diagonal); every guide must cross every section");
      cross[l].push_back(a);
    }
  }
  return cross;
}

// Step 2, for section k: each crossing becomes a row of the section, the nearest point when
// within kSnapFraction of the parameter spacing, else a point inserted into the section (it lies
// on the section curve). Sets features[l].rows[k]; notes each insertion. Throws InputError when
// two guides cross the section at one point.
void insert_crossings(PreparedSection& sec, Index k, const VectorXd& s, const GuideSet& gs,
                      const std::vector<std::vector<Approach>>& cross,
                      std::vector<Feature>& features, std::vector<std::string>& notes) {
  const Index n = sec.points.rows(), L = static_cast<Index>(gs.guides.size());
  const size_t ks = static_cast<size_t>(k);
  struct Place { // an inserted crossing: after row `row`, at parameter u
    Index row;
    double u;
    Index guide;
  };
  std::vector<Place> inserts;
  std::vector<Index> row_of(static_cast<size_t>(L), -1);
  for (Index l = 0; l < L; ++l) {
    const double u = cross[static_cast<size_t>(l)][ks].u;
    const Index i = interval_of(s, u);
    const double h = s(i + 1) - s(i);
    if (u - s(i) <= kSnapFraction * h)
      row_of[static_cast<size_t>(l)] = i;
    else if (s(i + 1) - u <= kSnapFraction * h)
      row_of[static_cast<size_t>(l)] = (i + 1) % n;
    else
      inserts.push_back({i, u, l});
  }
  std::sort(inserts.begin(), inserts.end(),
            [](const Place& a, const Place& b) { return a.u < b.u; });
  // Two guides through one point of the section: no common parameter can separate them.
  for (Index a = 0; a < L; ++a)
    for (Index b = a + 1; b < L; ++b) {
      const double ua = cross[static_cast<size_t>(a)][ks].u,
                   ub = cross[static_cast<size_t>(b)][ks].u;
      const Index ra = row_of[static_cast<size_t>(a)], rb = row_of[static_cast<size_t>(b)];
      const Index i = interval_of(s, ua);
      if ((ra >= 0 && ra == rb) ||
          (ra < 0 && rb < 0 && std::abs(ua - ub) <= kSnapFraction * (s(i + 1) - s(i))))
        throw_input_error(gs.path, gs.guides[static_cast<size_t>(b)].lines[0],
                          "guides " + gs.guides[static_cast<size_t>(a)].id + " and " +
                              gs.guides[static_cast<size_t>(b)].id + " cross section " + sec.id +
                              " at the same point; guides must cross each section "
                              "at distinct points");
    }
  // Rebuild the section with the inserted crossings; new index of every old row.
  std::vector<Index> new_row(static_cast<size_t>(n));
  MatrixXd pts(n + static_cast<Index>(inserts.size()), 3);
  std::vector<long> lines;
  std::vector<Index> source;
  size_t next = 0;
  Index w = 0;
  for (Index i = 0; i < n; ++i) {
    new_row[static_cast<size_t>(i)] = w;
    pts.row(w++) = sec.points.row(i);
    lines.push_back(sec.lines[static_cast<size_t>(i)]);
    source.push_back(sec.source[static_cast<size_t>(i)]);
    for (; next < inserts.size() && inserts[next].row == i; ++next) {
      const Approach& a = cross[static_cast<size_t>(inserts[next].guide)][ks];
      const Guide& g = gs.guides[static_cast<size_t>(inserts[next].guide)];
      row_of[static_cast<size_t>(inserts[next].guide)] = w;
      pts.row(w++) = a.point.transpose();
      lines.push_back(g.lines[static_cast<size_t>(std::lround(a.pos))]);
      source.push_back(-1);
      notes.push_back("section " + sec.id + ": crossing with guide " + g.id +
                      " inserted between points " + std::to_string(i) + " and " +
                      std::to_string((i + 1) % n));
    }
  }
  for (Index l = 0; l < L; ++l) {
    Index& row = row_of[static_cast<size_t>(l)];
    const bool inserted =
        std::any_of(inserts.begin(), inserts.end(), [&](const Place& p) { return p.guide == l; });
    if (!inserted)
      row = new_row[static_cast<size_t>(row)];
    features[static_cast<size_t>(l)].rows[ks] = row;
  }
  if (sec.le >= 0)
    sec.le = new_row[static_cast<size_t>(sec.le)];
  if (sec.te >= 0)
    sec.te = new_row[static_cast<size_t>(sec.te)];
  sec.points = pts;
  sec.lines = lines;
  sec.source = source;
}

// Rolls a section so that row r0 becomes row 0 (its features' rows with it).
void roll_section(PreparedSection& sec, size_t k, Index r0, std::vector<Feature>& features) {
  const Index n = sec.points.rows();
  const auto roll = [&](Index i) { return (i - r0 + n) % n; };
  MatrixXd pts(n, 3);
  std::vector<long> lines(static_cast<size_t>(n));
  std::vector<Index> source(static_cast<size_t>(n));
  for (Index i = 0; i < n; ++i) {
    pts.row(roll(i)) = sec.points.row(i);
    lines[static_cast<size_t>(roll(i))] = sec.lines[static_cast<size_t>(i)];
    source[static_cast<size_t>(roll(i))] = sec.source[static_cast<size_t>(i)];
  }
  sec.points = pts;
  sec.lines = lines;
  sec.source = source;
  if (sec.le >= 0)
    sec.le = roll(sec.le);
  if (sec.te >= 0)
    sec.te = roll(sec.te);
  for (Feature& f : features)
    f.rows[k] = roll(f.rows[k]);
}

// Step 2b. Kept starts (--align first) must not cross a guide between sections: when the guides
// come in one cyclic order around every section but the start points cut that order
// differently, every section is started at its crossing with the first guide instead.
void start_at_first_guide(LoftResult& r, const GuideSet& gs, std::vector<Feature>& features) {
  const size_t K = r.sections.size(), L = features.size();
  if (L < 2)
    return;
  const auto order_in = [&](size_t k) {
    std::vector<Index> idx(L);
    for (size_t l = 0; l < L; ++l)
      idx[l] = static_cast<Index>(l);
    std::sort(idx.begin(), idx.end(), [&](Index a, Index b) {
      return features[static_cast<size_t>(a)].rows[k] < features[static_cast<size_t>(b)].rows[k];
    });
    return idx;
  };
  const auto rotated = [](std::vector<Index> idx) {
    std::rotate(idx.begin(), std::find(idx.begin(), idx.end(), 0), idx.end());
    return idx;
  };
  const std::vector<Index> first = order_in(0);
  bool same = true, cyclic = true;
  for (size_t k = 1; k < K; ++k) {
    same = same && order_in(k) == first;
    cyclic = cyclic && rotated(order_in(k)) == rotated(first);
  }
  if (same || !cyclic)
    return;
  for (size_t k = 0; k < K; ++k)
    roll_section(r.sections[k], k, features[0].rows[k], features);
  r.notes.push_back("sections started at their crossing with guide " + gs.guides[0].id +
                    ": the given start points would cross a guide between sections");
}

// Step 3a. With an aligned start, the opposite edge is a feature too (unless a guide runs
// along it).
void add_opposite_edge(const LoftResult& r, StartAlign align, std::vector<Feature>& features) {
  if (align == StartAlign::first)
    return;
  Feature edge{
      align == StartAlign::leading_edge ? "the trailing edge" : "the leading edge", 0, {}, -1};
  for (const PreparedSection& s : r.sections)
    edge.rows.push_back(align == StartAlign::leading_edge ? s.te : s.le);
  if (std::none_of(features.begin(), features.end(),
                   [&](const Feature& f) { return f.rows == edge.rows; }))
    features.push_back(edge);
}

// Step 3b. The features must be distinct points of every section, start on every section's start
// point or on none, keep one order around all sections (sorted here by it) and move less than
// kMaxFeatureMove of the loop between neighbouring sections. Throws InputError naming the guide.
void check_features(const LoftResult& r, const GuideSet& gs, std::vector<Feature>& features) {
  const size_t K = r.sections.size();
  const auto line_of = [](const Feature& f) { return f.guide >= 0 ? f.line : 0L; };
  for (size_t a = 0; a < features.size(); ++a)
    for (size_t b = a + 1; b < features.size(); ++b)
      for (size_t k = 0; k < K; ++k)
        if (features[a].rows[k] == features[b].rows[k])
          throw_input_error(gs.path, line_of(features[b]),
                            features[a].name + " and " + features[b].name + " cross section " +
                                r.sections[k].id +
                                " at the same point; guides must cross each section at distinct "
                                "points");
  std::sort(features.begin(), features.end(),
            [](const Feature& a, const Feature& b) { return a.rows[0] < b.rows[0]; });
  for (const Feature& f : features)
    for (size_t k = 1; k < K; ++k)
      if ((f.rows[0] == 0) != (f.rows[k] == 0))
        throw_input_error(gs.path, line_of(f),
                          f.name + " passes through the start point of section " +
                              r.sections[0].id + " but not of section " + r.sections[k].id +
                              "; start every section on it or on none (see --align)");
  for (size_t a = 0; a + 1 < features.size(); ++a)
    for (size_t k = 1; k < K; ++k)
      if (!(features[a].rows[k] < features[a + 1].rows[k]))
        throw_input_error(gs.path, line_of(features[a + 1]),
                          features[a].name + " and " + features[a + 1].name + " cross section " +
                              r.sections[k].id + " in the opposite order to section " +
                              r.sections[0].id);
  // Positions as fractions of each section's chord length from its start.
  for (size_t k = 0; k + 1 < K; ++k) {
    const VectorXd f0 = chord_parameters(r.sections[k].points, true);
    const VectorXd f1 = chord_parameters(r.sections[k + 1].points, true);
    for (const Feature& f : features)
      if (std::abs(f1(f.rows[k + 1]) - f0(f.rows[k])) > kMaxFeatureMove)
        throw_input_error(gs.path, line_of(f),
                          f.name + " moves by more than half the section between sections " +
                              r.sections[k].id + " and " + r.sections[k + 1].id +
                              ": it crosses another guide or the line of the sections' start "
                              "points there");
  }
}

// Step 4. Landmarks of the section curves: every feature except one through the start.
std::vector<std::vector<Index>> feature_landmarks(const std::vector<Feature>& features, size_t K) {
  std::vector<std::vector<Index>> landmarks(K);
  for (const Feature& f : features)
    if (f.rows[0] != 0)
      for (size_t k = 0; k < K; ++k)
        landmarks[k].push_back(f.rows[k]);
  return landmarks;
}

// The parameter u of each guide: its landmark's common parameter (0 through the start).
std::vector<double> guide_parameters(const std::vector<Feature>& features,
                                     const std::vector<double>& landmark_u, size_t L) {
  std::vector<double> gu(L);
  size_t m = 0;
  for (const Feature& f : features) {
    if (f.guide >= 0)
      gu[static_cast<size_t>(f.guide)] = f.rows[0] == 0 ? 0.0 : landmark_u[m];
    if (f.rows[0] != 0)
      ++m;
  }
  return gu;
}

// Step 5. One guide's points along the span: its orientation (from the first section to the
// last), its crossings at v_k (the sections' rows `rows`), its own points between them at
// parameters proportional to arc length; pos[k] is the polyline position of crossing k.
// Throws InputError for guides that meet the sections out of order, meet two sections at one
// point, or run beyond the first or last section.
GuideFit fit_guide(const Guide& g, std::vector<double> pos, const std::vector<Index>& rows,
                   const LoftResult& r, const std::string& path) {
  const Index K = static_cast<Index>(r.sections.size()), n = g.points.rows();
  const VectorXd& v = r.section_v;
  GuideFit fit;
  fit.id = g.id;
  bool up = true, down = true;
  for (Index k = 0; k + 1 < K; ++k) {
    up = up && pos[static_cast<size_t>(k + 1)] > pos[static_cast<size_t>(k)];
    down = down && pos[static_cast<size_t>(k + 1)] < pos[static_cast<size_t>(k)];
  }
  if (!up && !down)
    throw_input_error(path, g.lines[0],
                      "guide " + g.id +
                          " does not run from the first section to the last: it "
                          "meets the sections out of their order");
  fit.reversed = down;
  std::vector<Index> order(static_cast<size_t>(n)); // input index of polyline vertex j
  for (Index j = 0; j < n; ++j)
    order[static_cast<size_t>(j)] = down ? n - 1 - j : j;
  MatrixXd G(n, 3);
  for (Index j = 0; j < n; ++j)
    G.row(j) = g.points.row(order[static_cast<size_t>(j)]);
  if (down)
    for (double& p : pos)
      p = static_cast<double>(n - 1) - p;
  // Arc length at polyline positions.
  VectorXd arc = VectorXd::Zero(n);
  for (Index j = 1; j < n; ++j)
    arc(j) = arc(j - 1) + (G.row(j) - G.row(j - 1)).norm();
  const auto arc_at = [&](double p) {
    const Index m = std::min<Index>(static_cast<Index>(std::floor(p)), n - 2);
    return arc(m) + (p - static_cast<double>(m)) * (arc(m + 1) - arc(m));
  };
  // A vertex within kSnapFraction of a segment of a crossing is replaced by the crossing.
  std::vector<Index> by_crossing(static_cast<size_t>(n), -1);
  for (Index k = 0; k < K; ++k) {
    const double pk = pos[static_cast<size_t>(k)];
    const Index j = std::lround(pk);
    if (std::abs(pk - static_cast<double>(j)) > kSnapFraction)
      continue;
    if (by_crossing[static_cast<size_t>(j)] >= 0)
      throw_input_error(
          path, g.lines[static_cast<size_t>(order[static_cast<size_t>(j)])],
          "guide " + g.id + " meets sections " +
              r.sections[static_cast<size_t>(by_crossing[static_cast<size_t>(j)])].id + " and " +
              r.sections[static_cast<size_t>(k)].id + " at this one point");
    by_crossing[static_cast<size_t>(j)] = k;
  }
  for (Index j = 0; j < n; ++j)
    if (by_crossing[static_cast<size_t>(j)] < 0 &&
        (static_cast<double>(j) < pos.front() || static_cast<double>(j) > pos.back()))
      throw_input_error(path, g.lines[static_cast<size_t>(order[static_cast<size_t>(j)])],
                        "guide " + g.id +
                            ": this point lies beyond the first or last section; a guide runs "
                            "from the first section to the last");
  std::vector<Eigen::RowVector3d> pts;
  std::vector<double> site;
  fit.input_row.assign(static_cast<size_t>(n), -1);
  for (Index k = 0; k < K; ++k) {
    // The crossing's point is the section's row (a section point or the inserted crossing).
    fit.crossing.push_back(static_cast<Index>(pts.size()));
    pts.push_back(r.sections[static_cast<size_t>(k)].points.row(rows[static_cast<size_t>(k)]));
    site.push_back(v(k));
    const Index j = std::lround(pos[static_cast<size_t>(k)]);
    const bool on_vertex = by_crossing[static_cast<size_t>(j)] == k;
    fit.source.push_back(on_vertex ? order[static_cast<size_t>(j)] : -1);
    if (on_vertex)
      fit.input_row[static_cast<size_t>(order[static_cast<size_t>(j)])] = fit.crossing.back();
    if (k + 1 == K)
      break;
    const double pk = pos[static_cast<size_t>(k)], pn = pos[static_cast<size_t>(k + 1)];
    const double a0 = arc_at(pk), a1 = arc_at(pn);
    for (Index j2 = 0; j2 < n; ++j2) {
      const double dj = static_cast<double>(j2);
      if (by_crossing[static_cast<size_t>(j2)] < 0 && dj > pk && dj < pn) {
        fit.input_row[static_cast<size_t>(order[static_cast<size_t>(j2)])] =
            static_cast<Index>(pts.size());
        pts.push_back(G.row(j2));
        site.push_back(v(k) + (v(k + 1) - v(k)) * (arc(j2) - a0) / (a1 - a0));
        fit.source.push_back(order[static_cast<size_t>(j2)]);
      }
    }
  }
  fit.points.resize(static_cast<Index>(pts.size()), 3);
  for (size_t i = 0; i < pts.size(); ++i)
    fit.points.row(static_cast<Index>(i)) = pts[i];
  fit.v = Eigen::Map<const VectorXd>(site.data(), static_cast<Index>(site.size()));
  return fit;
}

// Step 6. The guide curves G_l(v) and the knots of the blending functions along the span, each
// by averaging its own sites (well-conditioned collocation), interior knots of different curves
// closer than kSpanKnotGap of the section spacing made equal; a guide point closer than that to
// a crossing along the span is moved off it in parameter (not in space). Output: the curves, and
// blend_knots for the section blending functions. Throws InputError for guide points too close
// along the span to be interpolated.
std::vector<BSplineCurve> guide_curves(std::vector<GuideFit>& fits, const VectorXd& v, int q,
                                       const std::string& path, VectorXd& blend_knots) {
  const Index K = v.size();
  const auto interval = [&](double x) {
    return std::min<Index>(std::upper_bound(v.data(), v.data() + K, x) - v.data() - 1, K - 2);
  };
  const auto gap = [&](double x) {
    const Index k = interval(x);
    return kSpanKnotGap * (v(k + 1) - v(k));
  };
  std::vector<VectorXd> knots = {averaged_knots(v, q)};
  for (GuideFit& fit : fits) {
    for (Index i = 0; i < fit.v.size(); ++i)
      if (std::find(fit.crossing.begin(), fit.crossing.end(), i) == fit.crossing.end()) {
        const Index k = interval(fit.v(i));
        fit.v(i) = std::clamp(fit.v(i), v(k) + gap(fit.v(i)), v(k + 1) - gap(fit.v(i)));
      }
    for (Index i = 1; i < fit.v.size(); ++i)
      if (!(fit.v(i) > fit.v(i - 1)))
        throw_input_error(path, 0,
                          "guide " + fit.id +
                              ": two of its points are too close along the span to be "
                              "interpolated (closer than 1e-3 of the section spacing)");
    knots.push_back(averaged_knots(fit.v, q));
  }
  detail::snap_values(knots, q + 1, gap);
  std::vector<BSplineCurve> curves;
  for (size_t l = 0; l < fits.size(); ++l)
    curves.push_back(interpolate_in_space(fits[l].points, fits[l].v, knots[l + 1], q));
  blend_knots = knots[0];
  return curves;
}

// Step 7. The Gordon surface of the section curves and the guide curves (ordered by u).
BSplineSurface gordon_of(const std::vector<BSplineCurve>& sections, const VectorXd& v,
                         const std::vector<GuideFit>& fits, const std::vector<BSplineCurve>& curves,
                         int q, const VectorXd& blend_knots) {
  std::vector<size_t> by_u(fits.size());
  for (size_t l = 0; l < by_u.size(); ++l)
    by_u[l] = l;
  std::sort(by_u.begin(), by_u.end(), [&](size_t a, size_t b) { return fits[a].u < fits[b].u; });
  std::vector<BSplineCurve> guides;
  VectorXd u(static_cast<Index>(fits.size()));
  for (size_t l = 0; l < by_u.size(); ++l) {
    guides.push_back(curves[by_u[l]]);
    u(static_cast<Index>(l)) = fits[by_u[l]].u;
  }
  return gordon_bspline(sections, v, guides, u, q, true, kGordonTolerance, blend_knots);
}

// Step 8. Exactness along the guides: every fitted point, kCurveCheckSamples per span of each
// guide curve, and the guides' own input points at their parameters.
void guide_deviation(GuidedLoftResult& R, const GuideSet& gs,
                     const std::vector<BSplineCurve>& curves) {
  const PiecewiseSurface S = to_piecewise(R.loft.surface);
  for (size_t l = 0; l < R.guides.size(); ++l) {
    GuideFit& fit = R.guides[l];
    fit.deviation.resize(fit.v.size());
    for (Index i = 0; i < fit.v.size(); ++i)
      fit.deviation(i) = (evaluate(S, fit.u, fit.v(i)).transpose() - fit.points.row(i)).norm();
    const PiecewiseCurve pc = to_piecewise(curves[l]);
    for (Index b = 0; b + 1 < pc.breaks.size(); ++b) {
      const VectorXd t =
          VectorXd::LinSpaced(kCurveCheckSamples + 1, pc.breaks(b), pc.breaks(b + 1));
      const MatrixXd Gt = evaluate(pc, t);
      for (Index i = 0; i < t.size(); ++i)
        fit.curve_deviation = std::max(fit.curve_deviation,
                                       (evaluate(S, fit.u, t(i)).transpose() - Gt.row(i)).norm());
    }
    const Guide& g = gs.guides[l];
    fit.input_deviation.resize(g.points.rows());
    for (Index j = 0; j < g.points.rows(); ++j)
      fit.input_deviation(j) =
          (evaluate(S, fit.u, fit.v(fit.input_row[static_cast<size_t>(j)])).transpose() -
           g.points.row(j))
              .norm();
    R.max_guide_deviation =
        std::max({R.max_guide_deviation, fit.deviation.maxCoeff(), fit.curve_deviation});
    R.max_input_deviation = std::max(R.max_input_deviation, fit.input_deviation.maxCoeff());
  }
}

} // namespace

GuidedLoftResult guided_loft(const std::vector<Section>& sections, const GuideSet& gs,
                             const GuidedLoftOptions& go) {
  const LoftOptions& o = go.loft;
  const size_t K = sections.size(), L = gs.guides.size();
  detail::check_loft_inputs(sections, o);
  if (!(go.guide_tolerance > 0))
    throw std::invalid_argument("the guide tolerance must be positive");
  if (L < 1)
    throw_input_error(gs.path, 0, "no guides");
  GuidedLoftResult R;
  LoftResult& r = R.loft;
  r.sections = prepare_sections(sections, o.align, r.notes);
  // The spanwise model from the sections alone, as loft_sections chooses it.
  r.span = detail::choose_span_model(
      r.sections,
      detail::section_curves(r.sections, detail::edge_landmarks(r.sections, o.align), o), o);
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  for (const PreparedSection& s : r.sections) {
    lo = lo.cwiseMin(s.points.colwise().minCoeff().transpose());
    hi = hi.cwiseMax(s.points.colwise().maxCoeff().transpose());
  }
  const double diag = (hi - lo).norm();

  std::vector<VectorXd> own_u;
  const std::vector<std::vector<Approach>> cross =
      find_crossings(r.sections, gs, o, go.guide_tolerance * diag, go.guide_tolerance, own_u);
  std::vector<Feature> features;
  for (size_t l = 0; l < L; ++l)
    features.push_back({"guide " + gs.guides[l].id, gs.guides[l].lines[0], std::vector<Index>(K),
                        static_cast<int>(l)});
  for (size_t k = 0; k < K; ++k)
    insert_crossings(r.sections[k], static_cast<Index>(k), own_u[k], gs, cross, features, r.notes);
  if (o.align == StartAlign::first)
    start_at_first_guide(r, gs, features);
  std::vector<std::vector<Index>> guide_rows; // per guide, its row in every section
  for (const Feature& f : features)
    guide_rows.push_back(f.rows);
  add_opposite_edge(r, o.align, features);
  check_features(r, gs, features);

  const detail::SectionCurves sc =
      detail::section_curves(r.sections, feature_landmarks(features, K), o);
  r.used = sc.used;
  r.point_u = sc.point_u;
  r.section_v = detail::model_span_parameters(r.span, sc.curves, r.sections);
  const std::vector<double> gu = guide_parameters(features, sc.landmark_u, L);
  for (size_t l = 0; l < L; ++l) {
    std::vector<double> pos;
    for (const Approach& a : cross[l])
      pos.push_back(a.pos);
    R.guides.push_back(fit_guide(gs.guides[l], pos, guide_rows[l], r, gs.path));
    R.guides.back().u = gu[l];
    if (R.guides.back().reversed)
      r.notes.push_back("guide " + gs.guides[l].id +
                        ": runs from the last section to the first; reversed");
  }
  const int q = r.span.used.degree;
  VectorXd blend_knots;
  const std::vector<BSplineCurve> curves =
      guide_curves(R.guides, r.section_v, q, gs.path, blend_knots);
  r.surface = gordon_of(sc.curves, r.section_v, R.guides, curves, q, blend_knots);

  // Exactness: every section point, every guide point and the guide curves.
  detail::section_deviation(r, lo, hi);
  r.bbox_diagonal = diag;
  guide_deviation(R, gs, curves);
  r.max_deviation = std::max(r.max_deviation, R.max_guide_deviation);
  detail::require_exact(r, "guided loft: surface deviates from the sections or guides");
  return R;
}

} // namespace interlin
