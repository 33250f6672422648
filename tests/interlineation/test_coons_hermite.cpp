// C1 Hermite Coons interlineation: exact values and normal derivatives on every line, C1 across
// cells, the error identity with closed-form 1-D errors, fitted order.
#include "interlin/interlineation/coons_hermite.h"

#include "support/test_fields.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::VectorXd;
using test::Field;
using test::mono;
using test::t13;

namespace {

HermiteTraces hermite_traces_of(const Field& F, const VectorXd& x, const VectorXd& y) {
  HermiteTraces t;
  t.values.x = x;
  t.values.y = y;
  for (Index i = 0; i < x.size(); ++i) {
    t.values.on_x.push_back([F, a = x(i)](double s, int d) { return F(a, s, 0, d); });
    t.dx_on_x.push_back([F, a = x(i)](double s, int d) { return F(a, s, 1, d); });
  }
  for (Index j = 0; j < y.size(); ++j) {
    t.values.on_y.push_back([F, b = y(j)](double s, int d) { return F(s, b, d, 0); });
    t.dy_on_y.push_back([F, b = y(j)](double s, int d) { return F(s, b, d, 1); });
  }
  return t;
}

} // namespace

TEST_CASE("Hermite Coons reproduces values and normal derivatives on every line", "[hermite]") {
  const Field F = [](double x, double y, int dx, int dy) {
    RowVectorXd r(2);
    r << t13(x, y, dx, dy)(0),
        std::pow(0.5, dx) * std::exp(0.5 * x) * std::pow(-1.0, dy) * std::exp(-y);
    return r;
  };
  VectorXd x(4), y(3);
  x << 0, 0.2, 0.7, 1;
  y << -0.5, 0.1, 0.6;
  const HermiteCoons O = coons_hermite(hermite_traces_of(F, x, y));
  CHECK(O.dim == 2);
  double worst = 0, worst_d = 0;
  for (double s : VectorXd::LinSpaced(101, 0, 1)) {
    const double ys = -0.5 + 1.1 * s;
    for (Index i = 0; i < x.size(); ++i) {
      worst = std::max(worst, (evaluate(O, x(i), ys) - F(x(i), ys, 0, 0)).cwiseAbs().maxCoeff());
      worst_d = std::max(worst_d,
                         (evaluate(O, x(i), ys, 1, 0) - F(x(i), ys, 1, 0)).cwiseAbs().maxCoeff());
    }
    for (Index j = 0; j < y.size(); ++j) {
      worst = std::max(worst, (evaluate(O, s, y(j)) - F(s, y(j), 0, 0)).cwiseAbs().maxCoeff());
      worst_d =
          std::max(worst_d, (evaluate(O, s, y(j), 0, 1) - F(s, y(j), 0, 1)).cwiseAbs().maxCoeff());
    }
  }
  CHECK(worst < 1e-14);   // closed-form weights, O(1) values: round-off
  CHECK(worst_d < 1e-13); // derivative weights carry 1/h <= 5
  // C1 across an interior cell boundary (x = 0.2): one-sided first derivatives agree.
  for (double ys : {-0.3, 0.0, 0.45})
    for (auto [dx, dy] : {std::pair{1, 0}, {0, 1}}) {
      const RowVectorXd l = evaluate(O, 0.2 - 1e-10, ys, dx, dy), r = evaluate(O, 0.2, ys, dx, dy);
      CHECK((l - r).norm() < 1e-8);
    }
}

TEST_CASE("Hermite Coons error identity with closed-form 1-D errors", "[hermite]") {
  // For x^a with a <= 3 the cubic Hermite interpolant is exact; for x^4 the error on a cell is
  // (x - x_c)^2 (x - x_{c+1})^2 (f''''/4! = 1). So for f = x^4 y^4 + p(x, y) with p of degree
  // <= 3 in x or in y, f - O f = (x-x_c)^2 (x-x_c1)^2 (y-y_d)^2 (y-y_d1)^2.
  const Field f = [](double x, double y, int dx, int dy) {
    return RowVectorXd::Constant(
        1, mono(x, 4, dx) * mono(y, 4, dy) + 3 * mono(x, 3, dx) * mono(y, 5, dy) -
               2 * mono(x, 5, dx) * mono(y, 2, dy) + mono(y, 1, dy) * (dx == 0));
  };
  VectorXd x(3), y(4);
  x << 0, 0.4, 1.1;
  y << -0.2, 0.3, 0.5, 1.0;
  const HermiteCoons O = coons_hermite(hermite_traces_of(f, x, y));
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(0, 1);
  const auto cell_error = [](const VectorXd& n, double s) {
    Index c = 0;
    while (c + 2 < n.size() && s >= n(c + 1))
      ++c;
    return std::pow(s - n(c), 2) * std::pow(s - n(c + 1), 2);
  };
  for (int k = 0; k < 50; ++k) {
    const double xs = 1.1 * U(rng), ys = -0.2 + 1.2 * U(rng);
    CHECK(f(xs, ys, 0, 0)(0) - evaluate(O, xs, ys)(0) ==
          Approx(cell_error(x, xs) * cell_error(y, ys)).epsilon(0).margin(1e-14));
  }
}

TEST_CASE("Composite Hermite Coons converges like O(h^8) on a smooth function", "[hermite]") {
  // (I - P_x)(I - P_y) with cubic Hermite P: O(h^4) * O(h^4).
  std::vector<double> h, err;
  for (int n : {2, 4, 8}) {
    const VectorXd lines = VectorXd::LinSpaced(n + 1, 0, 1);
    const HermiteCoons O = coons_hermite(hermite_traces_of(t13, lines, lines));
    h.push_back(1.0 / n);
    err.push_back(test::max_error_on_unit_square(O, t13, 61));
  }
  INFO("errors " << err[0] << " " << err[1] << " " << err[2]);
  CHECK(test::fitted_order(h, err) == Approx(8.0).epsilon(0).margin(0.4));
}

TEST_CASE("Hermite Coons rejects incompatible derivative traces and twists", "[hermite]") {
  const VectorXd x = Eigen::Vector2d(0, 1), y = Eigen::Vector2d(0, 1);
  HermiteTraces t = hermite_traces_of(t13, x, y);
  t.dx_on_x[1] = [](double s, int d) {
    RowVectorXd r = t13(1, s, 1, d);
    r(0) += 1e-3;
    return r;
  };
  CHECK_THROWS_WITH(coons_hermite(t), Catch::Contains("f_x at crossing (1, 0)"));
  HermiteTraces w = hermite_traces_of(t13, x, y);
  w.twists = MatrixXd::Zero(4, 1);
  CHECK_THROWS_WITH(coons_hermite(w), Catch::Contains("twist"));
  w.twists.resize(4, 1);
  for (Index j = 0; j < 2; ++j)
    for (Index i = 0; i < 2; ++i)
      w.twists(i + 2 * j, 0) = t13(x(i), y(j), 1, 1)(0);
  CHECK_NOTHROW(coons_hermite(w));
}
