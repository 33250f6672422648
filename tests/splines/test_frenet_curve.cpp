// seed 004 §2.4: Frenet integration with piecewise-linear k(s), tau(s) — the helix, circle and
// line checks of the book (digest T-B6) against closed forms, RK4's fitted order, and planar
// agreement with the natural-curve quadrature.
#include "interlin/splines/frenet_curve.h"
#include "interlin/splines/natural_curve.h"

#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

PiecewiseLinearLaw constant(double v) {
  return {VectorXd::Zero(1), VectorXd::Constant(1, v)};
}

// Closed-form helix with curvature k and torsion tau, in the start frame (t0, n0, b0) = e_x, e_y,
// e_z at the origin, c = sqrt(k^2 + tau^2):
//   r(s) = t0 [tau^2 s / c^2 + k^2 sin(cs) / c^3] + n0 k (1 - cos cs) / c^2
//          + b0 k tau (s - sin(cs)/c) / c^2.
Vector3d helix(double k, double tau, double s) {
  const double c = std::hypot(k, tau);
  return {tau * tau * s / (c * c) + k * k * std::sin(c * s) / (c * c * c),
          k * (1 - std::cos(c * s)) / (c * c), k * tau * (s - std::sin(c * s) / c) / (c * c)};
}

} // namespace

TEST_CASE("Frenet: the book's circle, helix and line checks (digest T-B6)", "[splines][frenet]") {
  for (FrenetIntegrator m : {FrenetIntegrator::adaptive, FrenetIntegrator::rk4}) {
    FrenetOptions o;
    o.method = m;
    o.step = 1e-3; // RK4 error ~ h^4: 1e-12 on these O(1) curves
    // k = 1, tau = 0, s = pi/2 -> (1, 1, 0).
    const auto circ =
        integrate_frenet(constant(1), constant(0), VectorXd::Constant(1, M_PI / 2), {}, o);
    CHECK((circ[0].r - Vector3d(1, 1, 0)).norm() < 1e-11);
    // k = tau = 1, s = 2 pi / sqrt 2 -> (pi/sqrt2, 0, pi/sqrt2) = (2.2214414691, 0, 2.2214414691).
    const double S = 2 * M_PI / std::sqrt(2.0);
    const auto hel = integrate_frenet(constant(1), constant(1), VectorXd::Constant(1, S), {}, o);
    CHECK((hel[0].r - Vector3d(M_PI / std::sqrt(2.0), 0, M_PI / std::sqrt(2.0))).norm() < 1e-11);
    CHECK(hel[0].r.x() == Approx(2.2214414691).epsilon(0).margin(1e-10));
    // k = 0, tau = 1 -> the straight line (3, 0, 0) at s = 3.
    const auto line = integrate_frenet(constant(0), constant(1), VectorXd::Constant(1, 3.0), {}, o);
    CHECK((line[0].r - Vector3d(3, 0, 0)).norm() < 1e-12);
    // A general helix along its length, and the frame stays orthonormal.
    const VectorXd s = VectorXd::LinSpaced(25, 0, 12);
    const auto h = integrate_frenet(constant(0.7), constant(-0.4), s, {}, o);
    for (Eigen::Index i = 0; i < s.size(); ++i) {
      CHECK((h[static_cast<size_t>(i)].r - helix(0.7, -0.4, s(i))).norm() < 1e-10);
      const Eigen::Matrix3d F = (Eigen::Matrix3d() << h[static_cast<size_t>(i)].t,
                                 h[static_cast<size_t>(i)].n, h[static_cast<size_t>(i)].b)
                                    .finished();
      CHECK((F.transpose() * F - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-11);
    }
  }
}

TEST_CASE("Frenet RK4 converges with order 4 on the helix", "[splines][frenet][convergence]") {
  std::vector<double> hs, err;
  for (double h : {0.2, 0.1, 0.05, 0.025}) {
    FrenetOptions o;
    o.method = FrenetIntegrator::rk4;
    o.step = h;
    const auto f =
        integrate_frenet(constant(1.3), constant(0.6), VectorXd::Constant(1, 10.0), {}, o);
    hs.push_back(h);
    err.push_back((f[0].r - helix(1.3, 0.6, 10.0)).norm());
  }
  const double order = test::fitted_order(hs, err);
  INFO("errors " << err[0] << " " << err[3] << ", order " << order);
  CHECK(order == Approx(4.0).epsilon(0).margin(0.2)); // classical Runge–Kutta
}

TEST_CASE("Frenet with piecewise-linear k and tau = 0 equals the planar natural curve",
          "[splines][frenet]") {
  // k rises linearly to 1.2 at s = 1.5, then falls to 0.2 at s = 4 (the book's "epure" shape).
  PiecewiseLinearLaw k{(VectorXd(3) << 0, 1.5, 4).finished(),
                       (VectorXd(3) << 0, 1.2, 0.2).finished()};
  CHECK(evaluate(k, 0.75) == Approx(0.6).epsilon(0).margin(1e-15));
  CHECK(evaluate(k, 5.0) == 0.2); // constant beyond the last break
  const auto f = integrate_frenet(k, constant(0), VectorXd::Constant(1, 4.0));
  // Planar reference: two natural pieces with linear curvature, by Gauss–Legendre quadrature.
  PlanarNaturalCurve a;
  a.law = polynomial_law(Eigen::Vector2d(0, 0.8));
  a.length = 1.5;
  PlanarNaturalCurve b;
  b.law = polynomial_law(Eigen::Vector2d(1.2, -0.4));
  b.length = 2.5;
  b.start = natural_point(a, 1.5);
  b.phi0 = tangent_angle(a, 1.5);
  const Eigen::Vector2d end = natural_point(b, 2.5);
  CHECK(std::abs(f[0].r.z()) < 1e-15);
  CHECK((f[0].r.head<2>() - end).norm() < 1e-11);
  CHECK(std::atan2(f[0].t.y(), f[0].t.x()) == Approx(tangent_angle(b, 2.5)).epsilon(0).margin(1e-11));
}

TEST_CASE("Frenet rejects bad laws, frames and options", "[splines][frenet]") {
  PiecewiseLinearLaw bad{(VectorXd(2) << 1, 1).finished(), (VectorXd(2) << 0, 1).finished()};
  CHECK_THROWS_WITH(integrate_frenet(bad, constant(0), VectorXd::Constant(1, 1.0)),
                    Catch::Contains("increase strictly"));
  FrenetFrame skew;
  skew.n = Vector3d(1, 1, 0);
  CHECK_THROWS_WITH(integrate_frenet(constant(1), constant(0), VectorXd::Constant(1, 1.0), skew),
                    Catch::Contains("orthonormal"));
  FrenetOptions o;
  o.method = FrenetIntegrator::rk4;
  o.step = -1;
  CHECK_THROWS_WITH(integrate_frenet(constant(1), constant(0), VectorXd::Constant(1, 1.0), {}, o),
                    Catch::Contains("step"));
  CHECK_THROWS_WITH(integrate_frenet(constant(1), constant(0), (VectorXd(2) << 2, 1).finished()),
                    Catch::Contains("non-decreasing"));
}
