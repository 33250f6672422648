// Gordon / Coons interlineation on line grids: exact traces, digest 001 T11-T13, Theorem 3,
// and the error identity f - O f = (I - P_x)(I - P_y) f.
#include "interlin/interlineation/gordon_surface.h"
#include "interlin/interlineation/shape_diagnostics.h"
#include "interlin/splines/interpolate_curve.h"

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

namespace {

LineTraces traces_of(const Field& F, const VectorXd& x, const VectorXd& y) {
  LineTraces t;
  t.x = x;
  t.y = y;
  for (Index i = 0; i < x.size(); ++i)
    t.on_x.push_back([F, xi = x(i)](double s, int d) { return F(xi, s, 0, d); });
  for (Index j = 0; j < y.size(); ++j)
    t.on_y.push_back([F, yj = y(j)](double s, int d) { return F(s, yj, d, 0); });
  return t;
}

RowVectorXd scalar(double v) {
  return RowVectorXd::Constant(1, v);
}

// T11 function: f = e^x sin 2y + x y^2 (with derivatives up to order 2 in each variable).
RowVectorXd t11(double x, double y, int dx, int dy) {
  const double ex = std::exp(x);
  const double s = dy == 0 ? std::sin(2 * y) : dy == 1 ? 2 * std::cos(2 * y) : -4 * std::sin(2 * y);
  const double y2 = dy == 0 ? y * y : dy == 1 ? 2 * y : 2;
  const double xv = dx == 0 ? x : dx == 1 ? 1 : 0;
  return scalar(ex * s + xv * y2);
}

} // namespace

TEST_CASE("T11: bilinear Coons reproduces the four sides, interior value", "[gordon][T11]") {
  const VectorXd x = Eigen::Vector2d(0.2, 1.1), y = Eigen::Vector2d(-0.3, 0.7);
  const GordonSurface O = coons_bilinear(traces_of(t11, x, y));
  double side = 0;
  for (double s : VectorXd::LinSpaced(101, 0, 1)) {
    const double xs = 0.2 + 0.9 * s, ys = -0.3 + s;
    for (int i = 0; i < 2; ++i) {
      side = std::max(side, std::abs(evaluate(O, x(i), ys)(0) - t11(x(i), ys, 0, 0)(0)));
      side = std::max(side, std::abs(evaluate(O, xs, y(i))(0) - t11(xs, y(i), 0, 0)(0)));
    }
  }
  INFO("max deviation on the sides " << side);
  // The digest reports <= 4.4e-16 = 1 ulp of the largest side value (~3.5) for the direct
  // formula; our linear weights come from the explicit B-spline basis (a few more roundings).
  CHECK(side <= 4 * 4.4e-16);
  // digest T11 value (16 digits, computed by the digest's author): a few ulps of 0.8.
  CHECK(evaluate(O, 0.65, 0.2)(0) == Approx(0.8072562341083098).epsilon(1e-15));
  CHECK(t11(0.65, 0.2, 0, 0)(0) == Approx(0.7719467342591296).epsilon(1e-15));

  // f = x^2 y^2 on [0,1]^2: O = x y^2 + x^2 y - x y, f - O = x y (1-x)(1-y) (closed forms).
  const Field f2 = [](double a, double b, int da, int db) {
    return scalar(mono(a, 2, da) * mono(b, 2, db));
  };
  const GordonSurface O2 =
      coons_bilinear(traces_of(f2, Eigen::Vector2d(0, 1), Eigen::Vector2d(0, 1)));
  CHECK(std::abs(evaluate(O2, 0.5, 0.5)(0)) < 1e-16);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 50; ++k) {
    const double a = U(rng), b = U(rng);
    CHECK(evaluate(O2, a, b)(0) == Approx(a * b * b + a * a * b - a * b).epsilon(0).margin(1e-15));
    CHECK(f2(a, b, 0, 0)(0) - evaluate(O2, a, b)(0) ==
          Approx(a * b * (1 - a) * (1 - b)).epsilon(0).margin(1e-15));
  }
}

TEST_CASE("T12: Theorem 3 second derivatives of the Coons patch", "[gordon][T12][theorem3]") {
  // f = e^x + y^2 + x^2 y^2 on [0,1]^2: O_xx = e^x + 2y, O_yy = 2 + 2x (closed forms).
  const Field f = [](double x, double y, int dx, int dy) {
    return scalar((dy == 0 ? std::exp(x) : 0.0) + (dx == 0 ? mono(y, 2, dy) : 0.0) +
                  mono(x, 2, dx) * mono(y, 2, dy));
  };
  const GordonSurface O =
      coons_bilinear(traces_of(f, Eigen::Vector2d(0, 1), Eigen::Vector2d(0, 1)));
  for (double x : {0.0, 0.3, 0.5, 0.9, 1.0})
    for (double y : {0.0, 0.1, 0.6, 1.0}) {
      CHECK(evaluate(O, x, y, 2, 0)(0) == Approx(std::exp(x) + 2 * y).epsilon(1e-13));
      CHECK(evaluate(O, x, y, 0, 2)(0) == Approx(2 + 2 * x).epsilon(1e-13));
    }
  // digest T12 values (8 digits).
  CHECK(evaluate(O, 0.3, 0.6, 2, 0)(0) == Approx(2.5498588).epsilon(0).margin(5e-8));
  CHECK(evaluate(O, 0.3, 0.6, 0, 2)(0) == Approx(2.6).epsilon(0).margin(5e-8));
  CHECK(evaluate(O, 0.3, 0.6)(0) == Approx(1.6918588).epsilon(0).margin(5e-8));
  CHECK(f(0.3, 0.6, 0, 0)(0) == Approx(1.7422588).epsilon(0).margin(5e-8));
  CHECK(evaluate(O, 0.9, 0.1, 2, 0)(0) == Approx(2.6596031).epsilon(0).margin(5e-8));
  CHECK(evaluate(O, 0.9, 0.1, 0, 2)(0) == Approx(3.8).epsilon(0).margin(5e-8));
}

TEST_CASE("T13: composite Coons error table and its fitted O(h^4) order", "[gordon][T13]") {
  const Field f = [](double x, double y, int dx, int dy) {
    const double sx = dx == 0   ? std::sin(3 * x)
                      : dx == 1 ? 3 * std::cos(3 * x)
                                : -9 * std::sin(3 * x);
    const double cy = dy == 0   ? std::cos(2 * y)
                      : dy == 1 ? -2 * std::sin(2 * y)
                                : -4 * std::cos(2 * y);
    return scalar(sx * cy + mono(x, 3, dx) * mono(y, 3, dy));
  };
  const double table[] = {3.7624e-01, 2.9136e-02, 2.1650e-03, 1.4041e-04, 8.7321e-06};
  std::vector<double> h, err;
  int row = 0;
  for (int n : {1, 2, 4, 8, 16}) {
    const VectorXd lines = VectorXd::LinSpaced(n + 1, 0, 1);
    const GordonSurface O = coons_composite(traces_of(f, lines, lines));
    const double e = test::max_error_on_unit_square(O, f, 101);
    // The digest prints 5 significant digits: agreement to half a unit of the last one.
    CHECK(e == Approx(table[row]).epsilon(1.5e-4));
    h.push_back(1.0 / n);
    err.push_back(e);
    ++row;
  }
  const double all = test::fitted_order(h, err);
  const double fine = test::fitted_order({h[2], h[3], h[4]}, {err[2], err[3], err[4]});
  INFO("fitted order, all rows " << all << ", n = 4..16 " << fine);
  // Pre-asymptotic rows (n = 1, 2) pull the all-row fit below 4; the fine rows are O(h^4).
  CHECK(all == Approx(3.8).epsilon(0).margin(0.15));
  CHECK(fine == Approx(4.0).epsilon(0).margin(0.1));
  // The same orders from the digest's printed table itself.
  const std::vector<double> tab(table, table + 5);
  CHECK(test::fitted_order({h[2], h[3], h[4]}, {tab[2], tab[3], tab[4]}) ==
        Approx(4.0).epsilon(0).margin(0.1));
}

TEST_CASE("Cubic Gordon converges like O(h^8) = O(h_x^4 h_y^4) on the T13 function", "[gordon]") {
  // f - O f = (I - P_x)(I - P_y) f with cubic spline interpolation errors O(h^4) in each factor.
  std::vector<double> h, err;
  for (int n : {4, 8, 16}) {
    const VectorXd lines = VectorXd::LinSpaced(n + 1, 0, 1);
    const GordonSurface O = gordon_surface(traces_of(test::t13, lines, lines));
    h.push_back(1.0 / n);
    err.push_back(test::max_error_on_unit_square(O, test::t13, 101));
  }
  INFO("errors " << err[0] << " " << err[1] << " " << err[2]);
  // Measured 8.5 (studies/interlineation_convergence.py: 9.96e-6, 2.99e-8, 7.76e-11 on a 201^2
  // sample).
  CHECK(test::fitted_order(h, err) == Approx(8.0).epsilon(0).margin(0.7));
}

TEST_CASE("Gordon operators reproduce every trace, scalar and vector valued", "[gordon]") {
  // A smooth vector field f: R^2 -> R^3 with derivatives of every order (products of exp/sin).
  const Field F = [](double x, double y, int dx, int dy) {
    RowVectorXd r(3);
    const double ex = std::pow(0.7, dx) * std::exp(0.7 * x),
                 ey = std::pow(-1.3, dy) * std::exp(-1.3 * y);
    const double sx = std::pow(2.0, dx) * std::sin(2 * x + dx * M_PI / 2);
    const double cy = std::pow(3.0, dy) * std::cos(3 * y + dy * M_PI / 2);
    r << ex * ey, sx * cy + ex, (dy == 0 ? sx : 0.0) + (dx == 0 ? ey : 0.0);
    return r;
  };
  VectorXd x(4), y(5);
  x << -0.4, 0.1, 0.35, 1.2;
  y << 0.0, 0.2, 0.25, 0.7, 1.0;
  for (auto [px, py] : {std::pair{1, 1}, {2, 2}, {3, 3}, {1, 3}, {3, 2}}) {
    GordonOptions o;
    o.degree_x = px;
    o.degree_y = py;
    const GordonSurface O = gordon_surface(traces_of(F, x, y), o);
    CHECK(O.dim == 3);
    double worst = 0;
    for (double s : VectorXd::LinSpaced(201, 0, 1)) {
      const double xs = -0.4 + 1.6 * s, ys = s;
      for (Index i = 0; i < x.size(); ++i)
        worst = std::max(worst, (evaluate(O, x(i), ys) - F(x(i), ys, 0, 0)).cwiseAbs().maxCoeff());
      for (Index j = 0; j < y.size(); ++j)
        worst = std::max(worst, (evaluate(O, xs, y(j)) - F(xs, y(j), 0, 0)).cwiseAbs().maxCoeff());
    }
    INFO("degrees " << px << ", " << py);
    // Values O(3); cardinal weights from a collocation solve of condition ~10: round-off.
    CHECK(worst < 1e-14);
    // Derivatives along a line equal the trace's derivatives (exact on the line).
    CHECK((evaluate(O, x(2), 0.4, 0, 1) - F(x(2), 0.4, 0, 1)).norm() < 1e-13);
  }
  // Scalar traces from sampled data: the operator passes through every sample.
  const Field g = [](double a, double b, int, int) { return scalar(std::cos(a + 2 * b) + a * b); };
  LineTraces t;
  t.x = x;
  t.y = y;
  for (Index i = 0; i < x.size(); ++i) {
    VectorXd s(7);
    s << 0.0, 0.1, 0.2, 0.25, 0.5, 0.7, 1.0; // contains every y_j: crossings are data
    MatrixXd vals(7, 1);
    for (Index k = 0; k < 7; ++k)
      vals(k, 0) = g(x(i), s(k), 0, 0)(0);
    t.on_x.push_back(sampled_trace(s, vals, 3));
  }
  for (Index j = 0; j < y.size(); ++j) {
    VectorXd s(6);
    s << -0.4, -0.1, 0.1, 0.35, 0.8, 1.2;
    MatrixXd vals(6, 1);
    for (Index k = 0; k < 6; ++k)
      vals(k, 0) = g(s(k), y(j), 0, 0)(0);
    t.on_y.push_back(sampled_trace(s, vals, 3));
  }
  const GordonSurface O = gordon_surface(t);
  CHECK(O.dim == 1);
  CHECK(std::abs(evaluate(O, x(1), 0.5)(0) - g(x(1), 0.5, 0, 0)(0)) < 1e-14);
  CHECK(std::abs(evaluate(O, 0.8, y(3))(0) - g(0.8, y(3), 0, 0)(0)) < 1e-14);
}

TEST_CASE("Error identity f - O f = (I - P_x)(I - P_y) f on polynomials", "[gordon]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  MatrixXd c(6, 6); // f = sum c_ab x^a y^b, degree <= 5 in each variable
  for (Index a = 0; a < 6; ++a)
    for (Index b = 0; b < 6; ++b)
      c(a, b) = U(rng);
  const Field f = [c](double x, double y, int dx, int dy) {
    double s = 0;
    for (int a = 0; a < 6; ++a)
      for (int b = 0; b < 6; ++b)
        s += c(a, b) * mono(x, a, dx) * mono(y, b, dy);
    return scalar(s);
  };
  VectorXd x(5), y(4);
  x << 0, 0.15, 0.5, 0.6, 1;
  y << -1, -0.2, 0.3, 1;
  for (auto [px, py] : {std::pair{1, 1}, {2, 3}, {3, 3}}) {
    GordonOptions o;
    o.degree_x = px;
    o.degree_y = py;
    const GordonSurface O = gordon_surface(traces_of(f, x, y), o);
    // Independent route: e_a(x) = x^a - (1-D spline interpolant of x^a on the nodes)(x), from
    // interpolate_open, and (I-P_x)(I-P_y) x^a y^b = e_a(x) e_b(y).
    const auto error_1d = [](const VectorXd& nodes, int p, int a, double s) {
      MatrixXd vals(nodes.size(), 1);
      for (Index k = 0; k < nodes.size(); ++k)
        vals(k, 0) = std::pow(nodes(k), a);
      return std::pow(s, a) -
             evaluate(interpolate_open(vals, nodes, p), VectorXd::Constant(1, s))(0, 0);
    };
    for (int k = 0; k < 40; ++k) {
      const double xs = 0.5 + 0.5 * U(rng), ys = U(rng);
      double E = 0;
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b)
          E += c(a, b) * error_1d(x, px, a, xs) * error_1d(y, py, b, ys);
      INFO("degrees " << px << ", " << py << " at " << xs << ", " << ys);
      CHECK(f(xs, ys, 0, 0)(0) - evaluate(O, xs, ys)(0) == Approx(E).epsilon(0).margin(1e-13));
    }
  }
}

TEST_CASE("Theorem 3: random convex traces give a convex Coons patch in each direction",
          "[gordon][theorem3]") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0, 1);
  // Random convex function of one variable with derivatives: c0 + c1 t + sum a_m exp(b_m t) +
  // d t^2, a_m > 0, d >= 0.
  struct Convex {
    double c0, c1, d, a[3], b[3];
    double operator()(double t, int k) const {
      double s = k == 0 ? c0 + c1 * t + d * t * t : k == 1 ? c1 + 2 * d * t : k == 2 ? 2 * d : 0;
      for (int m = 0; m < 3; ++m)
        s += a[m] * std::pow(b[m], k) * std::exp(b[m] * t);
      return s;
    }
  };
  const auto random_convex = [&] {
    Convex c{4 * U(rng) - 2, 4 * U(rng) - 2, U(rng), {}, {}};
    for (int m = 0; m < 3; ++m)
      c.a[m] = 0.5 * U(rng), c.b[m] = 6 * U(rng) - 3;
    return c;
  };
  for (int trial = 0; trial < 20; ++trial)
    for (double sign : {1.0, -1.0}) { // convex and concave traces
      const double x0 = U(rng), x1 = x0 + 0.2 + U(rng), y0 = -U(rng), y1 = y0 + 0.2 + U(rng);
      const Convex g0 = random_convex(), g1 = random_convex(), h0 = random_convex(),
                   h1 = random_convex();
      // Traces on y = y_j: sign * g_j(x). Traces on x = x_i: sign * (h_i(y) + linear), the
      // linear part making them meet g at the corners (adding a linear function keeps convexity).
      const auto lin = [&](const Convex& h, double xi) {
        const double a0 = g0(xi, 0) - h(y0, 0), a1 = g1(xi, 0) - h(y1, 0);
        return std::pair{a0, (a1 - a0) / (y1 - y0)};
      };
      LineTraces t;
      t.x = Eigen::Vector2d(x0, x1);
      t.y = Eigen::Vector2d(y0, y1);
      for (const auto& [h, xi] : {std::pair{h0, x0}, {h1, x1}}) {
        const auto [a0, slope] = lin(h, xi);
        t.on_x.push_back([=](double s, int k) {
          return scalar(sign * (h(s, k) + (k == 0 ? a0 + slope * (s - y0) : k == 1 ? slope : 0)));
        });
      }
      for (const Convex& g : {g0, g1})
        t.on_y.push_back([=](double s, int k) { return scalar(sign * g(s, k)); });
      const GordonSurface O = coons_bilinear(t);
      const VectorXd xs = VectorXd::LinSpaced(41, x0, x1), ys = VectorXd::LinSpaced(41, y0, y1);
      const ShapeMap m = shape_map(O, xs, ys);
      const int want = sign > 0 ? 1 : -1;
      CHECK((m.along_u.array() == want).all());
      CHECK((m.along_v.array() == want).all());
      // The proof's identity: O_xx is the linear blend of the traces' second derivatives.
      for (Index k = 0; k < 41; k += 8) {
        const double w = (ys(k) - y0) / (y1 - y0);
        CHECK(evaluate(O, xs(k), ys(k), 2, 0)(0) ==
              Approx(sign * ((1 - w) * g0(xs(k), 2) + w * g1(xs(k), 2))).epsilon(1e-12));
      }
    }
}

TEST_CASE("Theorem 3 on a composite grid: separately convex data stay convex",
          "[gordon][theorem3]") {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> U(0, 1);
  for (int trial = 0; trial < 10; ++trial) {
    // f = sum a_m exp(b_m x + c_m y) + d x^2 y^2 + linear: convex in x for every y and in y for
    // every x; its traces on any grid are convex and compatible.
    double a[3], b[3], cc[3];
    for (int m = 0; m < 3; ++m)
      a[m] = U(rng), b[m] = 4 * U(rng) - 2, cc[m] = 4 * U(rng) - 2;
    const double d = U(rng), l0 = U(rng), l1 = U(rng);
    const Field f = [=](double x, double y, int dx, int dy) {
      double s = d * mono(x, 2, dx) * mono(y, 2, dy) + (dx + dy == 0 ? l0 * x + l1 * y : 0) +
                 (dx == 1 && dy == 0 ? l0 : 0) + (dx == 0 && dy == 1 ? l1 : 0);
      for (int m = 0; m < 3; ++m)
        s += a[m] * std::pow(b[m], dx) * std::pow(cc[m], dy) * std::exp(b[m] * x + cc[m] * y);
      return scalar(s);
    };
    VectorXd x(5), y(4);
    x << 0, 0.1, 0.45, 0.5, 1;
    y << 0, 0.3, 0.8, 1.3;
    const GordonSurface O = coons_composite(traces_of(f, x, y));
    const ShapeMap m = shape_map(O, VectorXd::LinSpaced(57, 0, 1), VectorXd::LinSpaced(53, 0, 1.3));
    CHECK((m.along_u.array() == 1).all());
    CHECK((m.along_v.array() == 1).all());
    const ShapeSummary s = summarize(m);
    CHECK(s.convex_u == 1.0);
    CHECK(s.concave_v == 0.0);
  }
}

TEST_CASE("Gordon operator: one family, periodic blending, errors", "[gordon]") {
  // f(t, y) periodic in t: lines t = t_l (5, nonuniform) and y = y_j (3).
  const Field f = [](double t, double y, int dt, int dy) {
    return scalar(std::cos(t + dt * M_PI / 2) * mono(y, 2, dy) +
                  (dy == 0 ? std::pow(2.0, dt) * std::sin(2 * t + dt * M_PI / 2) : 0.0));
  };
  VectorXd t(5), y(3);
  t << 0.3, 1.0, 2.5, 4.0, 5.5;
  y << 0, 0.5, 1;
  GordonOptions o;
  o.periodic_x = true;
  o.period_x = 2 * M_PI;
  const GordonSurface O = gordon_surface(traces_of(f, t, y), o);
  for (double s : {0.1, 0.7, 3.3, 6.0}) {
    // Periodic: the same value one period later; exact on the lines.
    CHECK((evaluate(O, s, 0.3) - evaluate(O, s + 2 * M_PI, 0.3)).norm() < 1e-13);
    CHECK(std::abs(evaluate(O, t(2), s / 6)(0) - f(t(2), s / 6, 0, 0)(0)) < 1e-14);
  }
  // C2 across the period's ends (the blending curve is clamped there).
  for (int d = 0; d <= 2; ++d)
    CHECK((evaluate(O, 0.3 + 1e-9, 0.4, d, 0) - evaluate(O, 0.3 + 2 * M_PI - 1e-9, 0.4, d, 0))
              .norm() < 1e-6);

  // One family only: P_x f on lines x = x_i.
  LineTraces one = traces_of(f, t, y);
  one.on_y.clear();
  one.y.resize(0);
  const GordonSurface P = gordon_surface(one, o);
  CHECK(std::abs(evaluate(P, t(3), 0.77)(0) - f(t(3), 0.77, 0, 0)(0)) < 1e-14);

  // Incompatible traces: the message names the crossing.
  LineTraces bad = traces_of(f, t, y);
  bad.on_x[1] = [f](double s, int d) -> RowVectorXd { return f(1.0, s, 0, d) + scalar(1e-6); };
  CHECK_THROWS_WITH(gordon_surface(bad, o), Catch::Contains("crossing (1, 0)"));
  CHECK_THROWS_WITH(coons_bilinear(traces_of(f, t, y)), Catch::Contains("two lines"));
  const GordonSurface C = coons_composite(traces_of(f, VectorXd::LinSpaced(3, 0, 1), y));
  CHECK_THROWS_WITH(evaluate(C, 1.5, 0.5), Catch::Contains("outside the grid"));
}
