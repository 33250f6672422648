// seed 001, Theorem 1 in full: every derivative of the explicit B-spline against the Cox–de Boor
// derivative recursion, and the seed's solve of (3) against the closed-form y_k, n = 1..7.
#include "interlin/splines/explicit_bspline.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>

using namespace interlin;
using Eigen::VectorXd;

namespace {

// d-th derivative of N_{i,p}(x; t) by the Cox–de Boor definition and its derivative formula
//   N'_{i,p} = p [N_{i,p-1} / (t_{i+p} - t_i) - N_{i+1,p-1} / (t_{i+p+1} - t_{i+1})],
// independent of the explicit construction (half-open spans [t_i, t_{i+1})).
double cox_derivative(const VectorXd& t, int i, int p, int d, double x) {
  if (d == 0) {
    if (p == 0)
      return (t(i) <= x && x < t(i + 1)) ? 1.0 : 0.0;
    double r = 0;
    if (t(i + p) > t(i))
      r += (x - t(i)) / (t(i + p) - t(i)) * cox_derivative(t, i, p - 1, 0, x);
    if (t(i + p + 1) > t(i + 1))
      r += (t(i + p + 1) - x) / (t(i + p + 1) - t(i + 1)) * cox_derivative(t, i + 1, p - 1, 0, x);
    return r;
  }
  if (p == 0)
    return 0.0;
  double r = 0;
  if (t(i + p) > t(i))
    r += p * cox_derivative(t, i, p - 1, d - 1, x) / (t(i + p) - t(i));
  if (t(i + p + 1) > t(i + 1))
    r -= p * cox_derivative(t, i + 1, p - 1, d - 1, x) / (t(i + p + 1) - t(i + 1));
  return r;
}

} // namespace

TEST_CASE("Theorem 1: all derivatives equal the Cox–de Boor derivatives, random knots n = 1..7",
          "[splines][theorem1][cox]") {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> gap(0.1, 2.0), unit(0.0, 1.0);
  for (int n = 1; n <= 7; ++n) {
    for (int trial = 0; trial < 30; ++trial) {
      VectorXd X(n + 2);
      X(0) = 4 * unit(rng) - 2;
      for (int i = 1; i < n + 2; ++i)
        X(i) = X(i - 1) + gap(rng);
      const ExplicitBSpline N = explicit_bspline(X, n);
      for (int s = 0; s < 20; ++s) {
        const double x = X(0) + (X(n + 1) - X(0)) * unit(rng);
        for (int d = 0; d <= n; ++d) {
          const double ref = cox_derivative(X, 0, n, d, x);
          // Derivative d scales like (1/h)^d with h >= 0.1: compare relative to the size of the
          // d-th derivative over the support, which the Taylor table bounds.
          const double scale = std::max(1.0, N.taylor.col(d).cwiseAbs().maxCoeff());
          CHECK(evaluate(N, x, d) == Approx(ref).epsilon(0).margin(1e-11 * scale));
        }
      }
      // Outside the support every derivative is exactly 0.
      for (int d = 0; d <= n; ++d) {
        CHECK(evaluate(N, X(0) - 0.25, d) == 0.0);
        CHECK(evaluate(N, X(n + 1) + 0.25, d) == 0.0);
      }
    }
  }
}

TEST_CASE("Theorem 1: the seed's solve of (3), the closed form and the recurrence agree, n = 1..7",
          "[splines][theorem1]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> gap(0.3, 1.5);
  for (int n = 1; n <= 7; ++n) {
    for (int trial = 0; trial < 20; ++trial) {
      VectorXd X(n + 2);
      X(0) = 0;
      for (int i = 1; i < n + 2; ++i)
        X(i) = X(i - 1) + gap(rng);
      const VectorXd a = theorem1_y(X, n), b = theorem1_y_closed_form(X, n),
                     c = theorem1_y_solve(X, n);
      // Span ratio <= 5: docs/formulas.md measures errors below 1e-12 relative in this range.
      const double scale = a.cwiseAbs().maxCoeff();
      for (int k = 0; k < n; ++k) {
        CHECK(b(k) == Approx(a(k)).epsilon(0).margin(1e-12 * scale));
        CHECK(c(k) == Approx(a(k)).epsilon(0).margin(1e-12 * scale));
      }
      // y_k are the knot values of the piecewise-linear (n-1)-th derivative, (1).
      const ExplicitBSpline N = explicit_bspline(X, n);
      for (int k = 1; k <= n; ++k)
        CHECK(evaluate(N, X(k), n - 1) == Approx(a(k - 1)).epsilon(0).margin(1e-12 * scale));
    }
  }
}
