// Interflatation operators (interflatation/operators): the box and grid interflatation (T14,
// exact on every plane, C0 and C2), Theorem 4 in 2-D (T15-T17 to the digits of digest 001,
// T19: Ou = 0 on dG for random free traces, exact on grid lines, continuity), the C1 Hermite
// variant of Example 3, and convergence of max |Ou - d| near dG with the fitted order.
#include "interlin/interflatation/operators/free_traces.h"
#include "interlin/interflatation/operators/grid_interflatation.h"
#include "interlin/interflatation/operators/region_interlineation.h"
#include "interlin/interflatation/rfunctions/r_operations.h"
#include "interlin/interlineation/coons_hermite.h"
#include "interlin/splines/closed_section_curve.h"
#include "support/test_support.h"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>

using namespace interlin;
using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

// Example 3's R-function (digest §2.7, [DOC]): u + v - sqrt(u^2 + v^2), u = x(1-x), v = y(1-y).
double example3(const Vector2d& p) {
  const double u = p(0) * (1 - p(0)), v = p(1) * (1 - p(1));
  return u + v - std::sqrt(u * u + v * v);
}

Eigen::VectorXd lines(std::initializer_list<double> v) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v)
    r(i++) = x;
  return r;
}

const Eigen::AlignedBox2d unit_square(Vector2d(0, 0), Vector2d(1, 1));

} // namespace

TEST_CASE("T14: box interflatation, exact on the faces, digest values", "[operators]") {
  const Vector3d lo(0, 0, 0), hi(1, 1, 1);
  const auto cube = [](const Vector3d& p) { return std::pow(p(0) * p(1) * p(2), 2); };
  // (xyz)^2: Of(1/2,1/2,1/2) = 1/32 and f - Of = -x(1-x) y(1-y) z(1-z) (digest T14).
  CHECK(box_interflatation(cube, lo, hi, Vector3d(0.5, 0.5, 0.5)) ==
        Approx(1.0 / 32).epsilon(1e-15));
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> U(0, 1);
  for (int k = 0; k < 50; ++k) {
    const Vector3d p(U(rng), U(rng), U(rng));
    const double err = cube(p) - box_interflatation(cube, lo, hi, p);
    CHECK(err == Approx(-p(0) * (1 - p(0)) * p(1) * (1 - p(1)) * p(2) * (1 - p(2)))
                     .epsilon(0)
                     .margin(1e-15));
  }
  const auto f = [](const Vector3d& p) {
    return std::sin(p(0) + 2 * p(1)) * std::exp(p(2)) + p(0) * p(1) * p(2);
  };
  CHECK(box_interflatation(f, lo, hi, Vector3d(0.3, 0.4, 0.5)) ==
        Approx(1.5386766581747588).epsilon(1e-15));
  // Exact on all six faces (digest: <= 4.4e-16; the Boolean sum adds 7 terms of size <= 3, so
  // allow 4 ulp of 3).
  double face_error = 0;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {0.0, 1.0})
      for (int k = 0; k < 20; ++k) {
        Vector3d p(U(rng), U(rng), U(rng));
        p(axis) = side;
        face_error = std::max(face_error, std::abs(box_interflatation(f, lo, hi, p) - f(p)));
      }
  CHECK(face_error <= 2.7e-15);
}

TEST_CASE("Grid interflatation: exact on every plane, C0 and C2 blending, orders", "[operators]") {
  const auto f = [](const Vector3d& p) {
    return std::sin(1.3 * p(0) + p(1)) * std::cos(0.7 * p(2)) + p(0) * p(1) * p(1);
  };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0, 1);
  for (int degree : {1, 3}) {
    // Nonuniform planes: exactness must not depend on spacing.
    std::array<Eigen::VectorXd, 3> nodes{lines({0, 0.15, 0.45, 0.6, 1}), lines({0, 0.3, 0.7, 1}),
                                         lines({0, 0.2, 0.35, 0.8, 1})};
    const PlaneTraces t = plane_traces(f, nodes);
    CHECK(plane_trace_mismatch(t) == 0);
    const GridInterflatation O = grid_interflatation(t, degree);
    double plane_error = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (Eigen::Index i = 0; i < nodes[axis].size(); ++i)
        for (int k = 0; k < 10; ++k) {
          Vector3d p(U(rng), U(rng), U(rng));
          p(axis) = nodes[axis](i);
          plane_error = std::max(plane_error, std::abs(evaluate(O, p) - f(p)));
        }
    // Round-off of sums of at most 7 x 5^3 terms of size 1.
    CHECK(plane_error <= 1e-13);
  }
  // f - Of = (I-P1)(I-P2)(I-P3) f: each factor O(h^2) (linear) or O(h^4) (cubic) -> orders 6, 12
  // for smooth f on uniform grids; the fit asks for at least 5.5 and 8 (the cubic error reaches
  // round-off quickly, so the fitted slope of the first halvings is taken).
  for (int degree : {1, 3}) {
    std::vector<double> h, e;
    for (int n : {3, 5, 9}) {
      const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n, 0, 1);
      const GridInterflatation O = grid_interflatation(plane_traces(f, {v, v, v}), degree);
      double worst = 0;
      std::mt19937 r2(3);
      for (int k = 0; k < 400; ++k) {
        const Vector3d p(U(r2), U(r2), U(r2));
        worst = std::max(worst, std::abs(evaluate(O, p) - f(p)));
      }
      h.push_back(1.0 / (n - 1));
      e.push_back(worst);
    }
    const double order = std::log(e[0] / e[1]) / std::log(h[0] / h[1]);
    INFO("degree " << degree << " errors " << e[0] << " " << e[1] << " " << e[2] << " order "
                   << order);
    CHECK(order >= (degree == 1 ? 5.5 : 8.0));
  }
}

TEST_CASE("T15: Example 3's R-function, digest values", "[operators]") {
  const std::vector<std::pair<Vector2d, double>> table = {
      {{0.5, 0.5}, 0.1464466094067262},   {{0.25, 0.5}, 0.125},
      {{0.25, 0.25}, 0.1098349570550447}, {{0.1, 0.5}, 0.0742933948882716},
      {{0.1, 0.1}, 0.0527207793864214},   {{0.9, 0.2}, 0.0664244024931418}};
  using rf::Expr;
  const Expr X = Expr::x(), Y = Expr::y();
  const ImplicitFunction w = rf::compile(rf::and0(X * (1 - X), Y * (1 - Y)),
                                         Eigen::AlignedBox3d(Vector3d(0, 0, 0), Vector3d(1, 1, 1)));
  for (const auto& [p, value] : table) {
    CHECK(example3(p) == Approx(value).epsilon(1e-15));
    Points3 P(1, 3);
    P << p(0), p(1), 0;
    Eigen::VectorXd F(1);
    w.value(P, F);
    CHECK(F(0) == Approx(value).epsilon(1e-15));
  }
}

TEST_CASE("T16: Theorem 4 on the unit square, C0, digest values", "[operators][theorem4]") {
  const PlaneBoundary square = implicit_boundary(example3, unit_square);
  const Eigen::VectorXd g = lines({0, 0.5, 1});
  // w = the R-function: Ou(0.25,0.25) = 0.0883883, max |Ou - w| = 0.0300247 at (0.13,0.13).
  const RegionInterlineation O = region_interlineation(square, g, g, example3);
  for (const auto& pieces : O.pieces)
    for (const CellPiece& p : pieces)
      CHECK(p.kind == CellKind::rectangle);
  CHECK(evaluate(O, Vector2d(0.25, 0.25)) == Approx(0.0883883).epsilon(0).margin(5e-8));
  double worst = 0;
  Vector2d at = Vector2d::Zero();
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const Vector2d p(i / 200.0, j / 200.0);
      const double e = std::abs(evaluate(O, p) - example3(p));
      if (e > worst) {
        worst = e;
        at = p;
      }
    }
  CHECK(worst == Approx(0.0300247).epsilon(0).margin(5e-8));
  // At (0.13, 0.13) or one of its mirror images (the problem is symmetric).
  CHECK((at.cwiseMin(Vector2d(1, 1) - at) - Vector2d(0.13, 0.13)).norm() < 1e-12);
  // Exact on the boundary and on both interior lines.
  for (int k = 0; k <= 40; ++k) {
    const double s = k / 40.0;
    for (const Vector2d& p : {Vector2d(0, s), Vector2d(1, s), Vector2d(s, 0), Vector2d(s, 1)})
      CHECK(evaluate(O, p) == 0);
    for (const Vector2d& p : {Vector2d(0.5, s), Vector2d(s, 0.5)})
      CHECK(evaluate(O, p) == Approx(example3(p)).epsilon(0).margin(1e-15));
  }
  // w = the normal function min(x, 1-x, y, 1-y): Ou = 2xy on [0, 1/2]^2.
  const auto normal = [](const Vector2d& p) { return std::min({p(0), 1 - p(0), p(1), 1 - p(1)}); };
  const RegionInterlineation N = region_interlineation(square, g, g, normal);
  CHECK(evaluate(N, Vector2d(0.25, 0.25)) == Approx(0.125).epsilon(0).margin(1e-15));
  CHECK(evaluate(N, Vector2d(0.1, 0.3)) == Approx(2 * 0.1 * 0.3).epsilon(0).margin(1e-15));
}

TEST_CASE("T17: curved triangles of the unit disc, digest values", "[operators][theorem4]") {
  const auto w = [](const Vector2d& p) { return 1 - p.norm(); };
  const Eigen::AlignedBox2d box(Vector2d(-1, -1), Vector2d(1, 1));
  const Eigen::VectorXd g = lines({-1, 0, 1});
  const auto disc = [](const Vector2d& p) { return 1 - p.squaredNorm(); };
  // The disc as an implicit curve and as a closed B-spline curve must give the same operator
  // where the curve is the circle (to the curve's accuracy).
  const RegionInterlineation O = region_interlineation(implicit_boundary(disc, box), g, g, w);
  // Each quadrant is one curved triangle: the circle touches the grid lines x, y = +-1, and the
  // sliver that the chord-end tolerance makes at the touch is no piece of its own.
  for (const auto& pieces : O.pieces) {
    REQUIRE(pieces.size() == 1);
    CHECK(pieces[0].kind == CellKind::triangle);
  }
  // First quadrant: Ou = (1-x)(1 - y / sqrt(1-x^2)); the digest's values to its 7 digits.
  CHECK(std::abs(evaluate(O, Vector2d(0.5, 0.5)) - 0.2113249) <= 5e-8);
  CHECK(std::abs(evaluate(O, Vector2d(0.3, 0.2)) - 0.5532401) <= 5e-8);
  // The closed form to round-off (1e-12: the chords of the implicit circle are roots to ~1e-15).
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> U(0, 1);
  double worst = 0;
  for (int k = 0; k < 100; ++k) {
    const double x = U(rng), y = U(rng) * std::sqrt(1 - x * x);
    worst = std::max(
        worst, std::abs(evaluate(O, Vector2d(x, y)) - (1 - x) * (1 - y / std::sqrt(1 - x * x))));
  }
  CHECK(worst <= 1e-12);
  // Zero on the circle, 1 - |x| and 1 - |y| on the axes.
  for (int k = 0; k < 64; ++k) {
    const double a = 2 * M_PI * (k + 0.37) / 64;
    CHECK(std::abs(evaluate(O, Vector2d(std::cos(a), std::sin(a)))) <= 1e-12);
    const double s = -1 + 2 * (k + 0.5) / 64;
    CHECK(evaluate(O, Vector2d(s, 0)) == Approx(1 - std::abs(s)).epsilon(0).margin(1e-12));
    CHECK(evaluate(O, Vector2d(0, s)) == Approx(1 - std::abs(s)).epsilon(0).margin(1e-12));
  }
}

TEST_CASE("T19: Ou = 0 on dG for random free traces (implicit, polygon, B-spline boundary)",
          "[operators][theorem4]") {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> U(-1, 1);
  // An ellipse-like curve through 24 points as a closed cubic B-spline section curve.
  Eigen::MatrixXd pts(24, 2);
  for (int k = 0; k < 24; ++k) {
    const double a = 2 * M_PI * k / 24;
    pts.row(k) << 1.7 * std::cos(a) + 0.2 * std::cos(2 * a), 0.9 * std::sin(a);
  }
  const BSplineCurve curve = closed_section_curve(pts).curve;
  Eigen::MatrixX2d hexagon(6, 2);
  hexagon << 0, -1, 1.2, -0.4, 1.0, 0.8, -0.1, 1.1, -1.3, 0.3, -0.9, -0.8;
  const auto lobe = [](const Vector2d& p) {
    return 1 - std::pow(p(0) / 1.6, 2) - std::pow(p(1) / (1 + 0.3 * p(0)), 2);
  };
  const Eigen::AlignedBox2d box(Vector2d(-2.1, -1.6), Vector2d(2.1, 1.6));
  struct Case {
    const char* name;
    PlaneBoundary b;
  };
  const std::vector<Case> cases = {{"implicit", implicit_boundary(lobe, box)},
                                   {"polygon", polygon_boundary(hexagon)},
                                   {"curve", curve_boundary(curve)}};
  for (const Case& c : cases)
    for (int trial = 0; trial < 3; ++trial) {
      // Random free traces: restrictions of a random smooth function, nonzero on dG.
      const double a0 = U(rng), a1 = U(rng), a2 = U(rng), a3 = U(rng), f = 2 + 2 * U(rng);
      const auto u = [=](const Vector2d& p) {
        return a0 + a1 * p(0) + a2 * p(1) * p(1) + a3 * std::sin(f * p(0) + p(1));
      };
      // Random nonuniform grid lines covering the box.
      const auto random_lines = [&](double lo, double hi, int n) {
        std::vector<double> v{lo - 0.1, hi + 0.1};
        for (int k = 0; k < n; ++k)
          v.push_back(lo + (hi - lo) * (0.5 + 0.5 * U(rng)));
        std::sort(v.begin(), v.end());
        return Eigen::Map<Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size())).eval();
      };
      const RegionInterlineation O =
          region_interlineation(c.b, random_lines(-2.0, 2.0, 6), random_lines(-1.5, 1.5, 5), u);
      // Boundary points: the ends of chords of random lines.
      double worst = 0;
      for (int k = 0; k < 60; ++k)
        for (int axis = 0; axis < 2; ++axis) {
          const double cpos = 1.2 * U(rng);
          for (double s : c.b.chords(axis, cpos)) {
            Vector2d p;
            p(axis) = cpos;
            p(1 - axis) = s;
            worst = std::max(worst, std::abs(evaluate(O, p)));
          }
        }
      INFO(c.name << " trial " << trial);
      // Round-off of the mapped Coons sum (t = 1 to 1e-16, traces of size <= 4).
      CHECK(worst <= 1e-12);
    }
}

TEST_CASE("Theorem 4: exact on grid lines and continuous for traces zero on dG, cell kinds",
          "[operators][theorem4]") {
  // Ellipse, traces from an R-function-like target that vanishes on dG: Ou = u on every grid
  // line, and Ou has no jumps across cell sides.
  const auto g = [](const Vector2d& p) { return 1 - std::pow(p(0) / 1.5, 2) - p(1) * p(1); };
  const auto u = [&](const Vector2d& p) { return g(p) * (1 + 0.3 * std::sin(2 * p(0) + p(1))); };
  const Eigen::AlignedBox2d box(Vector2d(-1.6, -1.1), Vector2d(1.6, 1.1));
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(9, -1.6, 1.6),
                        y = lines({-1.1, -0.75, -0.3, 0.1, 0.45, 0.8, 1.1});
  const RegionInterlineation O = region_interlineation(implicit_boundary(g, box), x, y, u);
  std::map<CellKind, int> kinds;
  for (const auto& pieces : O.pieces)
    for (const CellPiece& p : pieces)
      ++kinds[p.kind];
  CHECK(kinds[CellKind::rectangle] > 0);
  CHECK(kinds[CellKind::triangle] > 0);
  CHECK(kinds[CellKind::curved_top] + kinds[CellKind::curved_bottom] > 0);
  CHECK(kinds[CellKind::curved_left] + kinds[CellKind::curved_right] > 0);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(0, 1);
  double line_error = 0, jump = 0;
  for (Eigen::Index i = 1; i + 1 < x.size(); ++i)
    for (int k = 0; k < 50; ++k) {
      const Vector2d p(x(i), -1.1 + 2.2 * U(rng));
      if (g(p) <= 0)
        continue;
      line_error = std::max(line_error, std::abs(evaluate(O, p) - u(p)));
      const double e = 1e-9;
      jump = std::max(jump,
                      std::abs(evaluate(O, p + Vector2d(e, 0)) - evaluate(O, p - Vector2d(e, 0))));
    }
  for (Eigen::Index j = 1; j + 1 < y.size(); ++j)
    for (int k = 0; k < 50; ++k) {
      const Vector2d p(-1.6 + 3.2 * U(rng), y(j));
      if (g(p) <= 0)
        continue;
      line_error = std::max(line_error, std::abs(evaluate(O, p) - u(p)));
    }
  CHECK(line_error <= 1e-12);
  // |grad Ou| <= ~10 here: 1e-9 steps give jumps <= 1e-8 when Ou is continuous.
  CHECK(jump <= 1e-7);
}

TEST_CASE("Theorem 4 convergence: max |Ou - d| near the circle, C0, fitted order",
          "[operators][theorem4][convergence]") {
  // Traces from the exact distance d = 1 - r (smooth away from the centre); the error on the
  // band 0 < d < 0.25 falls as O(h^2) (bilinear Coons in mapped coordinates); measured
  // 4.6e-4, 1.2e-4, 3.1e-5 for 12, 24, 48 cells (order 1.90 fitted; 1.5 from 6 to 24 cells,
  // before the asymptotic range).
  const auto d = [](const Vector2d& p) { return 1 - p.norm(); };
  const auto disc = [](const Vector2d& p) { return 1 - p.squaredNorm(); };
  const Eigen::AlignedBox2d box(Vector2d(-1, -1), Vector2d(1, 1));
  std::vector<double> h, e;
  for (int n : {12, 24, 48}) {
    // Lines offset from the centre so that no line passes through r = 0 (d's kink).
    const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n + 1, -1.0 - 0.37 / n, 1.0 + 0.63 / n);
    const RegionInterlineation O = region_interlineation(implicit_boundary(disc, box), v, v, d);
    double worst = 0;
    for (int k = 0; k < 2000; ++k) {
      const double a = 2 * M_PI * k / 2000.0, r = 0.75 + 0.25 * ((k * 7919) % 1000) / 1000.0;
      const Vector2d p(r * std::cos(a), r * std::sin(a));
      worst = std::max(worst, std::abs(evaluate(O, p) - d(p)));
    }
    h.push_back(v(1) - v(0));
    e.push_back(worst);
  }
  const double order = test::fitted_order(h, e);
  INFO("errors " << e[0] << " " << e[1] << " " << e[2] << " order " << order);
  CHECK(order >= 1.7);
}

TEST_CASE("Example 3, C1 variant: Hermite Coons cells with value and slope traces",
          "[operators][theorem4]") {
  // Unit square cut by x = 1/2, y = 1/2 (digest §5 item 2): value traces of the R-function on
  // the interior lines, zero value traces on dG, and normal-derivative traces: the R-function's
  // (0 on the interior lines, by symmetry) and on dG the free choice m(s) = 4 s (1 - s), which
  // is 1 at the edge mid-points (d omega / dn = 1 there, T15) and 0 at the corners (C1 at a
  // right-angle corner of dG needs grad Ou = 0 there).
  const auto on_line = [](double c) {
    // omega(c, s) and d/ds along the line (symmetric in x and y).
    return Trace([c](double s, int d) {
      const double u = c * (1 - c), v = s * (1 - s), r = std::sqrt(u * u + v * v);
      Eigen::RowVectorXd out(1);
      if (d == 0)
        out(0) = r > 0 ? u + v - r : 0;
      else if (d == 1)
        out(0) = r > 0 ? (1 - 2 * s) * (1 - v / r) : 0;
      else
        throw std::invalid_argument("derivative order");
      return out;
    });
  };
  const auto slope = [](double sign) {
    return Trace([sign](double s, int d) {
      Eigen::RowVectorXd out(1);
      out(0) = sign * (d == 0 ? 4 * s * (1 - s) : (d == 1 ? 4 - 8 * s : -8.0 * (d == 2)));
      return out;
    });
  };
  const Trace zero_slope = [](double, int) { return Eigen::RowVectorXd::Zero(1).eval(); };
  HermiteTraces t;
  t.values.x = t.values.y = lines({0, 0.5, 1});
  t.values.on_x = t.values.on_y = {on_line(0), on_line(0.5), on_line(1)};
  t.dx_on_x = t.dy_on_y = {slope(1), zero_slope, slope(-1)};
  const HermiteCoons O = coons_hermite(t);
  double boundary = 0, lines_error = 0, jump = 0;
  for (int k = 0; k <= 50; ++k) {
    const double s = k / 50.0;
    for (const Vector2d& p : {Vector2d(0, s), Vector2d(1, s), Vector2d(s, 0), Vector2d(s, 1)})
      boundary = std::max(boundary, std::abs(evaluate(O, p(0), p(1))(0)));
    for (const Vector2d& p : {Vector2d(0.5, s), Vector2d(s, 0.5)})
      lines_error = std::max(lines_error, std::abs(evaluate(O, p(0), p(1))(0) - example3(p)));
    // d/dx across x = 1/2 from both cells, d/dy across y = 1/2.
    const double e = 1e-12;
    jump = std::max(
        {jump, std::abs(evaluate(O, 0.5 - e, s, 1, 0)(0) - evaluate(O, 0.5 + e, s, 1, 0)(0)),
         std::abs(evaluate(O, s, 0.5 - e, 0, 1)(0) - evaluate(O, s, 0.5 + e, 0, 1)(0))});
  }
  CHECK(boundary == 0);
  CHECK(lines_error <= 1e-15);
  // Second derivatives are O(10): steps of 1e-12 move the first derivative by <= 1e-10.
  CHECK(jump <= 1e-10);
  // The C1 equation is positive inside and close to the R-function.
  CHECK(evaluate(O, 0.25, 0.25)(0) > 0);
}

TEST_CASE("Theorem 4 free traces by a criterion: least squares and min-max improve on u = w",
          "[operators][theorem4][free_traces]") {
  // A family of regions with targets w that vanish on dG: the disc with the exact distance, a
  // hexagon with the exact distance to its edges, ellipses of three aspect ratios with the
  // normalised implicit g / sqrt(g^2 + |grad g|^2) (seed 000 (2.26), finite at the centre). The
  // criterion is measured on one point set and checked on another (validation): the fitted traces
  // must lower max |Ou - w| and the RMS there.
  Eigen::MatrixX2d hexagon(6, 2);
  hexagon << 0, -1, 1.2, -0.4, 1.0, 0.8, -0.1, 1.1, -1.3, 0.3, -0.9, -0.8;
  const auto polygon_distance = [hexagon](const Vector2d& p) {
    double d = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 6; ++i) {
      const Vector2d a = hexagon.row(i), b = hexagon.row((i + 1) % 6);
      const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      d = std::min(d, (a + t * (b - a) - p).norm());
    }
    return d;
  };
  struct Case {
    std::string name;
    PlaneBoundary boundary;
    std::function<double(const Vector2d&)> w, inside;
  };
  std::vector<Case> cases;
  const Eigen::AlignedBox2d box(Vector2d(-1.5, -1.5), Vector2d(1.5, 1.5));
  cases.push_back({"disc",
                   implicit_boundary([](const Vector2d& p) { return 1 - p.squaredNorm(); }, box),
                   [](const Vector2d& p) { return 1 - p.norm(); },
                   [](const Vector2d& p) { return 1 - p.norm(); }});
  cases.push_back(
      {"hexagon", polygon_boundary(hexagon), polygon_distance, [hexagon](const Vector2d& p) {
         // Inside a convex polygon: on the left of every edge (counter-clockwise).
         for (int i = 0; i < 6; ++i) {
           const Vector2d a = hexagon.row(i), e = Vector2d(hexagon.row((i + 1) % 6)) - a;
           if (e(0) * (p(1) - a(1)) - e(1) * (p(0) - a(0)) <= 0)
             return -1.0;
         }
         return 1.0;
       }});
  for (const double aspect : {1.3, 2.0, 3.0}) {
    const auto g = [aspect](const Vector2d& p) {
      return 1 - std::pow(p(0) * aspect / 1.4, 2) - std::pow(p(1) / 1.4, 2);
    };
    const auto w = [aspect, g](const Vector2d& p) {
      const Vector2d grad(-2 * p(0) * std::pow(aspect / 1.4, 2), -2 * p(1) / (1.4 * 1.4));
      return g(p) / std::sqrt(g(p) * g(p) + grad.squaredNorm());
    };
    cases.push_back({"ellipse " + std::to_string(aspect), implicit_boundary(g, box), w, g});
  }
  const Eigen::VectorXd lines6 = Eigen::VectorXd::LinSpaced(7, -1.5, 1.5);
  for (const Case& c : cases) {
    // Points of G: a 6 x 6 lattice per cell (training) and 2000 random points (validation).
    std::vector<Vector2d> train, check;
    for (int i = 0; i < 36; ++i)
      for (int j = 0; j < 36; ++j) {
        const Vector2d p(-1.5 + 3.0 * (i + 0.5) / 36, -1.5 + 3.0 * (j + 0.5) / 36);
        if (c.inside(p) > 0)
          train.push_back(p);
      }
    std::mt19937 rng(41);
    std::uniform_real_distribution<double> U(-1.5, 1.5);
    while (check.size() < 2000) {
      const Vector2d p(U(rng), U(rng));
      if (c.inside(p) > 0)
        check.push_back(p);
    }
    Eigen::MatrixX2d S(static_cast<Eigen::Index>(train.size()), 2);
    for (size_t k = 0; k < train.size(); ++k)
      S.row(static_cast<Eigen::Index>(k)) = train[k];
    const RegionInterlineation naive = region_interlineation(c.boundary, lines6, lines6, c.w);
    const auto errors = [&](const RegionInterlineation& O) {
      double mx = 0, ss = 0;
      for (const Vector2d& p : check) {
        const double e = evaluate(O, p) - c.w(p);
        mx = std::max(mx, std::abs(e));
        ss += e * e;
      }
      return std::make_pair(mx, std::sqrt(ss / static_cast<double>(check.size())));
    };
    const auto [naive_max, naive_rms] = errors(naive);
    const RegionInterlineation ls = fit_free_traces(naive, c.w, S, TraceCriterion::least_squares);
    const RegionInterlineation mm = fit_free_traces(naive, c.w, S, TraceCriterion::min_max);
    const auto [ls_max, ls_rms] = errors(ls);
    const auto [mm_max, mm_rms] = errors(mm);
    INFO(c.name << ": max |Ou - w| naive " << naive_max << " least squares " << ls_max
                << " min-max " << mm_max << "; rms " << naive_rms << " " << ls_rms << " "
                << mm_rms);
    // Measured ratios 0.51-0.89 (rms, least squares) and 0.53-0.84 (max, min-max).
    CHECK(ls_rms < 0.95 * naive_rms);
    CHECK(mm_max < 0.9 * naive_max);
    // Still the implicit equation: 0 on dG (chord ends of random lines).
    double on_boundary = 0;
    for (int k = 0; k < 20; ++k)
      for (int axis = 0; axis < 2; ++axis) {
        const double pos = 1.2 * (U(rng) / 1.5);
        for (double s : c.boundary.chords(axis, pos)) {
          Vector2d p;
          p(axis) = pos;
          p(1 - axis) = s;
          on_boundary = std::max(on_boundary, std::abs(evaluate(mm, p)));
        }
      }
    CHECK(on_boundary <= 1e-12);
  }
}
