#pragma once
// seed 004 (Borysenko, Ustenko, Ustenko, natural parametrization), §1.3–1.4, digest 004 §2.1,
// §2.4, §3.1: planar curves given by their curvature as a function of arc length.
//
//   phi(s) = phi_0 + int_0^s k(t) dt                  (1.3)  tangent angle, from +x, CCW
//   x(s)   = x_0 + int_0^s cos phi(t) dt              (1.4)
//   y(s)   = y_0 + int_0^s sin phi(t) dt
//
// The curvature law is a polynomial in s (any degree; the book uses 0..5) plus sinusoids, which
// covers the book's sine laws (1.5), (1.6) and the third law of §1.4; phi is then in closed form
// and only x, y need quadrature: adaptive Gauss–Legendre (default, ~1e-14) or the book's
// trapezoid rule with 2000 intervals (digest §2.4, "book mode").

#include <Eigen/Core>
#include <vector>

namespace interlin {

// amplitude * sin(frequency * s + phase)
struct Sinusoid {
  double amplitude = 0;
  double frequency = 1;
  double phase = 0;
};

// k(s) = sum_j poly(j) s^j + sum_m waves[m](s).
struct CurvatureLaw {
  Eigen::VectorXd poly;
  std::vector<Sinusoid> waves;
};

// Polynomial law k(s) = sum_j c(j) s^j (seed 004 (1.7), (1.13), §1.9 and Ch. 5: degrees 1..5).
CurvatureLaw polynomial_law(const Eigen::VectorXd& c);
// seed 004 (1.5): k = a sin(b s) + c.
CurvatureLaw sine_law(double a, double b, double c);
// seed 004 (1.6): k = A sin^2(b s) + 1  (= A/2 + 1 - (A/2) cos 2bs).
CurvatureLaw sine_squared_law(double A, double b);
// seed 004 §1.4, third law: k = A sin^2 s + sin s + 1.
CurvatureLaw sine_squared_sine_law(double A);

// k^(deriv)(s), deriv >= 0.
double curvature(const CurvatureLaw& k, double s, int deriv = 0);
// int_0^s k(t) dt in closed form (seed 004 (1.3); for (1.5) phi = phi_0 + c s - (a/b)(cos bs - 1)).
double turning(const CurvatureLaw& k, double s);

// A planar natural curve: start point, start tangent angle phi0 (radians), law, length S >= 0.
struct PlanarNaturalCurve {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  double phi0 = 0;
  CurvatureLaw law;
  double length = 0;
};

// Tangent angle phi(s) = phi0 + turning(law, s)  (1.3).
double tangent_angle(const PlanarNaturalCurve& c, double s);

enum class NaturalQuadrature {
  adaptive_gauss, // adaptive Gauss–Legendre (8 points per panel, panel halving), default
  trapezoid       // composite trapezoid with `intervals` panels on [0, s]: the book's rule
};

struct QuadratureOptions {
  NaturalQuadrature rule = NaturalQuadrature::adaptive_gauss;
  double tolerance = 1e-14; // adaptive: absolute error per unit length
  int intervals = 2000;     // trapezoid: the book's 2000 (digest §2.4)
};

// (x(s), y(s)) by (1.4). s may exceed the curve's length (the law continues). Throws
// std::invalid_argument for a non-finite s or law.
Eigen::Vector2d natural_point(const PlanarNaturalCurve& c, double s,
                              const QuadratureOptions& q = {});

// Dense sampling and curvature-plot data at #s increasing arc lengths s (for example
// VectorXd::LinSpaced(n, 0, S)).
//   points  #s by 2 (x, y);   phi, k, dk  #s each: tangent angle, k(s), k'(s)
// Adaptive mode integrates sample to sample; trapezoid mode integrates each point from 0 with
// `intervals` panels, as the book does.
struct NaturalSamples {
  Eigen::VectorXd s;
  Eigen::MatrixXd points;
  Eigen::VectorXd phi;
  Eigen::VectorXd k;
  Eigen::VectorXd dk;
};
NaturalSamples sample_natural_curve(const PlanarNaturalCurve& c, const Eigen::VectorXd& s,
                                    const QuadratureOptions& q = {});

} // namespace interlin
