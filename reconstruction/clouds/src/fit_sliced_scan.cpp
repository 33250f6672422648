#include "interlin/reconstruction/clouds/fit_sliced_scan.h"

#include "interlin/splines/approximate_curve.h"
#include "interlin/splines/parameterization.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

constexpr int kSmoothingHalfWidth = 3; // parameters: moving average over 7 ordered points
// Section samples handed to the loft, evenly spaced by arc length: at least 400 and 8 per control
// point (the loft's cubic through them then stays within about 1e-4 of the profile's size of the
// fitted curve at a nose of radius 1 % of the chord).
constexpr int kMinSamples = 400, kSamplesPerControl = 8;
// The rms residual to reach, in sigma: sqrt(2) for the in-plane residual of isotropic noise,
// with 6 % for the parameters' own error.
constexpr double kResidualRatio = 1.5;
// At least this many points per control point: randomly spaced points leave knot spans nearly
// empty when there are more control points, and the curve oscillates between the points.
constexpr Index kPointsPerControl = 4;

// The 2D coordinates of a slice and back (see FittedSection::curve).
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

// m parameters of a closed curve evenly spaced by arc length (a polygon of 16 m points).
Eigen::VectorXd arc_length_parameters(const BSplineCurve& c, int m) {
  const double u0 = domain_begin(c), u1 = domain_end(c);
  const int dense = 16 * m;
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(dense + 1, u0, u1);
  const MatrixXd D = evaluate(c, t);
  std::vector<double> len{0};
  for (int i = 1; i <= dense; ++i)
    len.push_back(len.back() + (D.row(i) - D.row(i - 1)).norm());
  Eigen::VectorXd u(m);
  for (int j = 0; j < m; ++j) {
    const double target = len.back() * j / m;
    const size_t i = size_t(std::upper_bound(len.begin(), len.end(), target) - len.begin()) - 1;
    const double f = len[i + 1] > len[i] ? (target - len[i]) / (len[i + 1] - len[i]) : 0;
    u(j) = t(Index(i)) + f * (t(Index(i) + 1) - t(Index(i)));
  }
  return u;
}

// Chord-length parameters of the ordered points after a circular moving average.
Eigen::VectorXd smoothed_parameters(const MatrixXd& Q) {
  const Index n = Q.rows();
  MatrixXd S = MatrixXd::Zero(n, Q.cols());
  for (Index i = 0; i < n; ++i) {
    for (int k = -kSmoothingHalfWidth; k <= kSmoothingHalfWidth; ++k)
      S.row(i) += Q.row(((i + k) % n + n) % n);
    S.row(i) /= 2 * kSmoothingHalfWidth + 1;
  }
  return chord_parameters(S, true);
}

FittedSection fit_slice(const Eigen::MatrixX3d& P, const SliceFamily& f, size_t k, double noise,
                        int samples, SliceFrame& frame) {
  const std::vector<Index>& rows = f.members[k];
  const Index n = Index(rows.size());
  Eigen::MatrixX2d Q(n, 2);
  for (Index i = 0; i < n; ++i)
    Q.row(i) = frame.to_plane(P.row(rows[size_t(i)]).transpose()).transpose();
  const std::vector<Index> order = order_profile(Q);
  const MatrixXd O = Q(order, Eigen::all);
  ApproximationOptions o;
  o.degree = 3;
  o.closed = true;
  o.parameters = smoothed_parameters(O);
  // discrepancy principle: the fewest control points (8, 16, ... n / kPointsPerControl) whose
  // rms residual is within kResidualRatio sigma (2D residuals of isotropic noise: sqrt(2) sigma);
  // a floor of 1e-7 of the profile's size stands for round-off when the noise is 0
  const double floor = 1e-7 * (O.colwise().maxCoeff() - O.colwise().minCoeff()).norm();
  const Index most = std::max<Index>(8, n / kPointsPerControl);
  Approximation a;
  for (Index c = 8;; c = std::min(most, 2 * c)) {
    o.num_ctrl = int(c);
    a = approximate_curve(O, o);
    if (a.rms_deviation <= std::max(kResidualRatio * noise, floor) || c == most)
      break;
  }
  FittedSection s;
  s.station = f.stations[k];
  s.points = n;
  s.curve = a.curve;
  s.control = int(a.curve.ctrl.rows()) - a.curve.degree;
  s.rms = a.rms_deviation;
  s.max = a.max_deviation;
  const int m = samples > 0 ? samples : std::max(kMinSamples, kSamplesPerControl * s.control);
  const Eigen::VectorXd u = arc_length_parameters(a.curve, m);
  const MatrixXd C = evaluate(a.curve, u);
  s.section.resize(m, 3);
  for (int i = 0; i < m; ++i)
    s.section.row(i) = frame.to_space(C.row(i).transpose()).transpose();
  s.u = u;
  return s;
}

// Largest distance from the fitted curves, halfway between their samples, to the loft's section
// curves S(u, v_k): Newton on |S(u, v_k) - m|^2 from the mean u of the two samples.
double section_gap(const std::vector<FittedSection>& sections,
                   const std::vector<SliceFrame>& frames, const LoftResult& loft) {
  const PiecewiseSurface S = to_piecewise(loft.surface);
  double gap = 0;
  for (size_t k = 0; k < sections.size(); ++k) {
    const BSplineCurve& c = sections[k].curve;
    const Index m = sections[k].section.rows();
    Eigen::VectorXd u_of(m); // the loft's u of each input sample (preparation rolls, reverses)
    const PreparedSection& prep = loft.sections[k];
    for (size_t r = 0; r < prep.source.size(); ++r)
      u_of(prep.source[r]) = loft.point_u[k](Index(r));
    const double v = loft.section_v(Index(k)), period = domain_end(c) - domain_begin(c);
    Eigen::VectorXd mid(m);
    for (Index i = 0; i < m; ++i) // halfway in the fitted curve's parameter
      mid(i) = i + 1 < m ? 0.5 * (sections[k].u(i) + sections[k].u(i + 1))
                         : sections[k].u(i) + 0.5 * (sections[k].u(0) + period - sections[k].u(i));
    const MatrixXd C = evaluate(c, mid);
    for (Index i = 0; i < m; ++i) {
      const Vector3d p = frames[k].to_space(C.row(i).transpose());
      double a = u_of(i), b = u_of((i + 1) % m);
      if (std::abs(b - a) > 0.5) // across the seam
        b += b < a ? 1 : -1;
      double u = 0.5 * (a + b);
      for (int it = 0; it < 8; ++it) {
        const double w = u - std::floor(u);
        const Vector3d d = evaluate(S, w, v) - p, su = evaluate(S, w, v, 1, 0);
        const double h = su.squaredNorm() + d.dot(evaluate(S, w, v, 2, 0));
        u -= d.dot(su) / (h > 0 ? h : su.squaredNorm());
      }
      gap = std::max(gap, (evaluate(S, u - std::floor(u), v) - p).norm());
    }
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
  std::vector<SliceFrame> frames;
  for (size_t k = 0; k < family.members.size(); ++k) {
    frames.emplace_back(family, family.stations[k], P, family.members[k]);
    r.sections.push_back(fit_slice(P, family, k, r.noise, options.samples, frames.back()));
  }
  if (options.progress)
    options.progress("fitted " + std::to_string(r.sections.size()) + " sections");
  r.loft = loft_sections(fitted_sections(r.sections), sliced_scan_loft_options());
  r.section_gap = section_gap(r.sections, frames, r.loft);
  if (options.progress)
    options.progress("lofted; fitted sections to the loft: " + std::to_string(r.section_gap));
  return r;
}

} // namespace interlin
