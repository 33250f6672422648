// seed 001 §2.2 / T18: closed section curves from points (the seed's system and its singular
// alternating mode, periodic interpolation that avoids it, the per-coordinate Theorem 2 spline),
// and least-squares approximation with smoothing and a tolerance for noisy sections.
#include "interlin/splines/approximate_curve.h"
#include "interlin/splines/closed_section_curve.h"
#include "interlin/splines/min_jump_quadratic.h"
#include "interlin/splines/parameterization.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// T18 data: 33 points on x = 2 cos(th), y = sin(th), th_p = 2 pi (p/32 + 0.02 sin(2 pi p/32)),
// p = 0..32 (P_32 = P_0 when `repeat`).
MatrixXd t18_points(bool repeat) {
  MatrixXd P(repeat ? 33 : 32, 2);
  for (Index p = 0; p < P.rows(); ++p) {
    const double th = 2 * M_PI * (p / 32.0 + 0.02 * std::sin(2 * M_PI * p / 32.0));
    P.row(p) << 2 * std::cos(th), std::sin(th);
  }
  return P;
}

// |sqrt(x^2/4 + y^2) - 1|: the ellipse's normalised implicit error (digest T18's measure).
double ellipse_error(double x, double y) {
  return std::abs(std::sqrt(x * x / 4 + y * y) - 1);
}

MatrixXd uniform_ellipse(Index intervals) { // points on the ellipse at uniform angles, repeated
  MatrixXd P(intervals + 1, 2);
  for (Index p = 0; p <= intervals; ++p)
    P.row(p) << 2 * std::cos(2 * M_PI * p / intervals), std::sin(2 * M_PI * p / intervals);
  P.row(intervals) = P.row(0);
  return P;
}

} // namespace

TEST_CASE("T18: chord parameters and the per-coordinate Theorem 2 section curve",
          "[splines][section][theorem2]") {
  const MatrixXd P = t18_points(false);
  const VectorXd F = chord_parameters(P, true);
  double total = 0;
  for (Index i = 0; i < 32; ++i)
    total += (P.row((i + 1) % 32) - P.row(i)).norm();
  // Digest T18 [MINE] values (8 digits printed).
  CHECK(total == Approx(9.6725840).epsilon(0).margin(1e-7));
  CHECK(F(1) == Approx(0.0231992).epsilon(0).margin(1e-7));
  CHECK(F(16) == Approx(0.5).epsilon(0).margin(1e-12)); // symmetric data
  // x(t) and y(t) by Theorem 2 on the 33 nodes F_0..F_32 (values P_32 = P_0).
  VectorXd x(33), y(33);
  for (Index p = 0; p < 33; ++p)
    x(p) = P(p % 32, 0), y(p) = P(p % 32, 1);
  const MinJumpQuadratic SX = min_jump_quadratic(F, x), SY = min_jump_quadratic(F, y);
  const VectorXd t = VectorXd::LinSpaced(4001, 0, 1);
  const VectorXd cx = evaluate(SX, t), cy = evaluate(SY, t);
  double e = 0;
  for (Index k = 0; k < t.size(); ++k)
    e = std::max(e, ellipse_error(cx(k), cy(k)));
  CHECK(e == Approx(2.868e-4).epsilon(0).margin(6e-8)); // digest: 2.868e-4
  const VectorXd half = VectorXd::Constant(1, 0.5);
  CHECK(evaluate(SX, half)(0) == Approx(-2.0).epsilon(0).margin(1e-12));
  CHECK(evaluate(SY, half)(0) == Approx(0).epsilon(0).margin(1e-12));
  // The seam is only C0: x' changes sign across it (digest [MINE] values, 7-8 digits).
  const VectorXd ends = (VectorXd(2) << 0.0, 1.0).finished();
  const VectorXd dx = evaluate(SX, ends, 1), dy = evaluate(SY, ends, 1);
  CHECK(dx(0) == Approx(-0.0184839).epsilon(0).margin(1e-7));
  CHECK(dx(1) == Approx(0.0184839).epsilon(0).margin(1e-7));
  CHECK(dy(0) == Approx(9.9783551).epsilon(0).margin(1e-7));
  CHECK(dy(1) == Approx(9.9783551).epsilon(0).margin(1e-7));
}

TEST_CASE("T18: the seed's system (knots at the data parameters) is singular for 33 points",
          "[splines][section]") {
  // 33 points, 32 uniform intervals: the alternating mode -> detected, no garbage returned.
  MatrixXd P = uniform_ellipse(32);
  VectorXd F = VectorXd::LinSpaced(33, 0, 1);
  CHECK_THROWS_WITH(seed_section_curve(P, F),
                    Catch::Contains("singular") && Catch::Contains("alternating"));
  // 34 points, 33 intervals: regular; the curve interpolates and closes with equal tangents.
  P = uniform_ellipse(33);
  F = VectorXd::LinSpaced(34, 0, 1);
  const BSplineCurve c = seed_section_curve(P, F);
  CHECK(c.ctrl.rows() == 35);
  // Condition number ~3e3 (measured smallest relative singular value 3.6e-4): 1e-12 absolute.
  CHECK((evaluate(c, F) - P).cwiseAbs().maxCoeff() < 1e-12);
  const MatrixXd d = evaluate(c, (VectorXd(2) << 0.0, 1.0).finished(), 1);
  CHECK((d.row(0) - d.row(1)).norm() < 1e-10);
  // Bad input: the polygon must be closed by repeating its first point.
  MatrixXd open = P;
  open(33, 0) += 0.1;
  CHECK_THROWS_WITH(seed_section_curve(open, F), Catch::Contains("repeat the first"));
}

TEST_CASE("T18: closed_section_curve avoids the singular mode, quadratic and cubic",
          "[splines][section]") {
  const MatrixXd P = t18_points(false); // 32 distinct points: the singular count for p = 2
  double err[4] = {0, 0, 0, 0};
  for (int p : {2, 3}) {
    SectionCurveOptions o;
    o.degree = p;
    const SectionCurve s = closed_section_curve(P, o);
    CHECK(s.curve.periodic);
    CHECK(s.max_deviation < 1e-13); // through every point
    const VectorXd t = VectorXd::LinSpaced(4001, 0, 1);
    const MatrixXd C = evaluate(s.curve, t);
    double e = 0;
    for (Index k = 0; k < t.size(); ++k)
      e = std::max(e, ellipse_error(C(k, 0), C(k, 1)));
    err[p] = e;
    // Tangent continuity at the seam (periodic: C^{p-1}).
    const MatrixXd d = evaluate(s.curve, (VectorXd(2) << 0.0, 1.0 - 1e-14).finished(), 1);
    CHECK((d.row(0) - d.row(1)).norm() < 1e-9 * d.row(0).norm());
  }
  // Measured 2.97e-4 (quadratic) and 1.19e-4 (cubic): the quadratic is as accurate as the
  // per-coordinate Theorem 2 curve (2.868e-4) but C1 at the seam; the cubic is better.
  INFO("max ellipse error: quadratic " << err[2] << ", cubic " << err[3]);
  CHECK(err[2] < 3.2e-4);
  CHECK(err[3] < 0.5 * err[2]);
  SectionCurveOptions bad;
  bad.degree = 40;
  CHECK_THROWS_WITH(closed_section_curve(P, bad), Catch::Contains("needs more than 40 points"));
}

TEST_CASE("Curve approximation: tolerance, smoothing and reported deviation on noisy sections",
          "[splines][approximation]") {
  std::mt19937 rng(17);
  std::normal_distribution<double> noise(0.0, 2e-3);
  const Index N = 240;
  MatrixXd P(N, 2), truth(N, 2);
  for (Index i = 0; i < N; ++i) {
    const double th = 2 * M_PI * i / N;
    truth.row(i) << 2 * std::cos(th), std::sin(th);
    P.row(i) = truth.row(i) + Eigen::RowVector2d(noise(rng), noise(rng));
  }
  // Tolerance: the fit grows its control net until every point is within 8e-3 (4 sigma).
  ApproximationOptions o;
  o.closed = true;
  o.tolerance = 8e-3;
  const Approximation a = approximate_curve(P, o);
  CHECK(a.met_tolerance);
  CHECK(a.max_deviation <= 8e-3);
  const VectorXd dev = (evaluate(a.curve, a.u) - P).rowwise().norm();
  CHECK(a.max_deviation ==
        Approx(dev.maxCoeff()).epsilon(0).margin(1e-15)); // reported = recomputed
  CHECK(dev(a.worst_point) == a.max_deviation);
  CHECK(a.curve.ctrl.rows() - a.curve.degree < N); // an approximation, not an interpolation
  // It filters the noise: the curve at the data parameters is closer to the true ellipse than
  // the data are (rms of the data's noise is 2e-3 * sqrt 2).
  double rms = 0;
  const MatrixXd C = evaluate(a.curve, a.u);
  for (Index i = 0; i < N; ++i)
    rms += std::pow(ellipse_error(C(i, 0), C(i, 1)), 2);
  rms = std::sqrt(rms / N);
  INFO("rms implicit error " << rms);
  CHECK(rms < 2e-3);

  // Smoothing: more weight, less bending energy, larger deviation (fixed control net).
  double last_energy = INFINITY, last_dev = 0;
  for (double lambda : {0.0, 1e-7, 1e-5, 1e-3}) {
    ApproximationOptions s;
    s.closed = true;
    s.num_ctrl = 60;
    s.smoothing = lambda;
    const Approximation f = approximate_curve(P, s);
    const double energy = bending_energy(f.curve);
    CHECK(energy < last_energy);
    CHECK(f.rms_deviation >= last_dev);
    last_energy = energy;
    last_dev = f.rms_deviation;
  }
  // With as many control points as points and no smoothing it interpolates (open and closed).
  for (bool closed : {false, true}) {
    ApproximationOptions i;
    i.closed = closed;
    i.num_ctrl = 40;
    const Approximation f = approximate_curve(P.topRows(40), i);
    CHECK(f.max_deviation < 1e-10);
  }
  // Open curve with few control points reproduces a cubic polynomial curve exactly.
  MatrixXd Q(50, 2);
  for (Index i = 0; i < 50; ++i) {
    const double x = i / 49.0;
    Q.row(i) << x, x * x * x - 0.5 * x;
  }
  ApproximationOptions c;
  c.num_ctrl = 6;
  CHECK(approximate_curve(Q, c).max_deviation < 1e-2); // chord parameters are not x: close
}

TEST_CASE("Curve approximation rejects bad options", "[splines][approximation]") {
  MatrixXd P(3, 2);
  P << 0, 0, 1, 0, 1, 1;
  ApproximationOptions o;
  o.degree = 3;
  CHECK_THROWS_WITH(approximate_curve(P, o), Catch::Contains("needs more than 3 points"));
  o.degree = 2;
  o.smoothing = -1;
  CHECK_THROWS_WITH(approximate_curve(P, o), Catch::Contains("smoothing"));
  o.smoothing = 0;
  o.num_ctrl = 9;
  CHECK_THROWS_WITH(approximate_curve(P, o), Catch::Contains("num_ctrl"));
  P(1, 0) = NAN;
  o.num_ctrl = 0;
  CHECK_THROWS_WITH(approximate_curve(P, o), Catch::Contains("finite"));
}

// knot_weights: the knots split the cumulative interval weight evenly. Points at u = i / 16 with
// weight 3 on the first half and 1 on the second: the weight reaches 24 of 32 at u = 1/2, so 8
// control points put knots at 4j / 48 for j <= 6 (0, 1/12, ..., 1/2) and at 1/2 + 4 / 16 = 3/4;
// weights all 1 give the parameter quantiles, as no weights do.
TEST_CASE("Curve approximation: knots spaced by interval weights", "[splines][approximation]") {
  const Index N = 16;
  MatrixXd P(N, 2);
  for (Index i = 0; i < N; ++i)
    P.row(i) << std::cos(2 * M_PI * double(i) / N), std::sin(2 * M_PI * double(i) / N);
  ApproximationOptions o;
  o.closed = true;
  o.num_ctrl = 8;
  o.parameters = VectorXd::LinSpaced(N + 1, 0, 1);
  const Approximation even = approximate_curve(P, o);
  o.knot_weights = VectorXd::Ones(N);
  CHECK(approximate_curve(P, o).curve.knots == even.curve.knots);
  o.knot_weights.head(N / 2).setConstant(3);
  const VectorXd t = approximate_curve(P, o).curve.knots;
  const int p = 3; // the period's knots start at index p
  for (int j = 0; j <= 6; ++j)
    CHECK(t(p + j) == Approx(4.0 * j / 48).margin(1e-15));
  CHECK(t(p + 7) == Approx(0.75).margin(1e-15));
  CHECK(t(p + 8) == Approx(1.0).margin(1e-15));
  o.knot_weights(2) = 0;
  CHECK_THROWS_WITH(approximate_curve(P, o), Catch::Contains("positive"));
  o.knot_weights = VectorXd::Ones(N - 1);
  CHECK_THROWS_WITH(approximate_curve(P, o), Catch::Contains("knot_weights"));
  o.knot_weights = VectorXd::Ones(N);
  o.closed = false;
  o.parameters = VectorXd::LinSpaced(N, 0, 1);
  CHECK_THROWS_WITH(approximate_curve(P, o), Catch::Contains("closed curves only"));
}

// knot_grid: separately fitted closed curves share knot values (multiples of the grid), so their
// knot union has no span shorter than the grid; the fit moves by far less than the noise.
TEST_CASE("Curve approximation: knots on a grid", "[splines][approximation]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 2 * M_PI);
  std::normal_distribution<double> noise(0.0, 1e-3);
  for (int n : {60, 300}) {
    std::vector<double> th(static_cast<size_t>(n));
    for (double& t : th)
      t = U(rng);
    std::sort(th.begin(), th.end());
    MatrixXd P(n, 2);
    for (Index i = 0; i < n; ++i)
      P.row(i) << 2 * std::cos(th[size_t(i)]) + noise(rng), std::sin(th[size_t(i)]) + noise(rng);
    ApproximationOptions o;
    o.closed = true;
    o.num_ctrl = n / 4;
    const Approximation free = approximate_curve(P, o);
    o.knot_grid = 1.0 / 65536;
    const Approximation grid = approximate_curve(P, o);
    INFO(n << " points");
    for (Index k = 0; k < grid.curve.knots.size(); ++k) {
      const double m = grid.curve.knots(k) / o.knot_grid;
      CHECK(m == std::round(m));
      CHECK(std::abs(grid.curve.knots(k) - free.curve.knots(k)) <= 0.5 * o.knot_grid);
    }
    // a knot moved by at most 2^-17 of the period: the curves differ by a small fraction of
    // the noise 1e-3 (measured 2.2e-6 and 8.8e-7)
    const double moved =
        (evaluate(grid.curve, grid.u) - evaluate(free.curve, free.u)).cwiseAbs().maxCoeff();
    INFO("the curve moved by " << moved);
    CHECK(moved < 1e-4);
  }
  ApproximationOptions bad;
  bad.knot_grid = 1.0 / 64;
  MatrixXd Q(8, 2);
  for (Index i = 0; i < 8; ++i)
    Q.row(i) << std::cos(i * M_PI / 4), std::sin(i * M_PI / 4);
  CHECK_THROWS_WITH(approximate_curve(Q, bad), Catch::Contains("closed curves only"));
  bad.closed = true;
  bad.parameters = VectorXd::LinSpaced(9, 0, 1.01); // a period off the grid
  CHECK_THROWS_WITH(approximate_curve(Q, bad), Catch::Contains("multiples"));
}
