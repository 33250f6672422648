// seed 001 §2.5 (surface through sections and user lines); digest 001 §5.1 [SUPPLEMENT] (Gordon).
#include "interlin/reconstruction/loft/guided_loft.h"

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
  const int per = 16;
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
  for (int it = 0; it < 80 && b - a > 1e-16; ++it) {
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

} // namespace

GuidedLoftResult guided_loft(const std::vector<Section>& sections, const GuideSet& gs,
                             const GuidedLoftOptions& go) {
  const LoftOptions& o = go.loft;
  const Index K = static_cast<Index>(sections.size());
  const Index L = static_cast<Index>(gs.guides.size());
  if (K < 2)
    throw std::invalid_argument("a loft needs at least 2 sections, got " + std::to_string(K));
  if (o.degree < 1 || o.span_degree < 1)
    throw std::invalid_argument("degrees must be >= 1");
  if (!(go.guide_tolerance > 0))
    throw std::invalid_argument("the guide tolerance must be positive");
  if (L < 1)
    throw_input_error(gs.path, 0, "no guides");
  for (const Section& s : sections)
    if (s.points.rows() < std::max(4, o.degree + 1))
      throw std::invalid_argument("section " + s.id + " has " + std::to_string(s.points.rows()) +
                                  " points; degree " + std::to_string(o.degree) +
                                  " needs at least " + std::to_string(std::max(4, o.degree + 1)));
  GuidedLoftResult R;
  LoftResult& r = R.loft;
  r.sections = prepare_sections(sections, o.align, r.notes);
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  for (const PreparedSection& s : r.sections)
    for (Index i = 0; i < s.points.rows(); ++i) {
      lo = lo.cwiseMin(s.points.row(i).transpose());
      hi = hi.cwiseMax(s.points.row(i).transpose());
    }
  const double diag = (hi - lo).norm(), tol = go.guide_tolerance * diag;

  // 1. Crossings of every guide with every provisional section curve (own chord parameters).
  std::vector<std::vector<Approach>> cross(static_cast<size_t>(L));
  std::vector<VectorXd> own_u(static_cast<size_t>(K));
  for (Index k = 0; k < K; ++k) {
    const MatrixXd& P = r.sections[static_cast<size_t>(k)].points;
    own_u[static_cast<size_t>(k)] = chord_parameters(P, true, o.section_exponent);
    const PiecewiseCurve C =
        to_piecewise(interpolate_closed(P, own_u[static_cast<size_t>(k)], o.degree));
    for (Index l = 0; l < L; ++l) {
      const Guide& g = gs.guides[static_cast<size_t>(l)];
      const Approach a = closest_approach(g.points, C, P, own_u[static_cast<size_t>(k)]);
      if (!(a.distance <= tol))
        throw_input_error(gs.path, g.lines[static_cast<size_t>(std::lround(a.pos))],
                          "guide " + g.id + " passes " + fmt(a.distance) + " from section " +
                              r.sections[static_cast<size_t>(k)].id + " (more than the tolerance " +
                              fmt(tol) + " = " + fmt(go.guide_tolerance) +
                              " x bounding-box diagonal); every guide must cross every section");
      cross[static_cast<size_t>(l)].push_back(a);
    }
  }

  // 2. Each crossing becomes a section row: the nearest point when within 1% of its parameter
  //    spacing, else a point inserted into the section (it lies on the section curve).
  std::vector<Feature> features;
  for (Index l = 0; l < L; ++l)
    features.push_back({"guide " + gs.guides[static_cast<size_t>(l)].id,
                        gs.guides[static_cast<size_t>(l)].lines[0],
                        std::vector<Index>(static_cast<size_t>(K)), static_cast<int>(l)});
  for (Index k = 0; k < K; ++k) {
    PreparedSection& sec = r.sections[static_cast<size_t>(k)];
    const VectorXd& s = own_u[static_cast<size_t>(k)];
    const Index n = sec.points.rows();
    // Per guide: (row, or -1 with insertion parameter).
    struct Place {
      Index row;
      double u;
      Index guide;
    };
    std::vector<Place> inserts;
    std::vector<Index> row_of(static_cast<size_t>(L), -1);
    for (Index l = 0; l < L; ++l) {
      const double u = cross[static_cast<size_t>(l)][static_cast<size_t>(k)].u;
      const Index i =
          std::min<Index>(std::upper_bound(s.data(), s.data() + n + 1, u) - s.data() - 1, n - 1);
      const double h = s(i + 1) - s(i);
      if (u - s(i) <= 0.01 * h)
        row_of[static_cast<size_t>(l)] = i;
      else if (s(i + 1) - u <= 0.01 * h)
        row_of[static_cast<size_t>(l)] = (i + 1) % n;
      else
        inserts.push_back({i, u, l});
    }
    std::sort(inserts.begin(), inserts.end(),
              [](const Place& a, const Place& b) { return a.u < b.u; });
    // Two guides through one point of the section: no common parameter can separate them.
    for (Index a = 0; a < L; ++a)
      for (Index b = a + 1; b < L; ++b) {
        const double ua = cross[static_cast<size_t>(a)][static_cast<size_t>(k)].u,
                     ub = cross[static_cast<size_t>(b)][static_cast<size_t>(k)].u;
        const Index ra = row_of[static_cast<size_t>(a)], rb = row_of[static_cast<size_t>(b)];
        const Index i =
            std::min<Index>(std::upper_bound(s.data(), s.data() + n + 1, ua) - s.data() - 1, n - 1);
        if ((ra >= 0 && ra == rb) ||
            (ra < 0 && rb < 0 && std::abs(ua - ub) <= 0.01 * (s(i + 1) - s(i))))
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
        const Approach& a = cross[static_cast<size_t>(inserts[next].guide)][static_cast<size_t>(k)];
        const Guide& g = gs.guides[static_cast<size_t>(inserts[next].guide)];
        row_of[static_cast<size_t>(inserts[next].guide)] = w;
        pts.row(w++) = a.point.transpose();
        lines.push_back(g.lines[static_cast<size_t>(std::lround(a.pos))]);
        source.push_back(-1);
        r.notes.push_back("section " + sec.id + ": crossing with guide " + g.id +
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
      features[static_cast<size_t>(l)].rows[static_cast<size_t>(k)] = row;
    }
    if (sec.le >= 0)
      sec.le = new_row[static_cast<size_t>(sec.le)];
    if (sec.te >= 0)
      sec.te = new_row[static_cast<size_t>(sec.te)];
    sec.points = pts;
    sec.lines = lines;
    sec.source = source;
  }
  // Kept starts (--align first) must not cross a guide between sections: when the guides come
  // in one cyclic order around every section but the start points cut that order differently,
  // every section is started at its crossing with the first guide instead.
  if (o.align == StartAlign::first && L > 1) {
    const auto order_in = [&](Index k) {
      std::vector<Index> idx(static_cast<size_t>(L));
      for (Index l = 0; l < L; ++l)
        idx[static_cast<size_t>(l)] = l;
      std::sort(idx.begin(), idx.end(), [&](Index a, Index b) {
        return features[static_cast<size_t>(a)].rows[static_cast<size_t>(k)] <
               features[static_cast<size_t>(b)].rows[static_cast<size_t>(k)];
      });
      return idx;
    };
    const auto rotated = [](std::vector<Index> idx) {
      std::rotate(idx.begin(), std::find(idx.begin(), idx.end(), 0), idx.end());
      return idx;
    };
    const std::vector<Index> first = order_in(0);
    bool same = true, cyclic = true;
    for (Index k = 1; k < K; ++k) {
      same = same && order_in(k) == first;
      cyclic = cyclic && rotated(order_in(k)) == rotated(first);
    }
    if (!same && cyclic) {
      for (Index k = 0; k < K; ++k) {
        PreparedSection& sec = r.sections[static_cast<size_t>(k)];
        const Index n = sec.points.rows(), r0 = features[0].rows[static_cast<size_t>(k)];
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
          f.rows[static_cast<size_t>(k)] = roll(f.rows[static_cast<size_t>(k)]);
      }
      r.notes.push_back("sections started at their crossing with guide " + gs.guides[0].id +
                        ": the given start points would cross a guide between sections");
    }
  }
  std::vector<std::vector<Index>> guide_rows;
  for (const Feature& f : features)
    guide_rows.push_back(f.rows);
  if (o.align != StartAlign::first) {
    Feature edge{
        o.align == StartAlign::leading_edge ? "the trailing edge" : "the leading edge", 0, {}, -1};
    for (const PreparedSection& s : r.sections)
      edge.rows.push_back(o.align == StartAlign::leading_edge ? s.te : s.le);
    // A guide on the opposite edge in every section is the same landmark.
    if (std::none_of(features.begin(), features.end(),
                     [&](const Feature& f) { return f.rows == edge.rows; }))
      features.push_back(edge);
  }

  // 3. Features at one point of a section, and their order around the sections.
  const auto where = [&](const Feature& f) {
    return f.guide >= 0 ? std::make_pair(gs.path, f.line) : std::make_pair(gs.path, 0L);
  };
  for (size_t a = 0; a < features.size(); ++a)
    for (size_t b = a + 1; b < features.size(); ++b)
      for (Index k = 0; k < K; ++k)
        if (features[a].rows[static_cast<size_t>(k)] == features[b].rows[static_cast<size_t>(k)]) {
          const auto [p, line] = where(features[b]);
          throw_input_error(p, line,
                            features[a].name + " and " + features[b].name + " cross section " +
                                r.sections[static_cast<size_t>(k)].id +
                                " at the same point; guides must cross each section at distinct "
                                "points");
        }
  std::sort(features.begin(), features.end(),
            [](const Feature& a, const Feature& b) { return a.rows[0] < b.rows[0]; });
  for (const Feature& f : features)
    for (Index k = 1; k < K; ++k)
      if ((f.rows[0] == 0) != (f.rows[static_cast<size_t>(k)] == 0)) {
        const auto [p, line] = where(f);
        throw_input_error(p, line,
                          f.name + " passes through the start point of section " +
                              r.sections[0].id + " but not of section " +
                              r.sections[static_cast<size_t>(k)].id +
                              "; start every section on it or on none (see --align)");
      }
  for (size_t a = 0; a + 1 < features.size(); ++a)
    for (Index k = 1; k < K; ++k)
      if (!(features[a].rows[static_cast<size_t>(k)] <
            features[a + 1].rows[static_cast<size_t>(k)])) {
        const auto [p, line] = where(features[a + 1]);
        throw_input_error(p, line,
                          features[a].name + " and " + features[a + 1].name + " cross section " +
                              r.sections[static_cast<size_t>(k)].id +
                              " in the opposite order to section " + r.sections[0].id);
      }

  // Between neighbouring sections a feature cannot jump by more than half the loop (as a
  // fraction of the section's chord length from its start): it would have crossed another guide
  // or the line of start points, and lines of one family of a surface never cross.
  for (Index k = 0; k + 1 < K; ++k) {
    const VectorXd f0 = chord_parameters(r.sections[static_cast<size_t>(k)].points, true);
    const VectorXd f1 = chord_parameters(r.sections[static_cast<size_t>(k + 1)].points, true);
    for (const Feature& f : features)
      if (std::abs(f1(f.rows[static_cast<size_t>(k + 1)]) - f0(f.rows[static_cast<size_t>(k)])) >
          0.5) {
        const auto [p, line] = where(f);
        throw_input_error(p, line,
                          f.name + " moves by more than half the section between sections " +
                              r.sections[static_cast<size_t>(k)].id + " and " +
                              r.sections[static_cast<size_t>(k + 1)].id +
                              ": it crosses another guide or the line of the sections' start "
                              "points there");
      }
  }

  // 4. Section curves with every feature (except one through the start) at one parameter.
  std::vector<std::vector<Index>> landmarks(static_cast<size_t>(K));
  for (const Feature& f : features)
    if (f.rows[0] != 0)
      for (Index k = 0; k < K; ++k)
        landmarks[static_cast<size_t>(k)].push_back(f.rows[static_cast<size_t>(k)]);
  const detail::SectionCurves sc = detail::section_curves(r.sections, landmarks, o);
  r.used = sc.used;
  r.point_u = sc.point_u;
  r.section_v = sc.section_v;
  const VectorXd& v = r.section_v;

  // 5. Guides: orientation, crossings at v_k, own points in between at chord fractions.
  std::vector<double> gu(static_cast<size_t>(L));
  {
    size_t m = 0;
    for (const Feature& f : features) {
      if (f.guide >= 0)
        gu[static_cast<size_t>(f.guide)] = f.rows[0] == 0 ? 0.0 : sc.landmark_u[m];
      if (f.rows[0] != 0)
        ++m;
    }
  }
  R.guides.resize(static_cast<size_t>(L));
  for (Index l = 0; l < L; ++l) {
    const Guide& g = gs.guides[static_cast<size_t>(l)];
    GuideFit& fit = R.guides[static_cast<size_t>(l)];
    fit.id = g.id;
    fit.u = gu[static_cast<size_t>(l)];
    const Index n = g.points.rows();
    std::vector<double> pos;
    for (const Approach& a : cross[static_cast<size_t>(l)])
      pos.push_back(a.pos);
    bool up = true, down = true;
    for (Index k = 0; k + 1 < K; ++k) {
      up = up && pos[static_cast<size_t>(k + 1)] > pos[static_cast<size_t>(k)];
      down = down && pos[static_cast<size_t>(k + 1)] < pos[static_cast<size_t>(k)];
    }
    if (!up && !down)
      throw_input_error(gs.path, g.lines[0],
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
    if (down)
      r.notes.push_back("guide " + g.id + ": runs from the last section to the first; reversed");
    // Arc length at polyline positions.
    VectorXd arc = VectorXd::Zero(n);
    for (Index j = 1; j < n; ++j)
      arc(j) = arc(j - 1) + (G.row(j) - G.row(j - 1)).norm();
    const auto arc_at = [&](double p) {
      const Index m = std::min<Index>(static_cast<Index>(std::floor(p)), n - 2);
      return arc(m) + (p - static_cast<double>(m)) * (arc(m + 1) - arc(m));
    };
    // A vertex within 1% of a segment of a crossing is replaced by the crossing.
    std::vector<Index> by_crossing(static_cast<size_t>(n), -1);
    for (Index k = 0; k < K; ++k) {
      const double pk = pos[static_cast<size_t>(k)];
      const Index j = std::lround(pk);
      if (std::abs(pk - static_cast<double>(j)) > 0.01)
        continue;
      if (by_crossing[static_cast<size_t>(j)] >= 0)
        throw_input_error(
            gs.path, g.lines[static_cast<size_t>(order[static_cast<size_t>(j)])],
            "guide " + g.id + " meets sections " +
                r.sections[static_cast<size_t>(by_crossing[static_cast<size_t>(j)])].id + " and " +
                r.sections[static_cast<size_t>(k)].id + " at this one point");
      by_crossing[static_cast<size_t>(j)] = k;
    }
    for (Index j = 0; j < n; ++j)
      if (by_crossing[static_cast<size_t>(j)] < 0 &&
          (static_cast<double>(j) < pos.front() || static_cast<double>(j) > pos.back()))
        throw_input_error(gs.path, g.lines[static_cast<size_t>(order[static_cast<size_t>(j)])],
                          "guide " + g.id +
                              ": this point lies beyond the first or last section; a guide runs "
                              "from the first section to the last");
    std::vector<Eigen::RowVector3d> pts;
    std::vector<double> site;
    fit.input_row.assign(static_cast<size_t>(n), -1);
    for (Index k = 0; k < K; ++k) {
      // The crossing's point is the section's row (a section point or the inserted crossing).
      fit.crossing.push_back(static_cast<Index>(pts.size()));
      pts.push_back(r.sections[static_cast<size_t>(k)].points.row(
          guide_rows[static_cast<size_t>(l)][static_cast<size_t>(k)]));
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
  }

  // 6. Guide curves and the blending functions along the span, each with knots by averaging
  //    its own sites (well-conditioned collocation), except that interior knots of different
  //    curves closer than 1e-3 of the section spacing are made equal: the knot union of the
  //    surface then has no span below ~1e-3 of its neighbours, where the explicit basis is exact
  //    to round-off (docs/formulas.md, span ratios). A guide point closer than that to a
  //    crossing along the span is moved off it in parameter (not in space).
  const int qb = static_cast<int>(std::min<Index>(o.span_degree, K - 1));
  const auto interval = [&](double x) {
    return std::min<Index>(std::upper_bound(v.data(), v.data() + K, x) - v.data() - 1, K - 2);
  };
  const auto gap = [&](double x) {
    const Index k = interval(x);
    return 1e-3 * (v(k + 1) - v(k));
  };
  std::vector<VectorXd> knots = {averaged_knots(v, qb)};
  for (GuideFit& fit : R.guides) {
    for (Index i = 0; i < fit.v.size(); ++i)
      if (std::find(fit.crossing.begin(), fit.crossing.end(), i) == fit.crossing.end()) {
        const Index k = interval(fit.v(i));
        fit.v(i) = std::clamp(fit.v(i), v(k) + gap(fit.v(i)), v(k + 1) - gap(fit.v(i)));
      }
    for (Index i = 1; i < fit.v.size(); ++i)
      if (!(fit.v(i) > fit.v(i - 1)))
        throw_input_error(gs.path, 0,
                          "guide " + fit.id +
                              ": two of its points are too close along the span to be "
                              "interpolated (closer than 1e-3 of the section spacing)");
    knots.push_back(averaged_knots(fit.v, qb));
  }
  detail::snap_values(knots, qb + 1, gap);
  std::vector<BSplineCurve> curves;
  for (size_t l = 0; l < R.guides.size(); ++l)
    curves.push_back(interpolate_in_space(R.guides[l].points, R.guides[l].v, knots[l + 1], qb));

  // 7. The Gordon surface (guides ordered by their parameter u).
  std::vector<size_t> by_u(static_cast<size_t>(L));
  for (size_t l = 0; l < by_u.size(); ++l)
    by_u[l] = l;
  std::sort(by_u.begin(), by_u.end(),
            [&](size_t a, size_t b) { return R.guides[a].u < R.guides[b].u; });
  std::vector<BSplineCurve> gcurves;
  VectorXd u(L);
  for (Index l = 0; l < L; ++l) {
    gcurves.push_back(curves[by_u[static_cast<size_t>(l)]]);
    u(l) = R.guides[by_u[static_cast<size_t>(l)]].u;
  }
  r.surface = gordon_bspline(sc.curves, v, gcurves, u, o.span_degree, true, 1e-10, knots[0]);

  // 8. Exactness: every section point, every guide point and the guide curves.
  detail::section_deviation(r, lo, hi);
  r.bbox_diagonal = diag;
  const PiecewiseSurface S = to_piecewise(r.surface);
  for (size_t l = 0; l < R.guides.size(); ++l) {
    GuideFit& fit = R.guides[l];
    fit.deviation.resize(fit.v.size());
    for (Index i = 0; i < fit.v.size(); ++i)
      fit.deviation(i) = (evaluate(S, fit.u, fit.v(i)).transpose() - fit.points.row(i)).norm();
    const PiecewiseCurve pc = to_piecewise(curves[l]);
    for (Index b = 0; b + 1 < pc.breaks.size(); ++b) {
      const VectorXd t = VectorXd::LinSpaced(65, pc.breaks(b), pc.breaks(b + 1));
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
  r.max_deviation = std::max(r.max_deviation, R.max_guide_deviation);
  detail::require_exact(r, "guided loft: surface deviates from the sections or guides");
  return R;
}

} // namespace interlin
