// seed 001, Theorem 1: digest 001 test cases T1–T6 (exact rationals) and Cox–de Boor agreement.
#include "interlin/splines/cox_de_boor.h"
#include "interlin/splines/explicit_bspline.h"

#include <catch2/catch.hpp>
#include <functional>
#include <random>

using namespace interlin;
using Eigen::VectorXd;

namespace {

// Rational reference values are exact; the explicit form accumulates a few roundings per span
// (Taylor propagation over at most n+1 spans and one small solve), so 1e-14 absolute on values
// of order 1 is the double-precision budget the issue asks for.
constexpr double kExact = 1e-14;

VectorXd knots(std::initializer_list<double> v) {
  VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double d : v)
    x(i++) = d;
  return x;
}

// N_{0,n}(x; X) by the Cox–de Boor definition (half-open spans), touching only X_0..X_{n+1}:
// independent of every piece of the explicit construction.
double cox_single(const VectorXd& t, int n, double x) {
  std::function<double(int, int)> N = [&](int i, int p) -> double {
    if (p == 0)
      return (t(i) <= x && x < t(i + 1)) ? 1.0 : 0.0;
    double r = 0;
    if (t(i + p) > t(i))
      r += (x - t(i)) / (t(i + p) - t(i)) * N(i, p - 1);
    if (t(i + p + 1) > t(i + 1))
      r += (t(i + p + 1) - x) / (t(i + p + 1) - t(i + 1)) * N(i + 1, p - 1);
    return r;
  };
  return N(0, n);
}

} // namespace

TEST_CASE("T1: quadratic B-spline on (0,1,3,4) matches the exact rationals",
          "[splines][theorem1]") {
  const VectorXd X = knots({0, 1, 3, 4});
  const ExplicitBSpline N = explicit_bspline(X, 2);
  const double xs[] = {0.5, 1, 1.5, 2, 2.5, 3, 3.5};
  const double ys[] = {1. / 12, 1. / 3, 7. / 12, 2. / 3, 7. / 12, 1. / 3, 1. / 12};
  for (int i = 0; i < 7; ++i)
    CHECK(evaluate(N, xs[i]) == Approx(ys[i]).epsilon(0).margin(kExact));
  CHECK(evaluate(N, -1.0) == 0.0);
  CHECK(evaluate(N, 0.0) == 0.0);
  CHECK(evaluate(N, 4.0) == 0.0);
  CHECK(evaluate(N, 5.0) == 0.0);
  const VectorXd y = theorem1_y(X, 2);
  CHECK(y(0) == Approx(2. / 3).epsilon(0).margin(kExact));
  CHECK(y(1) == Approx(-2. / 3).epsilon(0).margin(kExact));
  // The seed's closing condition for n = 2: y_2 = -y_1 (X_2-X_0)/(X_3-X_1).
  CHECK(y(1) == Approx(-y(0) * (X(2) - X(0)) / (X(3) - X(1))).epsilon(0).margin(kExact));
}

TEST_CASE("T2: uniform quadratic Taylor data per span", "[splines][theorem1]") {
  const ExplicitBSpline N = explicit_bspline(knots({0, 1, 2, 3}), 2);
  REQUIRE(N.taylor.rows() == 3);
  const double D[3][3] = {{0, 0, 1}, {0.5, 1, -2}, {0.5, -1, 1}}; // D0, D1, D2 (= top)
  for (int j = 0; j < 3; ++j)
    for (int q = 0; q < 3; ++q)
      CHECK(N.taylor(j, q) == Approx(D[j][q]).epsilon(0).margin(kExact));
  CHECK(evaluate(N, 1.5) == Approx(0.75).epsilon(0).margin(kExact));
  const VectorXd y = theorem1_y(knots({0, 1, 2, 3}), 2);
  CHECK(y(0) == Approx(1).epsilon(0).margin(kExact));
  CHECK(y(1) == Approx(-1).epsilon(0).margin(kExact));
}

TEST_CASE("T3: cubic on (0,1,3,4,7): Taylor table, value at 3.5, vanishing end",
          "[splines][theorem1]") {
  const VectorXd X = knots({0, 1, 3, 4, 7});
  const ExplicitBSpline N = explicit_bspline(X, 3);
  const double D[4][4] = {{0, 0, 0, 1. / 2},
                          {1. / 12, 1. / 4, 1. / 2, -2. / 3},
                          {25. / 36, -1. / 12, -5. / 6, 13. / 12},
                          {3. / 8, -3. / 8, 1. / 4, -1. / 12}};
  for (int j = 0; j < 4; ++j)
    for (int q = 0; q < 4; ++q)
      CHECK(N.taylor(j, q) == Approx(D[j][q]).epsilon(0).margin(kExact));
  CHECK(evaluate(N, 3.5) == Approx(329. / 576).epsilon(0).margin(kExact));
  const VectorXd y = theorem1_y(X, 3);
  CHECK(y(0) == Approx(1. / 2).epsilon(0).margin(kExact));
  CHECK(y(1) == Approx(-5. / 6).epsilon(0).margin(kExact));
  CHECK(y(2) == Approx(1. / 4).epsilon(0).margin(kExact));
  for (int d = 0; d <= 2; ++d) // all derivatives up to n-1 vanish at X_4 (from the left)
    CHECK(evaluate(N, 7.0 - 1e-300, d) == Approx(0).epsilon(0).margin(kExact));
}

TEST_CASE("T4: uniform cubic knot values", "[splines][theorem1]") {
  const VectorXd X = knots({0, 1, 2, 3, 4});
  const ExplicitBSpline N = explicit_bspline(X, 3);
  CHECK(evaluate(N, 1.0) == Approx(1. / 6).epsilon(0).margin(kExact));
  CHECK(evaluate(N, 2.0) == Approx(2. / 3).epsilon(0).margin(kExact));
  CHECK(evaluate(N, 3.0) == Approx(1. / 6).epsilon(0).margin(kExact));
  const VectorXd y = theorem1_y(X, 3);
  CHECK(y(0) == Approx(1).epsilon(0).margin(kExact));
  CHECK(y(1) == Approx(-2).epsilon(0).margin(kExact));
  CHECK(y(2) == Approx(1).epsilon(0).margin(kExact));
}

TEST_CASE("T5: quartic on (0,1/2,2,3,5,6)", "[splines][theorem1]") {
  const VectorXd X = knots({0, 0.5, 2, 3, 5, 6});
  const ExplicitBSpline N = explicit_bspline(X, 4);
  const VectorXd y = theorem1_y(X, 4);
  const double ye[] = {4. / 5, -16. / 11, 172. / 165, -4. / 11};
  for (int k = 0; k < 4; ++k)
    CHECK(y(k) == Approx(ye[k]).epsilon(0).margin(kExact));
  const double ve[] = {1. / 240, 68. / 165, 511. / 990, 1. / 66};
  for (int k = 1; k <= 4; ++k)
    CHECK(evaluate(N, X(k)) == Approx(ve[k - 1]).epsilon(0).margin(kExact));
  CHECK(evaluate(N, 3.0) == Approx(511. / 990).epsilon(0).margin(kExact));
}

TEST_CASE("T6: closed-form y_k equals the linear-solve y* (and the recurrence)",
          "[splines][theorem1]") {
  for (const auto& [X, n] :
       {std::pair{knots({0, 1, 3, 4}), 2}, std::pair{knots({0, 1, 3, 4, 7}), 3},
        std::pair{knots({0, 0.5, 2, 3, 5, 6}), 4}}) {
    const VectorXd a = theorem1_y(X, n), b = theorem1_y_closed_form(X, n),
                   c = theorem1_y_solve(X, n);
    for (int k = 0; k < n; ++k) {
      CHECK(a(k) == Approx(b(k)).epsilon(0).margin(kExact));
      CHECK(c(k) == Approx(b(k)).epsilon(0).margin(kExact));
    }
    // (3): the constructed spline closes its support.
    CHECK(closure_residual(explicit_bspline(X, n), X) < 1e-15);
  }
  // In particular y_1 = n! / prod_{j=2}^{n} (X_j - X_0) (digest §2.1.3).
  const VectorXd X = knots({0, 0.5, 2, 3, 5, 6});
  CHECK(theorem1_y_closed_form(X, 4)(0) == Approx(24.0 / (2 * 3 * 5)).epsilon(0).margin(kExact));
}

TEST_CASE("Explicit B-spline equals the Cox–de Boor definition on random knots, n = 0..7",
          "[splines][theorem1][cox]") {
  std::mt19937 rng(20261121);
  std::uniform_real_distribution<double> gap(0.05, 2.0), unit(0.0, 1.0);
  for (int n = 0; n <= 7; ++n) {
    for (int trial = 0; trial < 40; ++trial) {
      VectorXd X(n + 2);
      X(0) = 10 * unit(rng) - 5;
      for (int i = 1; i < n + 2; ++i)
        // A quarter of the trials repeat knots (multiplicity up to n+1) to cover the
        // generalisation of Theorem 1 to multiple knots.
        X(i) = X(i - 1) + ((trial % 4 == 0 && unit(rng) < 0.4 && i < n + 1) ? 0.0 : gap(rng));
      if (!(X(n + 1) > X(0)))
        continue;
      const ExplicitBSpline N = explicit_bspline(X, n);
      CHECK(closure_residual(N, X) < 1e-12); // (3) holds to round-off
      for (int s = 0; s < 25; ++s) {
        const double x = X(0) - 0.5 + (X(n + 1) - X(0) + 1.0) * unit(rng);
        // Relative to the largest value 1 of a normalised B-spline; knot ratios up to 40 and
        // degree 7 cost a few hundred ulps in the Taylor propagation.
        CHECK(evaluate(N, x) == Approx(cox_single(X, n, x)).epsilon(0).margin(1e-12));
      }
    }
  }
}
