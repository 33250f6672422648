// Projection onto F = 0: bracketed roots on segments (exact against the sphere's radius, also
// for non-smooth R-functions and NaN ends), seed 003's step-then-scan-then-narrow along a
// direction (finding a thin wall the first step jumps over), outward directions.
#include "interlin/reconstruction/meshing/project_to_zero.h"

#include "support/test_implicits.h"

#include <atomic>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace interlin;

TEST_CASE("roots_on_segments: sphere radius along random segments, few evaluations", "[project]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  const ImplicitFunction s = test::sphere(1.0);
  std::atomic<long> evaluations{0};
  ImplicitFunction f = s;
  f.value = [&](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    evaluations += long(P.rows());
    s.value(P, F);
  };
  const long n = 5000;
  Points3 A(n, 3), B(n, 3);
  for (long i = 0; i < n; ++i) {
    Eigen::RowVector3d d(u(rng), u(rng), u(rng));
    d.normalize();
    A.row(i) = 0.3 * u(rng) * d;         // inside
    B.row(i) = (1.2 + u(rng) * 0.1) * d; // outside
  }
  Eigen::VectorXd FA(n), FB(n);
  s.value(A, FA);
  s.value(B, FB);
  RootOptions o;
  o.tolerance = 1e-12;
  const Eigen::VectorXd t = roots_on_segments(f, A, B, FA, FB, o);
  for (long i = 0; i < n; ++i) {
    const Eigen::RowVector3d p = A.row(i) + t(i) * (B.row(i) - A.row(i));
    // Bracket <= 1e-12 of a segment of length <= 1.6: radius to ~2e-12.
    CHECK(std::abs(p.norm() - 1) < 3e-12);
  }
  // Illinois on a smooth root: far fewer than bisection's 40 steps (measured 8.17 per segment).
  CHECK(evaluations < 10 * n);
  // A flat root, (1 - |x|)^9, where regula falsi alone creeps from one side: the bisection every
  // fourth step still halves the bracket, so at most 4 x bisection's 40 steps (measured 145; 208
  // before session 23, whose rule let a bisection's own halving skip the next one).
  f.value = [&](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    evaluations += long(P.rows());
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      F(i) = std::pow(1 - P.row(i).norm(), 9);
  };
  Eigen::VectorXd GA(n), GB(n);
  f.value(A, GA);
  f.value(B, GB);
  evaluations = 0;
  o.max_evaluations = 1000;
  const Eigen::VectorXd tf = roots_on_segments(f, A, B, GA, GB, o);
  CHECK(evaluations <= 4 * 40 * n);
  for (long i = 0; i < n; ++i)
    CHECK(std::abs((A.row(i) + tf(i) * (B.row(i) - A.row(i))).norm() - 1) < 3e-12);
  // Reversed segments (outside end first) give 1 - t.
  const Eigen::VectorXd r = roots_on_segments(s, B, A, FB, FA, o);
  CHECK((r - (Eigen::VectorXd::Ones(n) - t)).cwiseAbs().maxCoeff() < 3e-12);
}

TEST_CASE("roots_on_segments: corners of R-functions, NaN ends, exact zeros, bad input",
          "[project]") {
  const ImplicitFunction cube = test::r0_cube(1.0);
  // Towards an edge and a corner of the cube: the root is the edge/corner itself.
  Points3 A(2, 3), B(2, 3);
  A << 0, 0, 0, 0.1, 0.1, 0.1;
  B << 1.5, 1.5, 0, 2, 2, 2;
  Eigen::VectorXd FA(2), FB(2);
  cube.value(A, FA);
  cube.value(B, FB);
  const Eigen::VectorXd t = roots_on_segments(cube, A, B, FA, FB);
  CHECK((A.row(0) + t(0) * (B.row(0) - A.row(0))).isApprox(Eigen::RowVector3d(1, 1, 0), 1e-9));
  CHECK((A.row(1) + t(1) * (B.row(1) - A.row(1))).isApprox(Eigen::RowVector3d(1, 1, 1), 1e-9));
  // F is NaN beyond x = 0.5 (outside): bisection finds the NaN boundary.
  const ImplicitFunction half = test::implicit(
      [](double x, double, double) { return x > 0.5 ? std::nan("") : 1.0; }, test::cube_box(1));
  Points3 P(1, 3), Q(1, 3);
  P << 0, 0, 0;
  Q << 1, 0, 0;
  Eigen::VectorXd FP(1), FQ(1);
  FP << 1;
  FQ << std::nan("");
  CHECK(roots_on_segments(half, P, Q, FP, FQ)(0) == Approx(0.5).epsilon(0).margin(1e-9));
  // An end with F = 0 is the root.
  FQ << 0;
  CHECK(roots_on_segments(half, P, Q, FP, FQ)(0) == 1);
  // No sign change.
  FQ << 2;
  CHECK_THROWS_AS(roots_on_segments(half, P, Q, FP, FQ), std::invalid_argument);
}

TEST_CASE("project_along: step, scan, narrow (seed 003 findBorder)", "[project]") {
  const ImplicitFunction s = test::sphere(1.0);
  Eigen::MatrixXd P(4, 3), D(4, 3);
  P << 0.5, 0, 0, 1.3, 0, 0, 0, 0.2, 0.9, 0, 0, 1;
  D << 1, 0, 0, 2, 0, 0, 0, 0.2, 0.9, 0, 0, 1; // outward; any length
  const Eigen::VectorXd h = Eigen::VectorXd::Constant(4, 0.7);
  std::vector<char> moved;
  CHECK(project_along(s, P, D, h, {}, &moved) == 0);
  CHECK(P.row(0).isApprox(Eigen::RowVector3d(1, 0, 0), 1e-9));
  CHECK(P.row(1).isApprox(Eigen::RowVector3d(1, 0, 0), 1e-9)); // from outside, inward
  CHECK(P.row(2).norm() == Approx(1).epsilon(0).margin(1e-9));
  CHECK(P.row(3).isApprox(Eigen::RowVector3d(0, 0, 1), 0)); // F = 0 exactly: stays
  CHECK((moved == std::vector<char>{1, 1, 1, 1}));

  // A wall 0.02 thick at x in [1, 1.02]; from x = 0.7 (outside) the step h = 0.5 jumps over it,
  // the scan in steps of 0.005 finds its near face.
  const ImplicitFunction wall = test::implicit(
      [](double x, double, double) { return (x - 1) * (1.02 - x); }, test::cube_box(2));
  Eigen::MatrixXd W(1, 3), N(1, 3);
  W << 0.7, 0, 0;
  N << -1, 0, 0; // the outward normal of the near face; the point is outside, so it walks +x
  CHECK(project_along(wall, W, N, Eigen::VectorXd::Constant(1, 0.5)) == 0);
  CHECK(W(0, 0) == Approx(1).epsilon(0).margin(1e-9));
  // Nothing within 100 h: the point stays and is counted.
  Eigen::MatrixXd X(1, 3);
  X << 0.7, 0, 0;
  Eigen::MatrixXd away(1, 3);
  away << 1, 0, 0;
  CHECK(project_along(wall, X, away, Eigen::VectorXd::Constant(1, 0.001)) == 1);
  CHECK(X(0, 0) == 0.7);
}

TEST_CASE("outward_directions: gradient and central differences agree", "[project]") {
  ImplicitFunction with = test::sphere(2.0);
  ImplicitFunction without = with;
  without.gradient = nullptr;
  Eigen::MatrixXd P(3, 3);
  P << 1, 0, 0, 0.3, -0.4, 1.2, 0, 0, 0;
  const Eigen::MatrixXd a = outward_directions(with, P, 1e-3);
  const Eigen::MatrixXd b = outward_directions(without, P, 1e-3);
  CHECK(a.row(0).isApprox(Eigen::RowVector3d(1, 0, 0), 1e-12));
  // Central differences are exact for a quadratic up to round-off.
  CHECK((a.topRows(2) - b.topRows(2)).cwiseAbs().maxCoeff() < 1e-9);
  CHECK(a.row(2).isZero(0)); // zero gradient: zero direction
  CHECK(b.row(2).isZero(0));
}
