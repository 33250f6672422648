// seed 004 §1.3–1.4 (digest 004 §2.1, §2.4, §3.1): planar curves in natural parametrization.
#include "interlin/splines/natural_curve.h"

#include "natural_quadrature.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::Vector2d;
using Eigen::VectorXd;

namespace {

void check_law(const CurvatureLaw& k) {
  if (!k.poly.allFinite())
    throw std::invalid_argument("curvature law: coefficients must be finite");
  for (const Sinusoid& w : k.waves)
    if (!std::isfinite(w.amplitude) || !std::isfinite(w.frequency) || !std::isfinite(w.phase))
      throw std::invalid_argument("curvature law: sinusoid parameters must be finite");
}

// Rough bound of |k| on [0, s] from samples, to size the first quadrature panels.
double curvature_scale(const CurvatureLaw& k, double s) {
  double m = 0;
  for (int i = 0; i <= 16; ++i)
    m = std::max(m, std::abs(curvature(k, s * i / 16.0)));
  double wmax = 0;
  for (const Sinusoid& w : k.waves)
    wmax = std::max(wmax, std::abs(w.frequency));
  return m + wmax;
}

void check_quadrature(const QuadratureOptions& q) {
  if (q.rule == NaturalQuadrature::trapezoid && q.intervals < 1)
    throw std::invalid_argument("natural curve: trapezoid rule needs intervals >= 1");
  if (q.rule == NaturalQuadrature::adaptive_gauss && !(q.tolerance > 0))
    throw std::invalid_argument("natural curve: quadrature tolerance must be > 0");
}

} // namespace

CurvatureLaw polynomial_law(const VectorXd& c) {
  CurvatureLaw k;
  k.poly = c;
  check_law(k);
  return k;
}

CurvatureLaw sine_law(double a, double b, double c) {
  CurvatureLaw k;
  k.poly = VectorXd::Constant(1, c);
  k.waves.push_back({a, b, 0.0});
  check_law(k);
  return k;
}

CurvatureLaw sine_squared_law(double A, double b) {
  // sin^2(bs) = 1/2 - cos(2bs)/2 = 1/2 + sin(2bs - pi/2)/2.
  CurvatureLaw k;
  k.poly = VectorXd::Constant(1, 1.0 + A / 2);
  k.waves.push_back({A / 2, 2 * b, -M_PI / 2});
  check_law(k);
  return k;
}

CurvatureLaw sine_squared_sine_law(double A) {
  CurvatureLaw k = sine_squared_law(A, 1.0);
  k.waves.push_back({1.0, 1.0, 0.0});
  return k;
}

double curvature(const CurvatureLaw& k, double s, int deriv) {
  if (deriv < 0)
    throw std::invalid_argument("derivative order must be >= 0");
  double v = 0;
  for (Index j = k.poly.size() - 1; j >= deriv; --j) {
    double f = 1;
    for (int m = 0; m < deriv; ++m)
      f *= static_cast<double>(j - m);
    v = v * s + f * k.poly(j);
  }
  for (const Sinusoid& w : k.waves)
    v += w.amplitude * std::pow(w.frequency, deriv) *
         std::sin(w.frequency * s + w.phase + deriv * M_PI / 2);
  return v;
}

double turning(const CurvatureLaw& k, double s) {
  double v = 0;
  for (Index j = k.poly.size() - 1; j >= 0; --j)
    v = v * s + k.poly(j) / static_cast<double>(j + 1);
  v *= s;
  for (const Sinusoid& w : k.waves)
    v += w.frequency == 0.0 ? w.amplitude * std::sin(w.phase) * s
                            : -w.amplitude / w.frequency *
                                  (std::cos(w.frequency * s + w.phase) - std::cos(w.phase));
  return v;
}

double tangent_angle(const PlanarNaturalCurve& c, double s) {
  return c.phi0 + turning(c.law, s);
}

Vector2d natural_point(const PlanarNaturalCurve& c, double s, const QuadratureOptions& q) {
  if (!std::isfinite(s) || !std::isfinite(c.phi0) || !c.start.allFinite())
    throw std::invalid_argument("natural curve: start, angle and arc length must be finite");
  check_law(c.law);
  check_quadrature(q);
  const auto f = [&](double t) {
    const double phi = tangent_angle(c, t);
    return Vector2d(std::cos(phi), std::sin(phi));
  };
  if (q.rule == NaturalQuadrature::trapezoid)
    return c.start + detail::trapezoid(f, 0.0, s, q.intervals);
  return c.start + detail::adaptive_gauss(f, 0.0, s, q.tolerance, curvature_scale(c.law, s));
}

NaturalSamples sample_natural_curve(const PlanarNaturalCurve& c, const VectorXd& s,
                                    const QuadratureOptions& q) {
  for (Index i = 1; i < s.size(); ++i)
    if (!(s(i) >= s(i - 1)))
      throw std::invalid_argument("natural curve sampling: arc lengths must be non-decreasing");
  check_quadrature(q);
  check_law(c.law);
  NaturalSamples out;
  out.s = s;
  out.points.resize(s.size(), 2);
  out.phi.resize(s.size());
  out.k.resize(s.size());
  out.dk.resize(s.size());
  Vector2d p = c.start;
  double prev = 0;
  for (Index i = 0; i < s.size(); ++i) {
    if (q.rule == NaturalQuadrature::trapezoid) {
      p = natural_point(c, s(i), q);
    } else {
      // Integrate from the previous sample only: the total error stays at the per-panel level.
      const auto f = [&](double t) {
        const double phi = tangent_angle(c, t);
        return Vector2d(std::cos(phi), std::sin(phi));
      };
      if (!std::isfinite(s(i)))
        throw std::invalid_argument("natural curve sampling: arc lengths must be finite");
      p += detail::adaptive_gauss(f, prev, s(i), q.tolerance, curvature_scale(c.law, s(i)));
      prev = s(i);
    }
    out.points.row(i) = p.transpose();
    out.phi(i) = tangent_angle(c, s(i));
    out.k(i) = curvature(c.law, s(i));
    out.dk(i) = curvature(c.law, s(i), 1);
  }
  return out;
}

} // namespace interlin
