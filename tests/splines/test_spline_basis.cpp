// The per-span explicit basis of a whole knot vector against Cox–de Boor (values and derivatives),
// partition of unity and continuity at the knots.
#include "interlin/splines/cox_de_boor.h"
#include "interlin/splines/knots.h"
#include "interlin/splines/spline_basis.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Random clamped or unclamped knot vector with occasional interior multiplicities.
VectorXd random_knots(std::mt19937& rng, int p, Index num_ctrl, bool clamped) {
  std::uniform_real_distribution<double> gap(0.1, 3.0), unit(0, 1);
  VectorXd t(num_ctrl + p + 1);
  t(0) = -1;
  for (Index i = 1; i < t.size(); ++i) {
    const bool end_clamp = clamped && (i <= p || i > num_ctrl);
    const bool repeat = !end_clamp && p > 1 && unit(rng) < 0.15 && i > p + 1 && t(i - 1) > t(i - 2);
    t(i) = t(i - 1) + ((end_clamp || repeat) ? 0.0 : gap(rng));
  }
  return t;
}

} // namespace

TEST_CASE("Explicit basis equals Cox–de Boor values and derivatives, degrees 1..7",
          "[splines][basis][cox]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int p = 1; p <= 7; ++p) {
    for (int trial = 0; trial < 6; ++trial) {
      const Index n = p + 1 + 3 * trial;
      const VectorXd t = random_knots(rng, p, n, trial % 2 == 0);
      const SplineBasis B = explicit_basis(t, p);
      for (int s = 0; s < 60; ++s) {
        const double u = t(p) + (t(n) - t(p)) * unit(rng);
        Index k1, k2;
        const MatrixXd E = basis_derivatives(B, u, p, &k1);
        const MatrixXd C = cox_de_boor_derivatives(t, p, n, u, p, &k2);
        REQUIRE(k1 == k2);
        for (int d = 0; d <= p; ++d) {
          // Derivatives scale like (1/h)^d; compare relative to the largest entry of the row.
          const double scale = std::max(1.0, C.row(d).cwiseAbs().maxCoeff());
          for (int r = 0; r <= p; ++r)
            CHECK(E(d, r) == Approx(C(d, r)).epsilon(0).margin(1e-11 * scale));
        }
      }
    }
  }
}

TEST_CASE("Partition of unity and non-negativity on the domain", "[splines][basis]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int p = 1; p <= 6; ++p) {
    const Index n = 4 * p;
    const VectorXd t = random_knots(rng, p, n, true);
    const SplineBasis B = explicit_basis(t, p);
    for (int s = 0; s <= 200; ++s) {
      const double u = t(p) + (t(n) - t(p)) * s / 200.0;
      const MatrixXd N = basis_derivatives(B, u, 1, nullptr);
      CHECK(N.row(0).sum() == Approx(1.0).epsilon(0).margin(1e-13)); // a sum of p+1 numbers <= 1
      CHECK(N.row(1).sum() == Approx(0.0).epsilon(0).margin(1e-11)); // derivative of the constant 1
      CHECK(N.row(0).minCoeff() >= -1e-13); // non-negative up to round-off of values <= 1
    }
  }
}

// d-th derivative of basis row r of span k's polynomial at local coordinate h (used to take
// exact one-sided limits at the right end of a span).
double span_derivative(const SplineBasis& B, Index k, int r, int d, double h) {
  const int p = B.degree;
  double v = 0;
  for (int q = p; q >= d; --q) {
    double falling = 1;
    for (int m = 0; m < d; ++m)
      falling *= q - m;
    v = v * h + B.coeffs((k - p) * (p + 1) + r, q) * falling;
  }
  return v;
}

TEST_CASE("Continuity at knots: derivatives of order <= p - multiplicity do not jump",
          "[splines][basis]") {
  for (int p : {3, 5}) {
    const std::vector<double> inner = {0.7, 1.3, 1.3, 2.0, 2.9, 2.9, 2.9, 3.4};
    const Index n = static_cast<Index>(inner.size()) + p + 1;
    VectorXd t(n + p + 1);
    t.head(p + 1).setZero();
    for (size_t i = 0; i < inner.size(); ++i)
      t(p + 1 + static_cast<Index>(i)) = inner[i];
    t.tail(p + 1).setConstant(4.0);
    const SplineBasis B = explicit_basis(t, p);
    for (double knot : {0.7, 1.3, 2.0, 2.9, 3.4}) {
      const int m = static_cast<int>(std::count(inner.begin(), inner.end(), knot));
      const Index kr = find_span(t, p, n, knot); // span starting at the knot
      Index kl = kr - 1;                         // last non-empty span ending at it
      while (!(t(kl) < t(kl + 1)))
        --kl;
      const double h = knot - t(kl);
      double max_jump[8] = {0};
      for (Index i = 0; i < n; ++i) { // every basis function
        for (int d = 0; d <= p; ++d) {
          const double left =
              (i >= kl - p && i <= kl) ? span_derivative(B, kl, int(i - (kl - p)), d, h) : 0.0;
          const double right =
              (i >= kr - p && i <= kr) ? span_derivative(B, kr, int(i - (kr - p)), d, 0.0) : 0.0;
          max_jump[d] = std::max(max_jump[d], std::abs(left - right));
        }
      }
      // C^{p-m}: jumps are round-off (derivatives here are O(1..100), so 1e-10 absolute) ...
      for (int d = 0; d <= p - m; ++d)
        CHECK(max_jump[d] < 1e-10);
      // ... and the derivative of order p-m+1 genuinely jumps.
      CHECK(max_jump[p - m + 1] > 1e-3);
    }
  }
}

TEST_CASE("Bad knot vectors are rejected with a clear error", "[splines][basis]") {
  VectorXd t(8);
  t << 0, 0, 0, 0, 2, 1, 1, 1; // decreasing
  CHECK_THROWS_WITH(explicit_basis(t, 3), Catch::Contains("non-decreasing"));
  t << 0, 0, 0, 0, 1, 1, 1, std::nan("");
  CHECK_THROWS_WITH(explicit_basis(t, 3), Catch::Contains("finite"));
  VectorXd s(4);
  s << 0, 0, 1, 1;
  CHECK_THROWS_WITH(explicit_basis(s, 3), Catch::Contains("control points"));
}
