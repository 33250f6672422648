// R-operations against the values of digest 000 §8 (T1-T8b, T12) and digest 002 §12.1, and
// against the identities of seed 000 §2.3.
#include "rf_eval.h"
#include "support/test_support.h"

#include "interlin/interflatation/rfunctions/r_operations.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace interlin;
using namespace interlin::rf;
using test::value_at;

namespace {

const Expr X = Expr::x(), Y = Expr::y(), Z = Expr::z();

// The digests print 7 decimals: agreement to half a unit in the last place.
constexpr double kPrinted = 5e-8;

} // namespace

TEST_CASE("R0 conjunction and disjunction: digest 000 T1 and digest 002 §12.1", "[rf][r0]") {
  const Expr a = and0(X, Y), o = or0(X, Y);
  CHECK(value_at(a, 3, 4) == Approx(2).epsilon(0).margin(1e-15)); // T1
  CHECK(value_at(o, 3, 4) == Approx(12).epsilon(0).margin(1e-15));
  // digest 002 §12.1 (closed forms)
  CHECK(value_at(a, 1, 1) == Approx(2 - std::sqrt(2.0)).epsilon(0).margin(1e-15));
  CHECK(value_at(a, 1, -1) == Approx(-std::sqrt(2.0)).epsilon(0).margin(1e-15));
  CHECK(value_at(a, -1, -1) == Approx(-2 - std::sqrt(2.0)).epsilon(0).margin(1e-15));
  CHECK(value_at(o, 1, 1) == Approx(2 + std::sqrt(2.0)).epsilon(0).margin(1e-15));
  CHECK(value_at(o, 1, -1) == Approx(std::sqrt(2.0)).epsilon(0).margin(1e-15));
  CHECK(value_at(o, -1, -1) == Approx(-2 + std::sqrt(2.0)).epsilon(0).margin(1e-15));
  // a ^0 0 = min(0, 2a), a v0 0 = max(0, 2a): exact in floating point
  CHECK(value_at(a, 2, 0) == 0.0);
  CHECK(value_at(a, -2, 0) == -4.0);
  CHECK(value_at(o, 2, 0) == 4.0);
  CHECK(value_at(o, -2, 0) == 0.0);
}

TEST_CASE("R0: sign rule, De Morgan, homogeneity on random operands", "[rf][r0]") {
  const ImplicitFunction a = test::compiled(and0(X, Y)), o = test::compiled(or0(X, Y));
  const ImplicitFunction nd = test::compiled(-and0(-X, -Y));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-10, 10);
  for (int i = 0; i < 1000; ++i) {
    const double x = u(rng), y = u(rng), t = std::abs(u(rng)) + 0.1;
    const double va = value_at(a, x, y), vo = value_at(o, x, y);
    CHECK((va > 0) == (x > 0 && y > 0)); // the Boolean function of the operation
    CHECK((vo > 0) == (x > 0 || y > 0));
    CHECK(value_at(nd, x, y) == Approx(vo).epsilon(0).margin(1e-12 * (1 + std::abs(vo)))); // De Morgan
    CHECK(value_at(a, t * x, t * y) == Approx(t * va).epsilon(0).margin(1e-12 * t * (1 + std::abs(va))));
  }
}

TEST_CASE("R0 with infinite and undefined operands gives the limits", "[rf][r0]") {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double big = std::numeric_limits<double>::max();
  // a ^0 +inf = a, a ^0 -inf = -inf (clamped to -DBL_MAX), a v0 -inf = a, a v0 +inf = +inf
  CHECK(value_at(and0(X, Y), 1.5, inf) == 1.5);
  CHECK(value_at(and0(X, Y), 1.5, -inf) == -big);
  CHECK(value_at(or0(X, Y), 1.5, -inf) == 1.5);
  CHECK(value_at(or0(X, Y), 1.5, inf) == big);
  // an undefined operand is an empty set: neutral in a union, absorbing in an intersection
  CHECK(value_at(or0(X, Y / Z), 1.5, 0, 0) == 1.5); // 0/0
  CHECK(value_at(and0(X, Y / Z), 1.5, 0, 0) == -big);
  CHECK(value_at(or0(X, Y), 2.5, nan) == 2.5);
  // overflowing squares: scaled, 1e200 * R0(3, 4) = 2e200
  CHECK(value_at(and0(X, Y), 3e200, 4e200) == Approx(2e200).epsilon(1e-15));
}

TEST_CASE("R-alpha, R1, R0^m, Rp: digest 000 T2-T5", "[rf][ralpha]") {
  CHECK(value_at(and_alpha(X, Y, 0.5), 3, 4) == Approx(2.2629658).epsilon(0).margin(kPrinted)); // T2
  CHECK(value_at(or_alpha(X, Y, 0.5), 3, 4) == Approx(7.0703675).epsilon(0).margin(kPrinted));
  CHECK(value_at(and1(X, Y), 3, 4) == 3.0); // T3
  CHECK(value_at(or1(X, Y), 3, 4) == 4.0);
  CHECK(value_at(and0m(X, Y, 2), 3, 4) == Approx(50).epsilon(0).margin(1e-12));                 // T4
  CHECK(value_at(andp(X, Y, 3), 3, 4) == Approx(7 - std::cbrt(91.0)).epsilon(0).margin(1e-14)); // T5
  CHECK(value_at(andp(X, Y, 3), 3, 4) == Approx(2.5020586).epsilon(0).margin(kPrinted));
  // alpha = 0 is R0, alpha = 1 is R1 (seed 000 §2.2); p = 2 is R0
  CHECK(value_at(and_alpha(X, Y, 0.0), 3, 4) == Approx(2).epsilon(0).margin(1e-14));
  CHECK(value_at(and_alpha(X, Y, 1.0), 3, 4) == Approx(3).epsilon(0).margin(1e-14));
  CHECK(value_at(or_alpha(X, Y, 1.0), -3, 4) == Approx(4).epsilon(0).margin(1e-14));
  CHECK(value_at(andp(X, Y, 2), 3, 4) == Approx(2).epsilon(0).margin(1e-14));
  CHECK_THROWS_AS(and_alpha(X, Y, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(andp(X, Y, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(and0m(X, Y, -1.0), std::invalid_argument);
}

TEST_CASE("R-alpha: properties 6-9 of seed 000 §2.3 for random operands and alpha (T7, T8)",
          "[rf][ralpha]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-5, 5), ua(-0.99, 1.0);
  for (int i = 0; i < 200; ++i) {
    const double al = ua(rng);
    const ImplicitFunction a = test::compiled(and_alpha(X, Y, al));
    const ImplicitFunction o = test::compiled(or_alpha(X, Y, al));
    const double x = u(rng), y = u(rng);
    const double va = value_at(a, x, y), vo = value_at(o, x, y);
    const double tol = 1e-12 * (1 + std::abs(x) + std::abs(y)) / (1 + al); // round-off of (2.2)
    CHECK(va + vo == Approx(2 / (1 + al) * (x + y)).epsilon(0).margin(tol));          // property 6
    CHECK(va * vo == Approx(2 / (1 + al) * x * y).epsilon(0).margin(10 * tol * (1 + std::abs(x * y)))); // 7
    CHECK(value_at(a, 0, std::abs(y)) == Approx(0).epsilon(0).margin(tol));  // property 8
    CHECK(value_at(a, x, y) <= std::min(x, y) + tol);             // bounded by R1
    CHECK(value_at(o, 0, -std::abs(y)) == Approx(0).epsilon(0).margin(tol)); // property 9
    CHECK(value_at(o, x, y) >= std::max(x, y) - tol);
  }
}

TEST_CASE("R-rho fillet: digest 000 T6", "[rf][fillet]") {
  const Expr a = and_fillet(X, Y, 1.0), o = or_fillet(X, Y, 1.0);
  CHECK(value_at(a, 0.5, 0.5) == Approx(0.25).epsilon(0).margin(1e-15));
  CHECK(value_at(o, -0.5, -0.5) == Approx(-0.25).epsilon(0).margin(1e-15));
  CHECK(value_at(a, 0.3, 0.6) == Approx(0.175).epsilon(0).margin(1e-15));
  CHECK(value_at(a, 0.1, 0.1) == Approx(-0.31).epsilon(0).margin(1e-15));
  CHECK(value_at(a, 3, 4) == Approx(2.0).epsilon(0).margin(1e-15)); // r >= rho: R0
  // inside the corner the fillet is the normalised circle of radius rho centred at (rho, rho)
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 0.7);
  for (int i = 0; i < 100; ++i) {
    const double x = u(rng), y = u(rng);
    const double circle = (1 - (x - 1) * (x - 1) - (y - 1) * (y - 1)) / 2;
    CHECK(value_at(a, x, y) == Approx(circle).epsilon(0).margin(1e-14));
  }
}

TEST_CASE("Equivalence: x~y = xy and the associative eps family (T8b)", "[rf][equiv]") {
  CHECK(value_at(equiv(X, Y), 3, -4) == -12.0);
  const Expr left = equiv_eps(equiv_eps(X, Y, 0.3, 2), Z, 0.3, 2);
  const Expr right = equiv_eps(X, equiv_eps(Y, Z, 0.3, 2), 0.3, 2);
  CHECK(value_at(left, 0.7, -1.3, 2.1) == Approx(-0.6660803).epsilon(0).margin(kPrinted));
  CHECK(value_at(right, 0.7, -1.3, 2.1) == Approx(-0.6660803).epsilon(0).margin(kPrinted));
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3, 3);
  const ImplicitFunction l = test::compiled(left), r = test::compiled(right);
  for (int i = 0; i < 100; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng);
    CHECK(value_at(l, x, y, z) == Approx(value_at(r, x, y, z)).epsilon(0).margin(1e-13));
  }
}

TEST_CASE("Normalised junction: d/dy of S1 ^alpha S2 at the corner (digest 000 T12)",
          "[rf][ralpha]") {
  // S1 = (y - x^3)/sqrt(1 + 9x^4) (above the cubic, normalised), S2 = y; both vanish at (0,0)
  const Expr s1 = (Y - X * X * X) / sqrt(1 + 9 * X * X * X * X), s2 = Y;
  // For constant alpha the operation is 1-homogeneous, so along the ray x = 0 the one-sided
  // derivative is exactly w(0, h) / h.
  const double h = 1e-4;
  CHECK(value_at(and_alpha(s1, s2, 0.0), 0, h) / h == Approx(2 - std::sqrt(2.0)).epsilon(0).margin(1e-12));
  CHECK(value_at(and_alpha(s1, s2, 0.5), 0, h) / h == Approx(0.6666667).epsilon(0).margin(kPrinted));
  // variable alpha (2.32): alpha = 1 - O(h^2) near the corner, and w(0,h)/h = 1 - O(h): the
  // one-sided derivative at the corner is 1; fitted order of the error about 1
  const ImplicitFunction wv = test::compiled(and_alpha_variable(s1, s2));
  std::vector<double> hs, errs;
  for (double t : {1e-2, 1e-3, 1e-4, 1e-5}) {
    hs.push_back(t);
    errs.push_back(1 - value_at(wv, 0, t) / t);
  }
  CHECK(errs.back() < 2e-5);
  CHECK(test::fitted_order(hs, errs) == Approx(1).epsilon(0).margin(0.05));
}

TEST_CASE("Derivative theorem (seed 000 §2.3): R-operations keep the operand's normal derivative",
          "[rf][r0]") {
  // On a1 = 0 with a2 > 0 the gradient of a1 ^ a2 is the gradient of a1, for R0, R-alpha, Rp
  // and the fillet beyond rho; likewise for v with a2 < 0.
  const Expr a1 = X - 0.3 * Y, a2 = 2 - Y * Y;
  for (const Expr& e : {and0(a1, a2), and_alpha(a1, a2, 0.4), andp(a1, a2, 3.0),
                        and_fillet(a1, a2, 0.5), or0(a1, -a2)}) {
    const Eigen::Vector3d g = test::gradient_at(e, 0.3 * 0.7, 0.7); // a1 = 0, a2 = 1.51
    CHECK(g.x() == Approx(1).epsilon(0).margin(1e-12));
    CHECK(g.y() == Approx(-0.3).epsilon(0).margin(1e-12));
    CHECK(g.z() == Approx(0).epsilon(0).margin(1e-12));
  }
}
