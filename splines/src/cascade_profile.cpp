// seed 004 §4.1–4.2 (digest 004 §6.1–6.2): axial-turbine cascade profile from 13 parameters.
#include "interlin/splines/cascade_profile.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;

namespace {

constexpr double kDeg = M_PI / 180;

[[noreturn]] void bad(const std::string& what) {
  throw std::invalid_argument("cascade profile: " + what);
}

void require(bool ok, const std::string& what) {
  if (!ok)
    bad(what);
}

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

void check_parameters(const CascadeParameters& p, const CascadeOptions& o) {
  const double v[] = {p.relative_pitch,
                      p.axial_width,
                      p.stagger_deg,
                      p.inlet_angle_deg,
                      p.outlet_angle_deg,
                      p.le_wedge_deg,
                      p.te_wedge_deg,
                      p.le_radius,
                      p.te_radius,
                      p.te_bend_deg,
                      p.max_thickness_position,
                      p.max_thickness,
                      p.throat};
  for (double x : v)
    require(std::isfinite(x), "every parameter must be a finite number");
  require(p.axial_width > 0, "axial width B must be > 0, got " + num(p.axial_width));
  require(p.relative_pitch > 0, "relative pitch must be > 0, got " + num(p.relative_pitch));
  require(p.le_radius > 0, "leading-edge radius must be > 0, got " + num(p.le_radius));
  require(p.te_radius > 0, "trailing-edge radius must be > 0, got " + num(p.te_radius));
  require(p.le_radius + p.te_radius < p.axial_width,
          "edge radii r1 + r2 must be smaller than the axial width B");
  require(p.stagger_deg > 0 && p.stagger_deg < 180,
          "stagger angle must lie in (0, 180) degrees, got " + num(p.stagger_deg));
  require(p.inlet_angle_deg > 0 && p.inlet_angle_deg < 180,
          "inlet angle must lie in (0, 180) degrees, got " + num(p.inlet_angle_deg));
  require(p.outlet_angle_deg > 0 && p.outlet_angle_deg < 90,
          "outlet angle must lie in (0, 90) degrees, got " + num(p.outlet_angle_deg));
  require(p.le_wedge_deg >= 0 && p.le_wedge_deg < 180,
          "leading-edge wedge angle must lie in [0, 180) degrees, got " + num(p.le_wedge_deg));
  require(p.te_wedge_deg > 0 && p.te_wedge_deg < 180, // y_O2 = r2 ctg(gamma_2 / 2)
          "trailing-edge wedge angle must lie in (0, 180) degrees, got " + num(p.te_wedge_deg));
  require(p.te_bend_deg >= 0 && p.te_bend_deg < 90,
          "trailing-edge bend angle must lie in [0, 90) degrees, got " + num(p.te_bend_deg));
  require(p.max_thickness_position > 0 && p.max_thickness_position < 1,
          "relative position of the maximum thickness must lie in (0, 1), got " +
              num(p.max_thickness_position));
  require(p.max_thickness > 0 && p.max_thickness < 1,
          "relative maximum thickness must lie in (0, 1), got " + num(p.max_thickness));
  require(p.throat >= 0, "throat must be >= 0 (0 = default), got " + num(p.throat));
  require(o.side_intervals >= 4, "side_intervals must be >= 4");
  require(o.edge_intervals >= 2 && o.edge_intervals % 2 == 0, "edge_intervals must be even, >= 2");
}

// Point and tangent angle at global arc length s along a side made of consecutive pieces.
CurvePose side_pose(const std::vector<PlanarNaturalCurve>& side, double s,
                    const QuadratureOptions& q) {
  for (size_t i = 0; i < side.size(); ++i) {
    const PlanarNaturalCurve& c = side[i];
    if (s <= c.length || i + 1 == side.size()) {
      const double t = std::min(std::max(s, 0.0), c.length);
      return {natural_point(c, t, q), tangent_angle(c, t)};
    }
    s -= c.length;
  }
  bad("empty side");
}

double side_length(const std::vector<PlanarNaturalCurve>& side) {
  double L = 0;
  for (const PlanarNaturalCurve& c : side)
    L += c.length;
  return L;
}

// Two-segment side: linear curvature start -> mid, then the joint segment mid' -> end with k
// (G2) or k, k' (G3) continued; mid' is the computed end of the first segment.
std::vector<PlanarNaturalCurve> fit_side(const CurvePose& start, const CurvePose& mid,
                                         const CurvePose& end, CascadeJoint joint,
                                         const ShootingOptions& o, double& miss) {
  const NaturalFit first = fit_linear_curvature(start, mid, o);
  const PlanarNaturalCurve& c = first.pieces[0];
  const CurvePose joint_pose{natural_point(c, c.length, o.quadrature), tangent_angle(c, c.length)};
  VectorXd fixed(joint == CascadeJoint::g3_cubic ? 2 : 1);
  fixed(0) = curvature(c.law, c.length);
  if (joint == CascadeJoint::g3_cubic)
    fixed(1) = curvature(c.law, c.length, 1);
  const NaturalFit second = fit_hermite_curvature(joint_pose, end, fixed, o);
  miss = std::max({miss, first.miss, second.miss});
  return {c, second.pieces[0]};
}

// Do segments p-q and r-s cross (proper intersection)?
bool crosses(const Vector2d& p, const Vector2d& q, const Vector2d& r, const Vector2d& s) {
  const auto orient = [](const Vector2d& a, const Vector2d& b, const Vector2d& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  const double d1 = orient(p, q, r), d2 = orient(p, q, s), d3 = orient(r, s, p),
               d4 = orient(r, s, q);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Does the pose's direction point towards b?
bool ahead(const CurvePose& a, const Vector2d& b) {
  return (b - a.point).dot(Vector2d(std::cos(a.angle), std::sin(a.angle))) > 0;
}

// Pitch, throat, the edge circles and the key points C1, C2, C3, K1, K2 (digest §6.1), checked
// for consistency: the sides run from the trailing edge forward to the leading edge.
void key_points(const CascadeParameters& p, CascadeProfile& P) {
  const double B = p.axial_width, r1 = p.le_radius, r2 = p.te_radius;
  const double by = p.stagger_deg * kDeg, b1 = p.inlet_angle_deg * kDeg,
               b2 = p.outlet_angle_deg * kDeg, g1 = p.le_wedge_deg * kDeg,
               g2 = p.te_wedge_deg * kDeg, delta = p.te_bend_deg * kDeg;
  P.pitch = p.relative_pitch * B;
  P.max_thickness = p.max_thickness * B;
  P.throat = p.throat > 0 ? p.throat : P.pitch * std::sin(b2); // [R] default
  require(P.throat < P.pitch,
          "throat " + num(P.throat) + " must be smaller than the pitch " + num(P.pitch));
  P.O2 = Vector2d(r2, r2 / std::tan(g2 / 2));
  P.O1 = Vector2d(B - r1, ((B - r2) * std::cos(by) + r1) / std::sin(by));
  P.C2 = {Vector2d(r2 * (1 - std::cos(b2 - g2 / 2)), P.O2.y() + r2 * std::sin(b2 - g2 / 2)),
          (M_PI + g2) / 2 - b2};
  P.K2 = {Vector2d(r2 * (1 + std::cos(b2 + g2 / 2)), P.O2.y() - r2 * std::sin(b2 + g2 / 2)),
          (M_PI - g2) / 2 - b2};
  P.C1 = {P.O1 + r1 * Vector2d(std::cos(b1 - g1 / 2), std::sin(b1 - g1 / 2)), b1 - (M_PI + g1) / 2};
  P.K1 = {P.O1 - r1 * Vector2d(std::cos(b1 + g1 / 2), std::sin(b1 + g1 / 2)), b1 - (M_PI - g1) / 2};
  const double phi_c3 = (M_PI + g2) / 2 - b2 - delta;
  P.C3 = {P.O2 + Vector2d(0, P.pitch) +
              (P.throat + r2) * Vector2d(std::sin(phi_c3), -std::cos(phi_c3)),
          phi_c3};
  require((P.O1 - P.O2).norm() > r1 + r2, "the edge circles overlap");
  require(ahead(P.C2, P.C3.point) && P.C3.point.x() < P.C1.point.x(),
          "inconsistent angles: the throat point C3 (" + num(P.C3.point.x()) + ", " +
              num(P.C3.point.y()) +
              ") does not lie between the trailing and leading edges on "
              "the suction side (check pitch, throat, outlet and bend angles)");
  require(P.C3.angle > P.C1.angle && P.K2.angle > P.K1.angle,
          "inconsistent angles: the sides must turn clockwise from the trailing to the leading "
          "edge (outlet angle, inlet angle and wedge angles)");
}

// Point A: the maximum-thickness circle (centre A + (c_m/2) n, n the inward normal, on the
// right of the suction side's direction) has its centre at x = B (1 - position); the first
// crossing seen from the leading edge (a 200-step scan), then bisection.
CurvePose max_thickness_point(const CascadeParameters& p, const CascadeProfile& P,
                              const QuadratureOptions& q) {
  const double xm = p.axial_width * (1 - p.max_thickness_position), half = P.max_thickness / 2;
  const double Ls = side_length(P.suction);
  const auto centre_x = [&](double s) {
    const CurvePose a = side_pose(P.suction, s, q);
    return a.point.x() + half * std::sin(a.angle) - xm;
  };
  const int scan = 200;
  double hi = Ls, fhi = centre_x(hi), lo = -1, flo = 0;
  for (int i = scan - 1; i >= 0; --i) {
    const double s = Ls * i / scan, f = centre_x(s);
    if ((f <= 0) != (fhi <= 0)) {
      lo = s;
      flo = f;
      break;
    }
    hi = s;
    fhi = f;
  }
  require(lo >= 0, "no suction-side point has its maximum-thickness circle centred at the given "
                   "relative position " +
                       num(p.max_thickness_position));
  for (int it = 0; it < 100 && hi - lo > 1e-15 * Ls; ++it) {
    const double m = 0.5 * (lo + hi), fm = centre_x(m);
    if ((fm <= 0) == (flo <= 0))
      lo = m, flo = fm;
    else
      hi = m;
  }
  return side_pose(P.suction, 0.5 * (lo + hi), q);
}

// Closed point list from the TE middle towards the suction side (see header): edge arcs at
// even angles, sides at cosine-spaced arc lengths.
MatrixXd profile_points(const CascadeParameters& p, const CascadeProfile& P,
                        const CascadeOptions& o) {
  const double r1 = p.le_radius, r2 = p.te_radius, b1 = p.inlet_angle_deg * kDeg,
               b2 = p.outlet_angle_deg * kDeg, g1 = p.le_wedge_deg * kDeg,
               g2 = p.te_wedge_deg * kDeg;
  const int ne = o.edge_intervals, ns = o.side_intervals;
  MatrixXd X(2 * (ne + ns), 2);
  Index row = 0;
  const auto put = [&](const Vector2d& v) { X.row(row++) = v.transpose(); };
  const double tc2 = M_PI - (b2 - g2 / 2), tk2 = 2 * M_PI - (b2 + g2 / 2);
  const auto te = [&](int i) {
    const double th = tc2 + (tk2 - tc2) * i / ne;
    return Vector2d(P.O2 + r2 * Vector2d(std::cos(th), std::sin(th)));
  };
  const double tc1 = b1 - g1 / 2;
  const auto le = [&](int i) {
    const double th = tc1 - (M_PI - g1) * i / ne;
    return Vector2d(P.O1 + r1 * Vector2d(std::cos(th), std::sin(th)));
  };
  const auto cosine = [&](int i, double L) { return L * (1 - std::cos(M_PI * i / ns)) / 2; };
  const QuadratureOptions& q = o.shooting.quadrature;
  const double Ls = side_length(P.suction), Lp = side_length(P.pressure);
  for (int i = ne / 2; i >= 1; --i)
    put(te(i));
  for (int i = 0; i < ns; ++i)
    put(side_pose(P.suction, cosine(i, Ls), q).point);
  for (int i = 0; i < ne; ++i)
    put(le(i));
  for (int i = ns; i >= 1; --i)
    put(side_pose(P.pressure, cosine(i, Lp), q).point);
  for (int i = ne; i > ne / 2; --i)
    put(te(i));
  if (!X.allFinite())
    throw std::runtime_error("cascade profile: non-finite point (please report)");
  return X;
}

// The sides must not cross each other or themselves (a simple closed polygon), and the passage
// must stay open: the profile may not touch its neighbour one pitch away.
void check_constructive(const MatrixXd& X, double pitch) {
  const Index n = X.rows();
  for (Index i = 0; i < n; ++i)
    for (Index j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1)
        continue;
      if (crosses(X.row(i), X.row((i + 1) % n), X.row(j), X.row((j + 1) % n)))
        bad("non-constructive profile: the contour crosses itself (the suction and pressure sides "
            "intersect; the book warns that bad combinations of maximum thickness and its "
            "position do this)");
    }
  const Vector2d shift(0, pitch);
  for (Index i = 0; i < n; ++i)
    for (Index j = 0; j < n; ++j)
      if (crosses(X.row(i), X.row((i + 1) % n), X.row(j) + shift.transpose(),
                  X.row((j + 1) % n) + shift.transpose()))
        bad("non-constructive profile: it overlaps its neighbour one pitch away (the passage "
            "is closed; reduce the thickness or increase the pitch)");
}

} // namespace

CascadeProfile cascade_profile(const CascadeParameters& p, const CascadeOptions& o) {
  check_parameters(p, o);
  CascadeProfile P;
  key_points(p, P);
  const ShootingOptions& so = o.shooting;
  P.suction = fit_side(P.C2, P.C3, P.C1, o.joint, so, P.miss);
  P.A = max_thickness_point(p, P, so.quadrature);
  P.K3 = {P.A.point + P.max_thickness * Vector2d(std::sin(P.A.angle), -std::cos(P.A.angle)),
          P.A.angle};
  require(ahead(P.K2, P.K3.point) && P.K3.point.x() < P.K1.point.x(),
          "inconsistent maximum thickness: the point K3 opposite the maximum-thickness point "
          "does not lie between the edges on the pressure side (reduce the thickness or move "
          "its position)");
  P.pressure = fit_side(P.K2, P.K3, P.K1, o.joint, so, P.miss);
  P.points = profile_points(p, P, o);
  check_constructive(P.points, P.pitch);
  return P;
}

MatrixXd side_curvature_plot(const std::vector<PlanarNaturalCurve>& side, int samples,
                             const QuadratureOptions& q) {
  if (side.empty() || samples < 2)
    throw std::invalid_argument("curvature plot: need a side and >= 2 samples");
  const double L = side_length(side);
  MatrixXd out(samples, 7);
  for (int i = 0; i < samples; ++i) {
    const double s = L * i / (samples - 1);
    double local = s;
    size_t k = 0;
    while (k + 1 < side.size() && local > side[k].length)
      local -= side[k++].length;
    const PlanarNaturalCurve& c = side[k];
    const Vector2d pt = natural_point(c, local, q);
    out.row(i) << s / L, s, pt.x(), pt.y(), tangent_angle(c, local), curvature(c.law, local),
        curvature(c.law, local, 1);
  }
  return out;
}

} // namespace interlin
