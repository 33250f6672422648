// Leave-one-out choice of the spanwise model (seed 001 §2.5 lofts; hold-out as in holdout.h).
#include "cross_validate_span.h"

#include "interlin/interlineation/interlinate_curves.h"
#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/splines/knots.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace interlin::detail {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// The spacings the automatic choice tries, in order of preference (ties go to the earlier). Each
// is the right one for some stack: station when the blade is smooth in its stacking coordinate,
// chord when it is smooth in the arc length across the sections, uniform when the sections sit
// at equal steps of a design coordinate the loft cannot see. Centripetal (the square root of
// chord) describes no stack (it keeps curves through uneven polygons from looping), and on
// unevenly spaced blades its leave-one-out error was low by accident. On the analytic blade
// families (docs/benchmarks.md, "Spanwise model on analytic blades"; the rule chosen on the even
// cases of the reference family, checked on the odd ones and on two fresh families) this set
// picks at worst 2.8 x, 2.7 x and 2.3 x the error of the best fixed option between sections;
// with centripetal in place of uniform 3.1 x, 5.0 x and 4.2 x.
const std::vector<SpanParameters> kAutoSpanParameters = {
    SpanParameters::station, SpanParameters::chord, SpanParameters::uniform};

template <class T>
std::vector<T> without(const std::vector<T>& all, size_t j) {
  std::vector<T> out = all;
  out.erase(out.begin() + static_cast<std::ptrdiff_t>(j));
  return out;
}

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(3);
  s << x;
  return s.str();
}

// x without entry j (empty stays empty).
VectorXd without(const VectorXd& x, Index j) {
  if (x.size() == 0)
    return x;
  VectorXd out(x.size() - 1);
  out << x.head(j), x.tail(x.size() - j - 1);
  return out;
}

// The fold's surface S over its knot spans in v that meet [v_lo, v_hi] only, in explicit form:
// the withheld section lies there, and converting the rest of the stack (most of the cost for
// many sections) would be wasted. The same polynomial patches as to_piecewise(S) over that range.
PiecewiseSurface band_of(const BSplineSurface& S, double v_lo, double v_hi) {
  const int p = S.degree_v;
  const Index a = find_span(S.knots_v, p, S.num_v, v_lo),
              b = find_span(S.knots_v, p, S.num_v, std::nextafter(v_hi, v_lo));
  BSplineSurface band = S;
  band.num_v = b - a + p + 1;
  band.knots_v = S.knots_v.segment(a - p, band.num_v + p + 1);
  band.ctrl = S.ctrl.middleRows(S.num_u * (a - p), S.num_u * band.num_v);
  return to_piecewise(band);
}

// The points of a withheld section that the hold-out measures: every step-th, step the smallest
// that leaves at most kHoldoutPoints, with their parameters u. The hold-out error varies smoothly
// along a section, and sections sampled densely from fitted curves (sectioned scans: 400 to 1000
// points) need not be measured at every sample; Rotor 37's 198 points per section are all kept.
struct HeldPoints {
  MatrixXd P;
  VectorXd u;
};

HeldPoints held_points(const MatrixXd& P, const VectorXd& u) {
  constexpr Index kHoldoutPoints = 256;
  const Index step = (P.rows() + kHoldoutPoints - 1) / kHoldoutPoints;
  HeldPoints h{MatrixXd((P.rows() + step - 1) / step, 3), VectorXd((P.rows() + step - 1) / step)};
  for (Index i = 0; i < h.P.rows(); ++i) {
    h.P.row(i) = P.row(i * step);
    h.u(i) = u(i * step);
  }
  return h;
}

// Distances of the withheld section's points P to the fold's surface S: the lower of the feet
// from the points' own parameters (u, v_j) and from the nearest samples of the band of S between
// the neighbouring sections [v_lo, v_hi] (kBandSamplesU x kBandSamplesV, kBandStarts starts).
// Near a thin edge the corresponding start can descend to the far side when the fold misses the
// section by more than the edge is thick; the band's samples find the near side.
VectorXd withheld_distances(const PiecewiseSurface& S, const MatrixXd& P, const VectorXd& u,
                            double v, double v_lo, double v_hi) {
  constexpr int kBandSamplesU = 256, kBandSamplesV = 8, kBandStarts = 4;
  ParametricSurface band = parametric(S);
  band.domain(2) = v_lo;
  band.domain(3) = v_hi;
  return project_from(S, P, u, VectorXd::Constant(P.rows(), v))
      .distance.cwiseMin(
          project_to_surface(band, P, kBandSamplesU, kBandSamplesV, kBandStarts).distance);
}

} // namespace

std::vector<SpanCandidate> span_candidates(const SectionStations& stations, Index K,
                                           const LoftOptions& o) {
  const bool has_stations = stations.stacking != Stacking::none;
  if (o.span == SpanParameters::station && !has_stations)
    throw std::invalid_argument(
        "span parameters 'station' need sections on parallel planes or on coaxial surfaces of "
        "revolution about z; these are neither (width across the stacking surface " +
        fmt(stations.spread) + " x the smallest station gap, more than " + fmt(kStationSpread) +
        "); use chord or uniform");
  std::vector<SpanParameters> params = {o.span};
  if (o.span == SpanParameters::automatic) {
    params = kAutoSpanParameters;
    if (!has_stations)
      params.erase(params.begin());
  }
  const int top = static_cast<int>(K - 1);
  std::vector<int> degrees = {std::min(o.span_degree, top)};
  if (o.span_degree == kAutoSpanDegree) {
    // Highest first: folds cannot tell degrees >= K - 2 apart (each fold has K - 1 sections),
    // and such ties go to the earlier candidate, the one that uses every section.
    degrees = {std::min(top, kMaxAutoSpanDegree), std::min(5, top), std::min(3, top)};
    degrees.erase(std::unique(degrees.begin(), degrees.end()), degrees.end());
  }
  std::vector<SpanCandidate> out;
  for (SpanParameters p : params)
    for (int q : degrees)
      out.push_back({p, q});
  return out;
}

void cross_validate(const std::vector<PreparedSection>& sections, const SectionCurves& curves,
                    const Eigen::VectorXd& distance, const SectionStations& stations,
                    std::vector<SpanCandidate>& candidates) {
  const size_t K = sections.size();
  std::vector<HeldPoints> held(K);
  long count = 0;
  for (size_t j = 1; j + 1 < K; ++j) {
    held[j] = held_points(sections[j].points, curves.point_u[j]);
    count += held[j].P.rows();
  }
  for (size_t c = 0; c < candidates.size(); ++c) {
    SpanCandidate& m = candidates[c];
    // Folds have K - 1 sections: candidates with the same parameters and the same degree there
    // are the same fold models (e.g. degrees 5 and 6 for K = 7).
    const auto same = std::find_if(
        candidates.begin(), candidates.begin() + static_cast<long>(c), [&](const SpanCandidate& o) {
          return o.parameters == m.parameters &&
                 std::min<size_t>(o.degree, K - 2) == std::min<size_t>(m.degree, K - 2);
        });
    if (same != candidates.begin() + static_cast<long>(c)) {
      m.loo_max = same->loo_max;
      m.loo_rms = same->loo_rms;
      continue;
    }
    const VectorXd v = span_parameters(m.parameters, distance, stations.station);
    double max = 0, sum2 = 0;
    for (size_t j = 1; j + 1 < K; ++j) {
      const Index jj = static_cast<Index>(j);
      const PiecewiseSurface S =
          band_of(interlinate_curves(without(curves.curves, j), without(v, jj), m.degree, true),
                  v(jj - 1), v(jj + 1));
      const VectorXd d = withheld_distances(S, held[j].P, held[j].u, v(jj), v(jj - 1), v(jj + 1));
      max = std::max(max, d.maxCoeff());
      sum2 += d.squaredNorm();
    }
    m.loo_max = max;
    m.loo_rms = std::sqrt(sum2 / static_cast<double>(count));
  }
}

SpanModel choose_span_model(const std::vector<PreparedSection>& sections,
                            const SectionCurves& curves, const LoftOptions& o) {
  const Index K = static_cast<Index>(sections.size());
  SpanModel m;
  std::vector<MatrixXd> points;
  for (const PreparedSection& s : sections)
    points.push_back(s.points);
  m.stations = section_stations(points);
  m.candidates = span_candidates(m.stations, K, o);
  m.folds = o.span_holdout ? static_cast<int>(std::max<Index>(K - 2, 0)) : 0;
  if (m.folds > 0)
    cross_validate(sections, curves, neighbour_distances(curves.curves, sections), m.stations,
                   m.candidates);
  size_t best = 0;
  for (size_t c = 1; c < m.candidates.size(); ++c)
    if (span_model_score(m.candidates[c]) < span_model_score(m.candidates[best]))
      best = c;
  m.used = m.candidates[best];
  m.chosen = m.candidates.size() > 1 && o.span_holdout;
  return m;
}

VectorXd model_span_parameters(const SpanModel& m, const std::vector<BSplineCurve>& curves,
                               const std::vector<PreparedSection>& sections) {
  return span_parameters(m.used.parameters, neighbour_distances(curves, sections),
                         m.stations.station);
}

} // namespace interlin::detail

namespace interlin {

// The largest distance: the surface is trusted by its worst section. (On the analytic blade
// family, docs/benchmarks.md, the rms or the geometric mean of both chose no better.)
double span_model_score(const SpanCandidate& c) {
  return c.loo_max;
}

} // namespace interlin
