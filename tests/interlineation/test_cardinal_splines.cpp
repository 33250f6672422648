// Cardinal blending functions (open and periodic) and collocation in a given spline space.
#include "interlin/interlineation/cardinal_splines.h"
#include "interlin/interlineation/spline_space.h"
#include "interlin/splines/interpolate_curve.h"

#include "support/test_surfaces.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

TEST_CASE("Open cardinal splines: delta at the nodes, partition of unity, smoothness class",
          "[cardinal]") {
  VectorXd x(6);
  x << -1, -0.7, 0.1, 0.15, 0.9, 2.0;
  for (int p : {1, 2, 3}) {
    const CardinalSplines c = cardinal_splines(x, p);
    for (Index k = 0; k < x.size(); ++k) {
      const MatrixXd a = evaluate(c, x(k), 0);
      for (Index i = 0; i < x.size(); ++i)
        // Collocation solve of condition ~10 on O(1) data: round-off.
        CHECK(a(0, i) == Approx(i == k ? 1.0 : 0.0).epsilon(0).margin(1e-14));
    }
    for (double s : VectorXd::LinSpaced(97, -1, 2)) {
      // Interpolation reproduces constants, so the weights sum to 1 and derivatives to 0.
      const MatrixXd a = evaluate(c, s, 2);
      CHECK(a.row(0).sum() == Approx(1.0).epsilon(0).margin(1e-14));
      CHECK(std::abs(a.row(1).sum()) < 1e-12);
    }
    // C^(p-1): derivative jumps across interior knots below round-off, order p jumps visible.
    const VectorXd& t = c.curve.knots;
    for (Index k = p + 1; k < t.size() - p - 1; ++k) {
      const MatrixXd l = evaluate(c, t(k) - 1e-9, p - 1), r = evaluate(c, t(k) + 1e-9, p - 1);
      CHECK((l.row(p - 1) - r.row(p - 1)).cwiseAbs().maxCoeff() < 1e-6);
    }
  }
  // Linear cardinal functions are the hats of composite Coons.
  const CardinalSplines hat = cardinal_splines(x, 1);
  CHECK(evaluate(hat, 0.5, 0)(0, 3) == Approx((0.9 - 0.5) / (0.9 - 0.15)).epsilon(1e-12));
  CHECK(evaluate(hat, 0.5, 0)(0, 4) == Approx((0.5 - 0.15) / (0.9 - 0.15)).epsilon(1e-12));
  CHECK_THROWS(cardinal_splines(Eigen::Vector3d(0, 1, 1), 3));
  CHECK_THROWS(cardinal_splines(VectorXd::Zero(1), 1));
}

TEST_CASE("Periodic cubic cardinal splines equal the periodic interpolants of the identity",
          "[cardinal]") {
  // Independent path for >= 4 nodes: interpolate_closed (odd degree: knots at the sites) of the
  // identity matrix is the same periodic C2 cubic spline with knots at the nodes.
  VectorXd nodes(5);
  nodes << 0.1, 0.3, 0.35, 0.6, 0.9;
  const CardinalSplines c = periodic_cardinal_splines(nodes, 0.0, 1.0, 3);
  VectorXd u(6);
  u << nodes, 1.1;
  const BSplineCurve ref = interpolate_closed(MatrixXd::Identity(5, 5), u, 3);
  for (double s : VectorXd::LinSpaced(101, 0, 1))
    for (int d = 0; d <= 2; ++d) {
      const MatrixXd a = evaluate(c, s, d);
      const MatrixXd b = evaluate(ref, VectorXd::Constant(1, s), d);
      // Two different linear solves on O(1) data; second derivatives scale with 1/h^2 ~ 400.
      CHECK((a.row(d) - b.row(0)).cwiseAbs().maxCoeff() < 1e-10 * std::pow(400.0, d / 2.0));
    }
  // Periodicity and C2 across the period's ends.
  for (int d = 0; d <= 2; ++d)
    CHECK((evaluate(c, 1e-12, d).row(d) - evaluate(c, 1.0 - 1e-12, d).row(d)).norm() < 1e-8);
  CHECK((evaluate(c, 0.25, 0) - evaluate(c, 3.25, 0)).norm() < 1e-14);
}

TEST_CASE("Periodic cardinal splines with few nodes", "[cardinal]") {
  // Two nodes (leading and trailing edge of a section): cubic, symmetric, sum 1.
  const CardinalSplines c = periodic_cardinal_splines(Eigen::Vector2d(0.0, 0.5), 0.0, 1.0, 3);
  CHECK(evaluate(c, 0.0, 0)(0, 0) == Approx(1.0).epsilon(1e-12));
  CHECK(std::abs(evaluate(c, 0.5, 0)(0, 0)) < 1e-15);
  for (double s : VectorXd::LinSpaced(41, 0, 1)) {
    const MatrixXd a = evaluate(c, s, 1);
    CHECK(a.row(0).sum() == Approx(1.0).epsilon(0).margin(1e-14));
    CHECK(a(0, 0) == Approx(evaluate(c, 1.0 - s, 0)(0, 0)).epsilon(0).margin(1e-14)); // symmetric
    CHECK(a(0, 0) >= -1e-15);
  }
  // Closed form for two equidistant nodes: M_0 = -M_1 = -24 (from the 2x2 cyclic system
  // [[2,1],[1,2]] (h+h) M = 6 (2/h)(e_1 - e_0), h = 1/2), so alpha_0 = 1 - 12 s^2 + 16 s^3 on
  // [0, 1/2].
  for (double s : {0.1, 0.2, 0.4})
    CHECK(evaluate(c, s, 0)(0, 0) == Approx(1 - 12 * s * s + 16 * s * s * s).epsilon(1e-13));
  // One node: the constant 1; hats for degree 1.
  CHECK(evaluate(periodic_cardinal_splines(VectorXd::Constant(1, 0.4), 0, 1, 3), 0.9, 1)(0, 0) ==
        Approx(1.0).epsilon(1e-12));
  const CardinalSplines h = periodic_cardinal_splines(Eigen::Vector3d(0.2, 0.5, 0.8), 0, 1, 1);
  CHECK(evaluate(h, 0.0, 0)(0, 0) == Approx(0.5).epsilon(1e-12)); // half-way from 0.8 - 1 to 0.2
  CHECK(evaluate(h, 0.0, 0)(0, 2) == Approx(0.5).epsilon(1e-12));
  CHECK_THROWS(periodic_cardinal_splines(Eigen::Vector2d(0.0, 1.0), 0, 1, 3)); // 1 = 0 + period
  CHECK_THROWS(periodic_cardinal_splines(Eigen::Vector2d(0.0, 0.5), 0, 1, 2));
}

TEST_CASE("Degree elevation by collocation keeps the curve", "[cardinal][spline_space]") {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int p : {1, 2, 3}) {
    BSplineCurve c;
    c.degree = p;
    c.knots = test::random_clamped_knots(rng, p, 9, 0.0, 2.0);
    c.ctrl = MatrixXd::NullaryExpr(9, 3, [&] { return U(rng); });
    for (int q = p; q <= 5; ++q) {
      const BSplineCurve e = elevate_degree(c, q);
      CHECK(e.degree == q);
      const VectorXd s = VectorXd::LinSpaced(201, 0, 2);
      CHECK((evaluate(e, s) - evaluate(c, s)).cwiseAbs().maxCoeff() < 1e-13);
    }
  }
  const VectorXd g = greville_abscissae((VectorXd(8) << 0, 0, 0, 0, 1, 1, 1, 1).finished(), 3);
  CHECK(g(1) == Approx(1.0 / 3).epsilon(1e-12));
  CHECK_THROWS(elevate_degree(
      BSplineCurve{3, VectorXd::LinSpaced(8, 0, 1), MatrixXd::Zero(4, 1), false}, 2));
}
