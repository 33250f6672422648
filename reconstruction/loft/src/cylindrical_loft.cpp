// seed 001 §2.5, formula (4): x = R(t,z) cos t, y = R(t,z) sin t, z = z for star-shaped bodies.
#include "interlin/reconstruction/loft/cylindrical_loft.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/splines/interpolate_curve.h"

#include <algorithm>
#include <cmath>
#include <numeric>
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
  s.precision(6);
  s << x;
  return s.str();
}

// Angle difference wrapped into (-pi, pi].
double wrap(double d) {
  d = std::remainder(d, 2 * M_PI);
  return d <= -M_PI ? d + 2 * M_PI : d;
}

std::invalid_argument section_error(const Section& s, Index row, const std::string& what) {
  return std::invalid_argument(
      "section " + s.id +
      (row >= 0 && static_cast<size_t>(row) < s.lines.size()
           ? " (line " + std::to_string(s.lines[static_cast<size_t>(row)]) + ")"
           : "") +
      ": " + what);
}

} // namespace

CylindricalLoft cylindrical_loft(const std::vector<Section>& sections, const GuideSet& meridians,
                                 const CylindricalLoftOptions& o) {
  const Index K = static_cast<Index>(sections.size());
  if (K < 2)
    throw std::invalid_argument("the cylindrical model needs at least 2 sections, got " +
                                std::to_string(K));
  if (o.degree < 1 || o.span_degree < 1 || !(o.tolerance > 0))
    throw std::invalid_argument("cylindrical model: degrees must be >= 1, the tolerance > 0");
  CylindricalLoft m;
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Section& s : sections) {
    if (s.points.rows() < std::max(3, o.degree + 1))
      throw section_error(
          s, 0, "needs at least " + std::to_string(std::max(3, o.degree + 1)) + " points");
    lo = lo.cwiseMin(s.points.colwise().minCoeff().transpose());
    hi = hi.cwiseMax(s.points.colwise().maxCoeff().transpose());
    mean += s.points.leftCols(2).colwise().mean().transpose() / static_cast<double>(K);
  }
  m.bbox_diagonal = (hi - lo).norm();
  const double tol = o.tolerance * m.bbox_diagonal;
  m.center = std::isnan(o.center_x) || std::isnan(o.center_y)
                 ? mean
                 : Eigen::Vector2d(o.center_x, o.center_y);

  // Sections: heights, polar angles (one monotone turn), radius traces R(t, z_k).
  LineTraces traces;
  traces.y.resize(K);
  std::vector<BSplineCurve> radius(static_cast<size_t>(K));
  for (Index k = 0; k < K; ++k) {
    const Section& s = sections[static_cast<size_t>(k)];
    const Index n = s.points.rows();
    // The section's height: the median z (one stray point does not move it).
    std::vector<double> zs(s.points.col(2).data(), s.points.col(2).data() + n);
    std::nth_element(zs.begin(), zs.begin() + n / 2, zs.end());
    const double zk = zs[static_cast<size_t>(n / 2)];
    for (Index i = 0; i < n; ++i)
      if (std::abs(s.points(i, 2) - zk) > tol)
        throw section_error(s, i,
                            "not in a plane z = const (|z - " + fmt(zk) +
                                "| = " + fmt(std::abs(s.points(i, 2) - zk)) + " > tolerance " +
                                fmt(tol) + ")");
    if (k > 0 && !(zk > traces.y(k - 1)))
      throw section_error(s, 0,
                          "sections must be ordered by increasing height z (this one is at " +
                              fmt(zk) + ", the previous at " + fmt(traces.y(k - 1)) + ")");
    traces.y(k) = zk;
    VectorXd t(n), r(n);
    for (Index i = 0; i < n; ++i) {
      const double dx = s.points(i, 0) - m.center(0), dy = s.points(i, 1) - m.center(1);
      r(i) = std::hypot(dx, dy);
      t(i) = std::atan2(dy, dx);
      if (!(r(i) > tol))
        throw section_error(s, i, "point on the axis: the section is not star-shaped around it");
    }
    // Steps of the polar angle: all of one sign, one full turn (star-shaped around the axis).
    double turn = 0;
    int sign = 0;
    for (Index i = 0; i < n; ++i) {
      const double d = wrap(t((i + 1) % n) - t(i));
      const int si = d > 0 ? 1 : (d < 0 ? -1 : 0);
      if (si == 0 || (sign != 0 && si != sign))
        throw section_error(s, (i + 1) % n,
                            "the polar angle around the axis (" + fmt(m.center(0)) + ", " +
                                fmt(m.center(1)) +
                                ") turns back here: the section is not star-shaped around it");
      sign = si;
      turn += d;
    }
    if (std::abs(std::abs(turn) - 2 * M_PI) > 1e-6)
      throw section_error(s, 0,
                          "does not go once around the axis (" + fmt(m.center(0)) + ", " +
                              fmt(m.center(1)) + ")");
    m.reversed.push_back(sign < 0);
    // Unwrapped increasing angles in the order of increasing angle.
    std::vector<Index> idx(static_cast<size_t>(n));
    std::iota(idx.begin(), idx.end(), 0);
    if (sign < 0)
      std::reverse(idx.begin(), idx.end());
    VectorXd u(n + 1), rr(n), angle(n);
    u(0) = t(idx[0]);
    for (Index i = 1; i < n; ++i)
      u(i) = u(i - 1) +
             std::abs(wrap(t(idx[static_cast<size_t>(i)]) - t(idx[static_cast<size_t>(i - 1)])));
    u(n) = u(0) + 2 * M_PI;
    for (Index i = 0; i < n; ++i) {
      rr(i) = r(idx[static_cast<size_t>(i)]);
      angle(idx[static_cast<size_t>(i)]) = u(i);
    }
    m.angles.push_back(angle);
    radius[static_cast<size_t>(k)] = interpolate_closed(rr, u, o.degree);
    traces.on_y.push_back(spline_trace(radius[static_cast<size_t>(k)]));
  }
  const auto section_radius = [&](Index k, double t) {
    return evaluate(radius[static_cast<size_t>(k)], VectorXd::Constant(1, t))(0, 0);
  };

  // Meridians t = t_l: radius samples along z, snapped to the sections' radii at their heights.
  struct Meridian {
    double t;
    VectorXd z, r;
  };
  std::vector<Meridian> mer;
  for (const Guide& g : meridians.guides) {
    // The meridian's angle: that of its first point off the axis.
    double cs = 0, sn = 0;
    for (Index j = 0; j < g.points.rows() && !(std::hypot(cs, sn) > tol); ++j) {
      cs = g.points(j, 0) - m.center(0);
      sn = g.points(j, 1) - m.center(1);
    }
    if (!(std::hypot(cs, sn) > tol))
      throw_input_error(meridians.path, g.lines[0],
                        "meridian " + g.id + " lies on the axis: no polar angle");
    const double tl = std::atan2(sn, cs), c = std::cos(tl), s = std::sin(tl);
    Meridian me{tl, VectorXd(g.points.rows()), VectorXd(g.points.rows())};
    for (Index j = 0; j < g.points.rows(); ++j) {
      const double dx = g.points(j, 0) - m.center(0), dy = g.points(j, 1) - m.center(1);
      const double off = -s * dx + c * dy, along = c * dx + s * dy;
      if (std::abs(off) > tol || along < -tol)
        throw_input_error(meridians.path, g.lines[static_cast<size_t>(j)],
                          "meridian " + g.id + ": this point is " + fmt(std::abs(off)) +
                              " off the half-plane through the axis at angle " + fmt(tl) +
                              " (tolerance " + fmt(tol) + ")");
      me.z(j) = g.points(j, 2);
      me.r(j) = along;
      if (j > 0 && !(me.z(j) > me.z(j - 1)))
        throw_input_error(meridians.path, g.lines[static_cast<size_t>(j)],
                          "meridian " + g.id + ": heights z must increase along the meridian");
    }
    for (Index k = 0; k < K; ++k) {
      Index hit = -1;
      for (Index j = 0; j < me.z.size(); ++j)
        if (std::abs(me.z(j) - traces.y(k)) <= tol)
          hit = j;
      if (hit < 0)
        throw_input_error(meridians.path, g.lines[0],
                          "meridian " + g.id + " has no point on section " +
                              sections[static_cast<size_t>(k)].id + " (z = " + fmt(traces.y(k)) +
                              "); give one point on every section");
      me.z(hit) = traces.y(k);
      me.r(hit) = section_radius(k, tl);
    }
    mer.push_back(me);
  }
  if (!mer.empty()) {
    // Angles in one period starting at the smallest, increasing, distinct.
    std::sort(mer.begin(), mer.end(),
              [](const Meridian& a, const Meridian& b) { return a.t < b.t; });
    traces.x.resize(static_cast<Index>(mer.size()));
    for (size_t l = 0; l < mer.size(); ++l) {
      traces.x(static_cast<Index>(l)) = mer[l].t;
      if (l > 0 && !(mer[l].t - mer[l - 1].t > 1e-9))
        throw_input_error(meridians.path, 0, "two meridians at the same angle " + fmt(mer[l].t));
      traces.on_x.push_back(
          sampled_trace(mer[l].z, mer[l].r,
                        static_cast<int>(std::min<Index>(o.span_degree, mer[l].z.size() - 1))));
    }
  }
  GordonOptions go;
  go.degree_x = o.degree >= 3 ? 3 : 1;
  go.periodic_x = true;
  go.period_x = 2 * M_PI;
  go.degree_y = o.span_degree;
  go.tolerance = 1e-9;
  m.z = traces.y;
  m.radius = gordon_surface(traces, go);

  // Every section point: S(t_i, z_k) against P_i.
  for (Index k = 0; k < K; ++k) {
    const Section& s = sections[static_cast<size_t>(k)];
    VectorXd dev(s.points.rows());
    for (Index i = 0; i < s.points.rows(); ++i) {
      const Vector3d p = evaluate(m, m.angles[static_cast<size_t>(k)](i), m.z(k));
      const double xy = (p.head<2>() - s.points.row(i).head<2>().transpose()).norm();
      if (!(xy <= 1e-9 * m.bbox_diagonal))
        throw std::runtime_error("cylindrical model: section " + s.id + " point " +
                                 std::to_string(i) + " is not reproduced (" + fmt(xy) + ")");
      dev(i) = (p - s.points.row(i).transpose()).norm();
    }
    m.max_deviation = std::max(m.max_deviation, dev.maxCoeff());
    m.deviation.push_back(dev);
  }
  return m;
}

Vector3d evaluate(const CylindricalLoft& m, double t, double z, int dt, int dz) {
  if (dt < 0 || dz < 0 || dt > 2 || dz > 2)
    throw std::invalid_argument("cylindrical model: derivative orders 0..2");
  Vector3d out = Vector3d::Zero();
  const double binom[3][3] = {{1, 0, 0}, {1, 1, 0}, {1, 2, 1}};
  for (int j = 0; j <= dt; ++j) {
    const double R = evaluate(m.radius, t, z, j, dz)(0), a = t + (dt - j) * M_PI / 2;
    out(0) += binom[dt][j] * R * std::cos(a);
    out(1) += binom[dt][j] * R * std::sin(a);
  }
  if (dt == 0 && dz == 0)
    out += Vector3d(m.center(0), m.center(1), z);
  else if (dt == 0 && dz == 1)
    out(2) = 1;
  return out;
}

ShapeMap shape_map(const CylindricalLoft& m, const VectorXd& t, const VectorXd& z, double tol) {
  ShapeMap s{t, z, Eigen::MatrixXi(t.size(), z.size()), Eigen::MatrixXi(t.size(), z.size())};
  const auto sign = [](double k, double tl) { return k > tl ? 1 : (k < -tl ? -1 : 0); };
  for (Index j = 0; j < z.size(); ++j)
    for (Index i = 0; i < t.size(); ++i) {
      const double R = evaluate(m.radius, t(i), z(j))(0),
                   Rt = evaluate(m.radius, t(i), z(j), 1, 0)(0),
                   Rtt = evaluate(m.radius, t(i), z(j), 2, 0)(0),
                   Rz = evaluate(m.radius, t(i), z(j), 0, 1)(0),
                   Rzz = evaluate(m.radius, t(i), z(j), 0, 2)(0);
      const double ku = (R * R + 2 * Rt * Rt - R * Rtt) / std::pow(R * R + Rt * Rt, 1.5);
      const double kv = -Rzz / std::pow(1 + Rz * Rz, 1.5);
      s.along_u(i, j) = sign(ku * m.bbox_diagonal, tol);
      s.along_v(i, j) = sign(kv * m.bbox_diagonal, tol);
    }
  return s;
}

} // namespace interlin
