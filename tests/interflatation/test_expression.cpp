// The expression compiler and evaluator: gradients (dual numbers) against finite differences and
// against graph differentiation, batch against single points, two threads against one,
// undefined values, constant folding and common sub-expressions.
#include "rf_eval.h"

#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/interflatation/rfunctions/model_expression.h"
#include "interlin/interflatation/rfunctions/normalization.h"
#include "interlin/interflatation/rfunctions/r_operations.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <thread>

using namespace interlin;
using namespace interlin::rf;
using test::gradient_at;
using test::value_at;

namespace {

const Expr X = Expr::x(), Y = Expr::y(), Z = Expr::z();

std::string model_path(const std::string& name) {
  return std::string(INTERLIN_DATA_DIR) + "/models/" + name;
}

// n random points in the box of f.
Points3 random_points(const ImplicitFunction& f, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  Points3 P(n, 3);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      P(i, c) = f.box.min()(c) + u(rng) * (f.box.max()(c) - f.box.min()(c));
  return P;
}

// A smooth expression touching every elementary operation away from its singularities.
Expr smooth_mix() {
  const Expr r2 = X * X + Y * Y + Z * Z;
  Expr e = sin(X * Y) + cos(2 * Z) * exp(-r2) + log(1 + r2) + atan2(Y + 3, X - 4);
  e = e + tan(0.3 * X) + asin(0.4 * sin(Y)) + acos(0.3 * cos(Z)) + atan(X * Z);
  e = e + pow(2 + sin(X), 1.5 + 0.2 * Y) + sqrt(2 + X * Y) / (3 + cos(Z)) + hypot(X + 2, Y);
  e = e + and0(X + 5, Y + 4) + or0(X - 5, Z - 4) + and_alpha(X + 3, 4 - Y, 0.3);
  return e + pow(3 + Z, 3) - pow(1.5 + X, -2) + abs(X + 9) * sign(Y + 9);
}

} // namespace

TEST_CASE("Gradients by dual numbers match central differences on a smooth mix", "[rf][gradient]") {
  const ImplicitFunction f = test::compiled(smooth_mix());
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const Eigen::Vector3d g = gradient_at(f, p.x(), p.y(), p.z());
    const Eigen::Vector3d fd = test::central_difference(f, p, 1e-5);
    // truncation h^2 |F'''| / 6 ~ 1e-9 and round-off eps |F| / h ~ 1e-10 for this mix
    CHECK((g - fd).norm() < 1e-7 * (1 + g.norm()));
  }
}

TEST_CASE("Dual-number gradients of the shipped models: graph derivative and finite differences",
          "[rf][gradient]") {
  for (const char* name : {"impeller.rf", "uav.rf", "car.rf", "valve.rf", "naca0011_plate.rf"}) {
    INFO(name);
    const ModelExpression m = load_model_expression(model_path(name));
    const ImplicitFunction f = compile(m.F, m.box);
    const Points3 P = random_points(f, 2000, 31);
    Eigen::VectorXd F(P.rows()), D(P.rows());
    Points3 G(P.rows(), 3);
    f.gradient(P, F, G);
    // Two independent implementations of the chain rule: the kernel's partials on dual numbers
    // and derivative() building expressions; they differ by round-off only.
    for (int c = 0; c < 3; ++c) {
      compile(derivative(m.F, c), m.box).value(P, D);
      for (Eigen::Index i = 0; i < P.rows(); ++i)
        CHECK(D(i) == Approx(G(i, c)).epsilon(0).margin(1e-9 * (1 + std::abs(G(i, c)))));
    }
    // Finite differences where the model is smooth around the point.
    const double h = 1e-6;
    int compared = 0;
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      const Eigen::Vector3d p = P.row(i).transpose();
      bool smooth = true;
      Eigen::Vector3d fd;
      for (int c = 0; c < 3; ++c) {
        Eigen::Vector3d a = p, b = p;
        a(c) += h;
        b(c) -= h;
        const double fa = value_at(f, a.x(), a.y(), a.z()), fb = value_at(f, b.x(), b.y(), b.z());
        const double fwd = (fa - F(i)) / h, bwd = (F(i) - fb) / h;
        // a kink within h (abs, min, an R0 corner, the polyline) shows as one-sided slopes
        // that differ by more than the h |F''| of a smooth function
        smooth = smooth && std::abs(fwd - bwd) < 1e-4 * (1 + std::abs(fwd));
        fd(c) = (fa - fb) / (2 * h);
      }
      if (!smooth)
        continue;
      ++compared;
      const Eigen::Vector3d g = G.row(i).transpose();
      // truncation h^2 |third derivative| / 6 and round-off eps |F| / h ~ 1e-10 for |F| < 1e6
      CHECK((g - fd).norm() < 1e-5 * (1 + g.norm()));
    }
    CHECK(compared > 1800); // kinks are rare
  }
}

TEST_CASE("derivative() builds exact derivatives, including second derivatives", "[rf][gradient]") {
  const Expr e = sin(X * Y) + Z * Z * Z;
  const Expr exx = derivative(derivative(e, 0), 0), exy = derivative(derivative(e, 0), 1);
  const ImplicitFunction fxx = test::compiled(exx), fxy = test::compiled(exy);
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 50; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng);
    CHECK(value_at(fxx, x, y, z) == Approx(-y * y * std::sin(x * y)).epsilon(0).margin(1e-14));
    CHECK(value_at(fxy, x, y, z) ==
          Approx(std::cos(x * y) - x * y * std::sin(x * y)).epsilon(0).margin(1e-13));
    const Eigen::Vector3d g = gradient_at(e, x, y, z);
    CHECK(value_at(derivative(e, 2), x, y, z) == Approx(g.z()).epsilon(0).margin(1e-13));
  }
  // the gradient of a normalised function needs second derivatives of the inner one:
  // duals on the expanded graph versus finite differences
  const ImplicitFunction n = test::compiled(normalize(X * X + 2 * Y * Y - Z + sin(Z)));
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const Eigen::Vector3d g = gradient_at(n, p.x(), p.y(), p.z());
    CHECK((g - test::central_difference(n, p, 1e-5)).norm() < 1e-7 * (1 + g.norm()));
  }
  CHECK_THROWS_AS(derivative(e, 3), std::invalid_argument);
}

TEST_CASE("Batch evaluation equals point-by-point evaluation, bit for bit", "[rf][batch]") {
  for (const char* name : {"impeller.rf", "uav.rf", "naca0011_plate.rf"}) {
    INFO(name);
    const ImplicitFunction f = load_model(model_path(name));
    const Points3 P = random_points(f, 1000, 41); // 1000: several blocks of 256 and a remainder
    Eigen::VectorXd F(P.rows()), FG(P.rows());
    Points3 G(P.rows(), 3);
    f.value(P, F);
    f.gradient(P, FG, G);
    for (Eigen::Index i = 0; i < P.rows(); ++i) {
      CHECK(value_at(f, P(i, 0), P(i, 1), P(i, 2)) == F(i));
      CHECK(FG(i) == F(i)); // the gradient pass computes the same values
      const Eigen::Vector3d g = gradient_at(f, P(i, 0), P(i, 1), P(i, 2));
      CHECK(g == G.row(i).transpose());
    }
  }
}

TEST_CASE("Two threads on disjoint halves give the single-thread result", "[rf][threads]") {
  const ImplicitFunction f = load_model(model_path("impeller.rf"));
  const Points3 P = random_points(f, 100000, 51);
  Eigen::VectorXd one(P.rows()), two(P.rows()), g1(P.rows()), g2(P.rows());
  Points3 G1(P.rows(), 3), G2(P.rows(), 3);
  f.value(P, one);
  f.gradient(P, g1, G1);
  const Eigen::Index half = P.rows() / 2, rest = P.rows() - half;
  std::thread a([&] {
    f.value(P.topRows(half), two.head(half));
    f.gradient(P.topRows(half), g2.head(half), G2.topRows(half));
  });
  std::thread b([&] {
    f.value(P.bottomRows(rest), two.tail(rest));
    f.gradient(P.bottomRows(rest), g2.tail(rest), G2.bottomRows(rest));
  });
  a.join();
  b.join();
  CHECK(one == two);
  CHECK(g1 == g2);
  CHECK(G1 == G2);
}

TEST_CASE("Undefined and infinite values become finite outputs", "[rf][robust]") {
  const double big = std::numeric_limits<double>::max();
  CHECK(value_at(sqrt(X), -1, 0) == -big); // undefined: outside
  CHECK(value_at(1 / X, 0, 0) == big);     // +inf clamped
  CHECK(value_at(-1 / X, 0, 0) == -big);
  CHECK(value_at(log(X), 0, 0) == -big);
  CHECK(gradient_at(sqrt(X), -1, 0).allFinite());
  CHECK(gradient_at(1 / X, 0, 0).allFinite());
  CHECK(gradient_at(hypot(X, Y), 0, 0) == Eigen::Vector3d::Zero()); // singular factor taken as 0
  CHECK(gradient_at(and0(X, Y), 0, 0) == Eigen::Vector3d(1, 1, 0));
  // sizes are checked
  const ImplicitFunction f = test::compiled(X);
  Points3 P(3, 3);
  Eigen::VectorXd F(2);
  CHECK_THROWS_AS(f.value(P, F), std::invalid_argument);
}

TEST_CASE("Constant folding, common sub-expressions, substitution", "[rf][expression]") {
  CHECK((Expr(2) * 3 + 1).constant_value() == 7);
  CHECK(and0(Expr(3.0), Expr(4.0)).constant_value() == Approx(2).epsilon(0).margin(1e-15));
  CHECK_THROWS_AS(X.constant_value(), std::invalid_argument);
  CHECK((X * 1 + 0).node() == X.node()); // identities are dropped
  // sqrt(x^2 + y^2) built twice is one sub-expression of the compiled program
  const Expr a = sqrt(X * X + Y * Y), b = sqrt(X * X + Y * Y);
  CHECK(operation_count(a + b) == operation_count(a) + 1);
  // substitution is simultaneous: (x, y) -> (y, x) swaps
  const Expr s = substitute(X - 2 * Y, Y, X, Z);
  CHECK(value_at(s, 1, 10) == Approx(10 - 2).epsilon(0).margin(0));
}
