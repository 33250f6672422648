#include "interlin/reconstruction/clouds/fit_sliced_scan.h"

#include "interlin/interlineation/interlinate_curves.h"
#include "interlin/reconstruction/meshing/parallel_for.h"
#include "interlin/splines/approximate_curve.h"
#include "interlin/splines/knot_insertion.h"
#include "interlin/splines/parameterization.h"

#include "profile_curves.h"
#include "smooth_spanwise.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

namespace interlin {

using detail::capped_knot_weights;
using detail::closest_parameters;
using detail::kDofPerControl;
using detail::kKnotGrid;
using detail::kPointsPerControl;
using detail::turning_weights;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

constexpr int kSmoothingHalfWidth = 3; // parameters: moving average over 7 ordered points
// Section samples (FittedSection::section), evenly spaced by arc length: at least 400 and 8 per
// control point.
constexpr int kMinSamples = 400, kSamplesPerControl = 8;
// The first reference curve has this many control points, knots even.
constexpr Index kPilotControl = 32;
// Shape passes: parameters from the feet on the reference curve, then a new reference.
constexpr int kShapePasses = 2;
// least_cp stops after this many counts in a row without a lower C_p.
constexpr int kRisesToStop = 3;
// The surface must reproduce each fitted curve to this fraction of the diagonal (as loft_sections
// guarantees for its input points).
constexpr double kExactness = 1e-9;

// The 2D coordinates of a slice and back: in-plane axes (planar), or arc length r * angle and the
// axial coordinate (radial); to_space(to_plane(p)) moves p onto the slice surface.
struct SliceFrame {
  SliceKind kind;
  Vector3d axis, e1, e2;
  double station = 0, angle = 0; // radial: the slice's radius and mean angle

  SliceFrame(const SliceFamily& f, double s, const Eigen::MatrixX3d& P,
             const std::vector<Index>& rows)
      : kind(f.kind), axis(f.axis.normalized()), e1(axis.unitOrthogonal()), e2(axis.cross(e1)),
        station(s) {
    if (kind == SliceKind::radial) { // circular mean of the points' angles
      double c = 0, sn = 0;
      for (Index i : rows) {
        const Vector3d p = P.row(i).transpose();
        c += p.dot(e1);
        sn += p.dot(e2);
      }
      angle = std::atan2(sn, c);
    }
  }
  Eigen::Vector2d to_plane(const Vector3d& p) const {
    if (kind == SliceKind::planar)
      return {p.dot(e1), p.dot(e2)};
    const double a = std::remainder(std::atan2(p.dot(e2), p.dot(e1)) - angle, 2 * M_PI);
    return {station * a, p.dot(axis)};
  }
  Vector3d to_space(const Eigen::Vector2d& q) const {
    if (kind == SliceKind::planar)
      return station * axis + q(0) * e1 + q(1) * e2;
    const double a = angle + q(0) / station;
    return q(1) * axis + station * (std::cos(a) * e1 + std::sin(a) * e2);
  }
};

// Arc length along a curve, tabulated on a polygon of `chords` chords evenly spaced in the
// parameter: the fraction of the length at a parameter and the parameter at a fraction (linear
// along each chord).
struct ArcLength {
  Eigen::VectorXd t;
  std::vector<double> len{0};
  ArcLength(const BSplineCurve& c, int chords)
      : t(Eigen::VectorXd::LinSpaced(chords + 1, domain_begin(c), domain_end(c))) {
    const MatrixXd D = evaluate(c, t);
    for (int i = 1; i <= chords; ++i)
      len.push_back(len.back() + (D.row(i) - D.row(i - 1)).norm());
  }
  double fraction(double u) const {
    const double h = t(1) - t(0);
    const Index i = std::clamp<Index>(Index(std::floor((u - t(0)) / h)), 0, t.size() - 2);
    const double f = (u - t(i)) / h;
    return (len[size_t(i)] + f * (len[size_t(i) + 1] - len[size_t(i)])) / len.back();
  }
  double parameter(double fraction) const {
    const double target = fraction * len.back();
    const size_t i = std::min(
        size_t(std::upper_bound(len.begin(), len.end(), target) - len.begin()) - 1, len.size() - 2);
    const double f = len[i + 1] > len[i] ? (target - len[i]) / (len[i + 1] - len[i]) : 0;
    return t(Index(i)) + f * (t(Index(i) + 1) - t(Index(i)));
  }
};

// One slice's points projected onto its slice surface (plane or cylinder) in 3D, in order around
// the profile, and the same after a circular moving average (for parameters and edges, which
// the noise would otherwise jitter).
struct OrderedSlice {
  MatrixXd points, smoothed;
};

OrderedSlice ordered_slice(const Eigen::MatrixX3d& P, const std::vector<Index>& rows,
                           const SliceFrame& frame) {
  const Index n = Index(rows.size());
  Eigen::MatrixX2d Q(n, 2);
  for (Index i = 0; i < n; ++i)
    Q.row(i) = frame.to_plane(P.row(rows[size_t(i)]).transpose()).transpose();
  const std::vector<Index> order = order_profile(Q);
  OrderedSlice s{MatrixXd(n, 3), MatrixXd(n, 3)};
  for (Index i = 0; i < n; ++i) {
    Eigen::Vector2d m = Eigen::Vector2d::Zero();
    for (int k = -kSmoothingHalfWidth; k <= kSmoothingHalfWidth; ++k)
      m += Q.row(order[size_t(((i + k) % n + n) % n)]).transpose();
    s.points.row(i) = frame.to_space(Q.row(order[size_t(i)]).transpose()).transpose();
    s.smoothed.row(i) = frame.to_space(m / (2 * kSmoothingHalfWidth + 1)).transpose();
  }
  return s;
}

// Closed-curve parameters s[k] (#P + 1 from 0 to 1, leading edge first) mapped piecewise
// linearly so that every trailing edge (row te[k]) sits at one common parameter, the mean of
// theirs (as loft_sections does with arc-length correspondence).
void align_trailing_edges(std::vector<Eigen::VectorXd>& s, const std::vector<Index>& te) {
  double F = 0;
  for (size_t k = 0; k < s.size(); ++k)
    F += s[k](te[k]) / double(s.size());
  for (size_t k = 0; k < s.size(); ++k) {
    const double f = s[k](te[k]);
    Eigen::VectorXd& u = s[k];
    for (Index i = 0; i < u.size(); ++i)
      u(i) = u(i) <= f ? u(i) * F / f : F + (u(i) - f) * (1 - F) / (1 - f);
    u(0) = 0, u(u.size() - 1) = 1;
  }
}

// A closed cubic through the points at parameters u (#P + 1, increasing from 0 to 1) with
// `control` control points, knots on the grid, spaced by the interval weights w (empty: evenly by
// point count), capped at #P / (kPointsPerSpan control) times the even weight per point, so that
// every span holds kPointsPerSpan points, and so that no span is shorter than 4 grid steps.
// Throws as approximate_curve when the points of a span share too few parameters (feet gathered
// by a curve that loops through the noise).
Approximation weighted_fit(const MatrixXd& P, const Eigen::VectorXd& u, Index control,
                           const Eigen::VectorXd& w) {
  ApproximationOptions o;
  o.degree = 3;
  o.closed = true;
  o.parameters = u;
  o.knot_grid = kKnotGrid;
  o.num_ctrl = int(control);
  if (w.size() != 0)
    o.knot_weights = capped_knot_weights(w, Eigen::VectorXd::Ones(w.size()), u, control);
  return approximate_curve(P, o);
}

// The points' feet on curve c (Newton from u): their parameters t on c (#P) and their arc-length
// fractions f from the foot of point 0, the leading edge (#P + 1: in [0, 1), closing 1 last).
struct Feet {
  Eigen::VectorXd t, f;
};

Feet feet_on(const BSplineCurve& c, const MatrixXd& P, const Eigen::VectorXd& u) {
  Feet g;
  g.t = closest_parameters(c, P, u);
  const ArcLength arc(c, 16 * int(P.rows()));
  const double f0 = arc.fraction(g.t(0));
  g.f.resize(P.rows() + 1);
  for (Index i = 0; i < P.rows(); ++i) {
    const double h = arc.fraction(g.t(i)) - f0;
    g.f(i) = h - std::floor(h);
  }
  g.f(0) = 0;
  g.f(P.rows()) = 1;
  return g;
}

// Least squares with c control points at parameters f (#P + 1, point 0 at 0), the points taken in
// increasing f, knots weighted by the turning of curve `ref` between the points' parameters t on
// it. Output: the fit, u in the points' given order.
Approximation fit_at(const MatrixXd& P, const Eigen::VectorXd& f, Index c, const BSplineCurve& ref,
                     const Eigen::VectorXd& t) {
  const Index n = P.rows();
  std::vector<Index> order{};
  order.resize(size_t(n));
  std::iota(order.begin(), order.end(), Index(0));
  std::stable_sort(order.begin(), order.end(), [&](Index i, Index j) { return f(i) < f(j); });
  Eigen::VectorXd u(n + 1), tt(n + 1);
  u << f(order), 1.0;
  tt << t(order), t(order.front()) + domain_end(ref) - domain_begin(ref);
  Approximation a = weighted_fit(P(order, Eigen::all), u, c, turning_weights(ref, tt));
  Eigen::VectorXd back(n);
  back(order) = a.u;
  a.u = back;
  return a;
}

// fit_at, then again at the feet on that fit, so that the residuals are distances normal to the
// fitted curve (the parameters carry no tangential noise for more control points to fit).
Approximation corrected_fit(const MatrixXd& P, const Feet& g, Index c, const BSplineCurve& ref) {
  const Approximation a = fit_at(P, g.f, c, ref, g.t);
  const Feet h = feet_on(a.curve, P, a.u);
  return fit_at(P, h.f, c, a.curve, h.t);
}

// The fit whose control points minimise Mallows' C_p with the known noise: the fewest-risk fit
// (corrected_fit when `correct`, else fit_at) among 8, 10, ... #P / kPointsPerControl control
// points (steps of 1/4, until kRisesToStop in a row do not improve on the best), risk RSS + 2
// sigma^2 dof with dof = kDofPerControl per control point and sigma^2 = s2.
Approximation least_cp(const MatrixXd& P, const Feet& g, const BSplineCurve& ref, double s2,
                       bool correct) {
  const Index n = P.rows(), most = std::max<Index>(8, n / kPointsPerControl);
  Approximation best;
  double best_cp = std::numeric_limits<double>::infinity();
  int rises = 0;
  for (Index c = 8; rises < kRisesToStop; c = std::min(most, std::max(c + 1, c * 5 / 4))) {
    double cp = std::numeric_limits<double>::infinity();
    Approximation a;
    try {
      a = correct ? corrected_fit(P, g, c, ref) : fit_at(P, g.f, c, ref, g.t);
      cp = double(n) * a.rms_deviation * a.rms_deviation + 2 * s2 * double(kDofPerControl * c);
    } catch (const std::exception&) { // a singular fit: not a candidate
    }
    rises = cp < best_cp ? 0 : rises + 1;
    if (cp < best_cp)
      best_cp = cp, best = std::move(a);
    if (c == most)
      break;
  }
  if (!(best_cp < std::numeric_limits<double>::infinity())) // no candidate: as the smallest
    return correct ? corrected_fit(P, g, 8, ref) : fit_at(P, g.f, 8, ref, g.t);
  return best;
}

// A profile's fit before the trailing edges are aligned: the last curve, the points' feet on it
// and the control points chosen.
struct ProfileFit {
  BSplineCurve reference;
  Feet feet;
  Index control = 0;
};

// kShapePasses passes from a pilot (kPilotControl control points, knots even, at the parameters
// u): the next curve is least_cp's fit from the feet on the last one. A floor of 1e-7 of the
// profile's size stands for round-off when the noise is 0.
ProfileFit fit_profile(const MatrixXd& P, const Eigen::VectorXd& u, double noise) {
  const double floor = 1e-7 * (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
  const double s2 = std::pow(std::max(noise, floor), 2);
  const Index most = std::max<Index>(8, P.rows() / kPointsPerControl);
  Approximation a = weighted_fit(P, u, std::min(kPilotControl, most), {});
  ProfileFit f;
  for (int pass = 0; pass < kShapePasses; ++pass)
    a = least_cp(P, feet_on(a.curve, P, a.u), a.curve, s2, pass + 1 == kShapePasses);
  f.control = a.curve.ctrl.rows() - a.curve.degree;
  f.reference = a.curve;
  f.feet = feet_on(a.curve, P, a.u);
  return f;
}

// The final fit of a profile at its aligned parameters u (#P + 1), with fewer control points
// (steps of 1/5) if the chosen count's system is singular there.
Approximation final_fit(const MatrixXd& P, const ProfileFit& f, const Eigen::VectorXd& u) {
  for (Index c = f.control;; c = std::max<Index>(8, c * 4 / 5)) {
    try {
      return fit_at(P, u, c, f.reference, f.feet.t);
    } catch (const std::runtime_error&) {
      if (c == 8)
        throw;
    }
  }
}

// The final fits, or the isocurves of smooth_spanwise where its C_p is lower, each with its
// points' feet as parameters and their distances as deviations. Output: the spanwise control
// points (0: the fits kept).
Index smooth_final_fits(const std::vector<MatrixXd>& P, std::vector<Approximation>& fits,
                        const std::vector<double>& stations, double noise, int threads) {
  const size_t K = fits.size();
  Eigen::VectorXd v = Eigen::VectorXd::Zero(Index(K));
  std::vector<BSplineCurve> curves;
  std::vector<Eigen::VectorXd> u;
  Eigen::AlignedBox3d box;
  for (size_t k = 0; k < K; ++k) {
    v(Index(k)) = (stations[k] - stations.front()) / (stations.back() - stations.front());
    curves.push_back(fits[k].curve);
    u.push_back(fits[k].u);
    box.extend(Vector3d(P[k].colwise().minCoeff())).extend(Vector3d(P[k].colwise().maxCoeff()));
  }
  const double s2 = std::pow(std::max(noise, 1e-7 * box.diagonal().norm()), 2);
  detail::SpanwiseSections s = detail::smooth_spanwise(P, u, curves, v, s2, threads);
  for (size_t k = 0; k < K; ++k) {
    const Eigen::VectorXd d = (evaluate(s.curves[k], s.u[k]) - P[k]).rowwise().norm();
    fits[k].curve = std::move(s.curves[k]);
    fits[k].u = std::move(s.u[k]);
    fits[k].rms_deviation = std::sqrt(d.squaredNorm() / double(d.size()));
    fits[k].max_deviation = d.maxCoeff();
  }
  return s.span_control;
}

// The fitted section: the curve, its residuals and its arc-length samples.
FittedSection fitted_section(const Approximation& a, double station, Index points, int samples) {
  FittedSection s;
  s.station = station;
  s.points = points;
  s.curve = periodic_to_clamped(a.curve, 0.0);
  s.control = int(a.curve.ctrl.rows()) - a.curve.degree;
  s.rms = a.rms_deviation;
  s.max = a.max_deviation;
  const int m = samples > 0 ? samples : std::max(kMinSamples, kSamplesPerControl * s.control);
  const ArcLength arc(s.curve, 16 * m);
  s.u.resize(m);
  for (int j = 0; j < m; ++j)
    s.u(j) = arc.parameter(double(j) / m);
  s.section = evaluate(s.curve, s.u);
  return s;
}

// The loft of the fitted curves: on one knot vector (knot insertion, exact) and interlinated
// cubically along the span at the stations (seed 001 §2.5; interlinate_curves), so S(u, v_k)
// equals curve k for every u. Its deviation from each section's samples is recorded as
// loft_sections records its input points'.
LoftResult loft_fitted_curves(const std::vector<FittedSection>& fitted,
                              std::vector<PreparedSection> prepared,
                              std::vector<std::string> notes) {
  const Index K = Index(fitted.size());
  std::vector<BSplineCurve> curves;
  Eigen::VectorXd v(K);
  for (Index k = 0; k < K; ++k) {
    curves.push_back(fitted[size_t(k)].curve);
    v(k) = (fitted[size_t(k)].station - fitted[0].station) /
           (fitted.back().station - fitted[0].station);
  }
  LoftResult r;
  r.span.used.parameters = SpanParameters::station;
  r.span.used.degree = int(std::min<Index>(3, K - 1));
  r.surface = interlinate_curves(make_compatible(curves), v, r.span.used.degree, true);
  r.section_v = v;
  r.used = Correspondence::arc_length;
  r.notes = std::move(notes);
  const PiecewiseSurface S = to_piecewise(r.surface);
  Eigen::AlignedBox3d box;
  for (Index k = 0; k < K; ++k) {
    const FittedSection& f = fitted[size_t(k)];
    PreparedSection& p = prepared[size_t(k)];
    p.points = f.section;
    p.lines.assign(size_t(f.section.rows()), 0);
    p.source.resize(size_t(f.section.rows()));
    for (size_t i = 0; i < p.source.size(); ++i)
      p.source[i] = Index(i), p.lines[i] = long(i) + 1;
    p.le = 0;
    p.te = -1;
    Eigen::VectorXd d(f.section.rows());
    for (Index i = 0; i < d.size(); ++i) {
      d(i) = (evaluate(S, f.u(i), v(k)) - f.section.row(i).transpose()).norm();
      box.extend(f.section.row(i).transpose());
    }
    r.point_u.push_back(Eigen::VectorXd(d.size() + 1));
    r.point_u.back() << f.u, 1.0;
    r.deviation.push_back(d);
    r.max_deviation = std::max(r.max_deviation, d.maxCoeff());
  }
  r.sections = std::move(prepared);
  r.bbox_diagonal = box.diagonal().norm();
  return r;
}

// Largest distance from the fitted curves, halfway between their samples, to the loft's section
// curves S(u, v_k) at the same parameter (an upper bound of the distance between the curves).
double section_gap(const std::vector<FittedSection>& sections, const LoftResult& loft) {
  const PiecewiseSurface S = to_piecewise(loft.surface);
  double gap = 0;
  for (size_t k = 0; k < sections.size(); ++k) {
    const Eigen::VectorXd& u = sections[k].u;
    const Index m = u.size();
    Eigen::VectorXd mid(m);
    for (Index i = 0; i < m; ++i)
      mid(i) = 0.5 * (u(i) + (i + 1 < m ? u(i + 1) : 1.0));
    const MatrixXd C = evaluate(sections[k].curve, mid);
    for (Index i = 0; i < m; ++i)
      gap = std::max(gap,
                     (evaluate(S, mid(i), loft.section_v(Index(k))) - C.row(i).transpose()).norm());
  }
  return gap;
}

} // namespace

std::vector<Section> fitted_sections(const std::vector<FittedSection>& fitted) {
  std::vector<Section> sections;
  for (size_t k = 0; k < fitted.size(); ++k) {
    Section s;
    s.id = std::to_string(k + 1);
    s.points = fitted[k].section;
    s.lines.resize(size_t(s.points.rows()));
    for (size_t i = 0; i < s.lines.size(); ++i)
      s.lines[i] = long(i) + 1;
    sections.push_back(std::move(s));
  }
  return sections;
}

LoftOptions sliced_scan_loft_options() {
  LoftOptions lo;
  lo.align = StartAlign::leading_edge;
  lo.match = Correspondence::arc_length;
  // Spanwise cubic at the slices' stations (chord spacing for radial slices about an axis other
  // than z, which have none), without cross-validation: tens of densely fitted sections made the
  // leave-one-out choice cost minutes, for no measurable accuracy (docs/benchmarks.md, "Sectioned
  // scans: the spanwise model").
  lo.span_degree = 3;
  lo.span_holdout = false;
  return lo;
}

SlicedFit fit_sliced_scan(const Eigen::MatrixX3d& P, const SliceFamily& family,
                          const SliceFitOptions& options) {
  if (family.kind != SliceKind::planar && family.kind != SliceKind::radial)
    throw std::invalid_argument("fit_sliced_scan: the family is neither planar nor radial");
  if (family.members.size() < 2)
    throw std::invalid_argument("fit_sliced_scan: at least 2 slices are needed");
  SlicedFit r;
  r.family = family;
  r.noise = options.noise > 0 ? options.noise : family.spread;
  // Order each slice, then one winding and the start at the leading edge for all (the edges of
  // the smoothed profiles, prepare_sections), and common parameters.
  std::vector<OrderedSlice> slices;
  std::vector<Section> smoothed;
  for (size_t k = 0; k < family.members.size(); ++k) {
    const SliceFrame frame(family, family.stations[k], P, family.members[k]);
    slices.push_back(ordered_slice(P, family.members[k], frame));
    Section s;
    s.id = std::to_string(k + 1);
    s.points = slices.back().smoothed;
    s.lines.assign(size_t(s.points.rows()), 0);
    smoothed.push_back(std::move(s));
  }
  std::vector<std::string> notes;
  const std::vector<PreparedSection> prepared =
      prepare_sections(smoothed, StartAlign::leading_edge, notes);
  // The pilot's parameters: chord length along the smoothed polyline. The fits then move every
  // point to its foot's arc-length fraction, so that u means the same fraction of the profile in
  // every section (the loft's correspondence; the smoothed polyline cuts the noses short, by a
  // different share in each section).
  std::vector<MatrixXd> points;
  std::vector<Eigen::VectorXd> u;
  std::vector<Index> te;
  for (size_t k = 0; k < slices.size(); ++k) {
    points.push_back(slices[k].points(prepared[k].source, Eigen::all));
    u.push_back(chord_parameters(prepared[k].points, true));
    te.push_back(prepared[k].te);
  }
  align_trailing_edges(u, te);
  // Each profile's shape and parameters, then one trailing-edge parameter for all, and the
  // final fits there.
  const long K = long(slices.size());
  const int threads = detail::resolve_threads(options.threads);
  std::vector<ProfileFit> fits(size_t(K), ProfileFit{});
  detail::parallel_for(K, threads, [&](long k, int) {
    fits[size_t(k)] = fit_profile(points[size_t(k)], u[size_t(k)], r.noise);
  });
  for (size_t k = 0; k < slices.size(); ++k)
    u[k] = fits[k].feet.f;
  align_trailing_edges(u, te);
  std::vector<Approximation> finals(static_cast<size_t>(K));
  detail::parallel_for(K, threads, [&](long k, int) {
    finals[size_t(k)] = final_fit(points[size_t(k)], fits[size_t(k)], u[size_t(k)]);
  });
  if (options.smooth_span)
    r.span_control = smooth_final_fits(points, finals, family.stations, r.noise, threads);
  r.sections.resize(size_t(K));
  detail::parallel_for(K, threads, [&](long k, int) {
    const size_t i = size_t(k);
    r.sections[i] =
        fitted_section(finals[i], family.stations[i], points[i].rows(), options.samples);
  });
  if (options.progress)
    options.progress("fitted " + std::to_string(r.sections.size()) + " sections");
  r.loft = loft_fitted_curves(r.sections, prepared, std::move(notes));
  if (!(r.loft.max_deviation <= kExactness * r.loft.bbox_diagonal))
    throw std::runtime_error("fit_sliced_scan: the loft deviates from the fitted sections by " +
                             std::to_string(r.loft.max_deviation) + "; refusing to continue");
  r.section_gap = section_gap(r.sections, r.loft);
  if (options.progress)
    options.progress("lofted; fitted sections to the loft: " + std::to_string(r.section_gap));
  return r;
}

} // namespace interlin
