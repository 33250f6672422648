// seed 001, Theorem 2: digest 001 test cases T7–T10 for the minimal-jump quadratic spline.
#include "interlin/splines/min_jump_quadratic.h"

#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::VectorXd;

namespace {

VectorXd vec(std::initializer_list<double> v) {
  VectorXd x(static_cast<Index>(v.size()));
  Index i = 0;
  for (double d : v)
    x(i++) = d;
  return x;
}

VectorXd one(double t) {
  return VectorXd::Constant(1, t);
}

// The digest's nonuniform T7/T8 grid.
VectorXd t7_grid() {
  return vec({0, 0.3, 0.5, 1, 1.2, 1.7, 2});
}

// Max |S - f| over n equally spaced samples of [a, b] (the digest's T10 measure, 4001 samples).
template <class F>
double max_error(const MinJumpQuadratic& S, F f, double a, double b, int n) {
  const VectorXd t = VectorXd::LinSpaced(n, a, b);
  const VectorXd s = evaluate(S, t);
  double e = 0;
  for (Index k = 0; k < t.size(); ++k)
    e = std::max(e, std::abs(s(k) - f(t(k))));
  return e;
}

} // namespace

TEST_CASE("T7: Theorem 2 spline is exact on quadratics (M = 6, J = 0)", "[splines][theorem2]") {
  const VectorXd x = t7_grid();
  const VectorXd y = (3 * x.array().square() - 2 * x.array() + 1).matrix();
  const MinJumpQuadratic S = min_jump_quadratic(x, y);
  // Values of order 10 from a closed form and one short recurrence: a few ulps.
  for (Index i = 0; i < S.M.size(); ++i)
    CHECK(S.M(i) == Approx(6.0).epsilon(0).margin(1e-12));
  CHECK(jump_functional(S) < 1e-22);
  const VectorXd t = VectorXd::LinSpaced(201, 0, 2);
  const VectorXd s = evaluate(S, t);
  for (Index k = 0; k < t.size(); ++k)
    CHECK(s(k) == Approx(3 * t(k) * t(k) - 2 * t(k) + 1).epsilon(0).margin(1e-13));
}

TEST_CASE("T8: Theorem 2 on x^3, nonuniform grid, exact rationals", "[splines][theorem2]") {
  const VectorXd x = t7_grid();
  const VectorXd y = x.array().cube().matrix();
  const MinJumpQuadratic S = min_jump_quadratic(x, y);
  const double M[] = {11433. / 5510,  9781. / 11020,   129071. / 27550,
                      79207. / 11020, 221639. / 27550, 14023. / 1102};
  // Exact rationals; values up to 13, so 1e-13 absolute is a few ulps of the recurrence.
  for (Index i = 0; i < 6; ++i)
    CHECK(S.M(i) == Approx(M[i]).epsilon(0).margin(1e-13));
  CHECK(jump_functional(S) == Approx(61617469. / 1377500).epsilon(0).margin(1e-12));
  CHECK(evaluate(S, one(0.75))(0) == Approx(366829. / 881600).epsilon(0).margin(1e-14));
  CHECK(evaluate(S, one(1.5))(0) == Approx(1170066. / 344375).epsilon(0).margin(1e-14));
  // [MINE] regression value of the digest, 6 printed digits.
  CHECK(max_error(
            S, [](double t) { return t * t * t; }, 0, 2, 4001) == Approx(0.022899).epsilon(0).margin(1e-6));
  // C^1: one-sided derivatives agree at the interior nodes (each side from its own piece).
  for (Index i = 1; i + 1 < x.size(); ++i) {
    const double h0 = x(i) - x(i - 1), h1 = x(i + 1) - x(i);
    const double left = (y(i) - y(i - 1)) / h0 + 0.5 * S.M(i - 1) * h0;
    const double right = (y(i + 1) - y(i)) / h1 - 0.5 * S.M(i) * h1;
    CHECK(left == Approx(right).epsilon(0).margin(1e-13));
  }
  // Minimality: J is quadratic in M_{1,2}; moving it by +-0.01 raises J by the digest's 0.002204.
  for (double dm : {-0.01, 0.01}) {
    MinJumpQuadratic P = S;
    P.M = theorem2_recurrence(x, y, S.M(0) + dm);
    CHECK(jump_functional(P) - jump_functional(S) == Approx(0.002204).epsilon(0).margin(5e-7));
  }
}

TEST_CASE("T9: Theorem 2 on x^3 at integer nodes (hand-checkable)", "[splines][theorem2]") {
  const VectorXd x = vec({0, 1, 2, 3, 4});
  const VectorXd y = x.array().cube().matrix();
  const MinJumpQuadratic S = min_jump_quadratic(x, y);
  const double M[] = {4, 8, 16, 20};
  for (Index i = 0; i < 4; ++i)
    CHECK(S.M(i) == Approx(M[i]).epsilon(0).margin(1e-13));
  CHECK(jump_functional(S) == Approx(96).epsilon(0).margin(1e-12));
  CHECK(evaluate(S, one(0.5))(0) == Approx(0).epsilon(0).margin(1e-14));
  CHECK(evaluate(S, one(2.5))(0) == Approx(15.5).epsilon(0).margin(1e-13));
}

TEST_CASE("Theorem 2: recurrence, explicit form and brute-force minimum agree",
          "[splines][theorem2]") {
  VectorXd x(9), y(9);
  for (Index i = 0; i < 9; ++i) {
    x(i) = i + 0.37 * std::sin(3.0 * i); // nonuniform, still increasing
    y(i) = std::exp(0.3 * x(i)) * std::cos(x(i));
  }
  const double m12 = theorem2_m12(x, y);
  const VectorXd a = theorem2_recurrence(x, y, m12), b = theorem2_explicit(x, y, m12);
  for (Index i = 0; i < a.size(); ++i)
    CHECK(a(i) == Approx(b(i)).epsilon(0).margin(1e-11 * std::max(1.0, std::abs(b(i)))));
  // J(m) is a parabola in m: its vertex from three samples is the closed-form minimiser.
  const auto J = [&](double m) {
    MinJumpQuadratic S{x, y, theorem2_recurrence(x, y, m)};
    return jump_functional(S);
  };
  const double d = 0.5, jm = J(m12 - d), j0 = J(m12), jp = J(m12 + d);
  const double vertex = m12 - d * (jp - jm) / (2 * (jp - 2 * j0 + jm));
  CHECK(vertex == Approx(m12).epsilon(0).margin(1e-9 * std::max(1.0, std::abs(m12))));
  // Two nodes: no jump to minimise, the chord.
  const MinJumpQuadratic L = min_jump_quadratic(vec({0, 2}), vec({1, 5}));
  CHECK(L.M(0) == 0.0);
  CHECK(evaluate(L, one(0.5))(0) == Approx(2.0).epsilon(0).margin(1e-15));
}

TEST_CASE("T10: Theorem 2 converges like O(h^3) on uniform and nonuniform grids",
          "[splines][theorem2][convergence]") {
  // The digest's table ([MINE] regression values, 7 significant digits printed).
  const int Ns[] = {5, 9, 17, 33, 65, 129};
  const double uniform[] = {4.459644e-03, 5.023880e-04, 6.121664e-05,
                            7.601912e-06, 9.487584e-07, 1.185072e-07};
  const double nonuniform[] = {1.059951e-02, 1.140266e-03, 1.360967e-04,
                               1.678131e-05, 2.088784e-06, 2.602844e-07};
  std::vector<double> h, eu, en;
  for (int r = 0; r < 6; ++r) {
    const int N = Ns[r];
    VectorXd xu(N), xn(N);
    for (int i = 0; i < N; ++i) {
      const double s = double(i) / (N - 1);
      xu(i) = M_PI * s;
      xn(i) = M_PI * (s + 0.3 * s * (1 - s));
    }
    const auto f = [](double t) { return std::sin(t); };
    const double e1 =
        max_error(min_jump_quadratic(xu, xu.array().sin().matrix()), f, 0, M_PI, 4001);
    const double e2 =
        max_error(min_jump_quadratic(xn, xn.array().sin().matrix()), f, 0, M_PI, 4001);
    CHECK(e1 == Approx(uniform[r]).epsilon(2e-6));
    CHECK(e2 == Approx(nonuniform[r]).epsilon(2e-6));
    h.push_back(1.0 / (N - 1));
    eu.push_back(e1);
    en.push_back(e2);
  }
  const double pu = test::fitted_order(h, eu), pn = test::fitted_order(h, en);
  INFO("fitted orders: uniform " << pu << ", nonuniform " << pn);
  // Theorem 2 interpolates with a quadratic spline: third order in the max norm.
  CHECK(pu == Approx(3.0).epsilon(0).margin(0.1));
  CHECK(pn == Approx(3.0).epsilon(0).margin(0.1));
}

TEST_CASE("Theorem 2 rejects bad nodes", "[splines][theorem2]") {
  CHECK_THROWS_WITH(min_jump_quadratic(vec({0}), vec({1})), Catch::Contains("at least 2"));
  CHECK_THROWS_WITH(min_jump_quadratic(vec({0, 1, 1}), vec({1, 2, 3})),
                    Catch::Contains("increase strictly"));
  CHECK_THROWS_WITH(min_jump_quadratic(vec({0, 1}), vec({1, NAN})), Catch::Contains("finite"));
  CHECK_THROWS_WITH(min_jump_quadratic(vec({0, 1}), vec({1, 2, 3})), Catch::Contains("values"));
}
