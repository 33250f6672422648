// Normalised primitives, normalisation, pieces of curves and walls: digest 000 T9-T11, T13,
// T14, closed-form gradients, and |grad| = 1 on the boundary of every normalised primitive.
#include "rf_eval.h"

#include "interlin/interflatation/rfunctions/normalization.h"
#include "interlin/interflatation/rfunctions/primitives.h"
#include "interlin/interflatation/rfunctions/r_operations.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <optional>
#include <random>

using namespace interlin;
using namespace interlin::rf;
using test::gradient_at;
using test::value_at;

namespace {

const Expr X = Expr::x(), Y = Expr::y(), Z = Expr::z();
constexpr double kPrinted = 5e-8; // the digests print 7 decimals

// A point of {F = 0} on the ray from `inside` (F > 0) in direction d, by bisection to 1e-14;
// none when the ray stays inside up to `reach` (unbounded primitives).
std::optional<Eigen::Vector3d> boundary_point(const ImplicitFunction& f,
                                              const Eigen::Vector3d& inside,
                                              const Eigen::Vector3d& d, double reach) {
  double lo = 0, hi = reach;
  auto F = [&](double t) {
    const Eigen::Vector3d p = inside + t * d;
    return test::value_at(f, p.x(), p.y(), p.z());
  };
  REQUIRE(F(lo) > 0);
  if (F(hi) >= 0)
    return std::nullopt;
  while (hi - lo > 1e-14 * reach) {
    const double m = 0.5 * (lo + hi);
    (F(m) > 0 ? lo : hi) = m;
  }
  return inside + 0.5 * (lo + hi) * d;
}

} // namespace

TEST_CASE("Rectangle (2.21) with a = 2, b = 1: digest 000 T9", "[rf][primitives]") {
  const Expr w = and0(4 - X * X, 1 - Y * Y); // the un-normalised form of the worked example
  CHECK(value_at(w, 0, 0) == Approx(5 - std::sqrt(17.0)).epsilon(0).margin(1e-15));
  CHECK(value_at(w, 0, 0) == Approx(0.8768944).epsilon(0).margin(kPrinted));
  CHECK(value_at(w, 2, 0) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(w, 0, 1) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(w, 2.5, 0) < 0);
  // the normalised rectangle has the same zero set
  const ImplicitFunction r = test::compiled(rectangle(X, Y, 2.0, 1.0));
  CHECK(value_at(r, 2, 0) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(r, 0, 1) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(r, 1, 0.5) > 0);
  CHECK(value_at(r, 2.5, 0) < 0);
}

TEST_CASE("Normalised circle and strip, both forms: digest 000 T10, T11", "[rf][primitives]") {
  const double r[] = {0, 1, 2, 3};
  const double c1[] = {1, 0.75, 0, -1.25};
  const double c2[] = {1.1547005, 0.8320503, 0, -1.0910895};
  for (int i = 0; i < 4; ++i) {
    CHECK(value_at(circle(X, Y, 2.0), r[i], 0) == Approx(c1[i]).epsilon(0).margin(1e-15));
    CHECK(value_at(circle_smooth(X, Y, 2.0), 0, r[i]) == Approx(c2[i]).epsilon(0).margin(kPrinted));
  }
  for (const Expr& c : {circle(X, Y, 2.0), circle_smooth(X, Y, 2.0)}) // T10: |grad| = 1 at r = R
    CHECK(gradient_at(c, 2 * std::cos(0.7), 2 * std::sin(0.7)).norm() == Approx(1).epsilon(0).margin(1e-15));
  const double yv[] = {0, 0.5, 1, 2};
  const double s1[] = {0.5, 0.375, 0, -1.5};
  const double s2[] = {0.5773503, 0.4160251, 0, -1.1338934};
  for (int i = 0; i < 4; ++i) {
    CHECK(value_at(strip(Y, 1.0), 0, yv[i]) == Approx(s1[i]).epsilon(0).margin(1e-15));
    CHECK(value_at(strip_smooth(Y, 1.0), 0, yv[i]) == Approx(s2[i]).epsilon(0).margin(kPrinted));
  }
  // strip_smooth tends to -|u| as b -> 0 (seed 000 (2.31))
  CHECK(value_at(strip_smooth(Y, 1e-8), 0, 0.3) == Approx(-0.3).epsilon(0).margin(1e-8));
}

TEST_CASE("Gradients of primitives equal their closed forms", "[rf][primitives][gradient]") {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-2, 2);
  const ImplicitFunction sph = test::compiled(sphere(X, Y, Z, 1.5));
  const ImplicitFunction tor = test::compiled(torus(X, Y, Z, 1.2, 0.4));
  const ImplicitFunction lay = test::compiled(layer(Z, -0.5, 1.0));
  const ImplicitFunction hs = test::compiled(halfspace(X, Y, Z, 1.0, -2.0, 2.0, 0.5));
  for (int i = 0; i < 200; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng);
    // sphere (R^2 - r^2)/(2R): grad = -p / R
    CHECK((gradient_at(sph, x, y, z) - Eigen::Vector3d(x, y, z) / -1.5).norm() < 1e-15);
    // torus (r^2 - (rho - R)^2 - z^2)/(2r): grad = -((rho - R) p_xy / rho, z) / r
    const double rho = std::hypot(x, y);
    const Eigen::Vector3d gt(-(rho - 1.2) * x / rho / 0.4, -(rho - 1.2) * y / rho / 0.4, -z / 0.4);
    CHECK((gradient_at(tor, x, y, z) - gt).norm() < 1e-13);
    // layer (z - a)(b - z)/(b - a): d/dz = (a + b - 2z)/(b - a)
    CHECK((gradient_at(lay, x, y, z) - Eigen::Vector3d(0, 0, (0.5 - 2 * z) / 1.5)).norm() < 1e-15);
    CHECK((gradient_at(hs, x, y, z) - Eigen::Vector3d(1, -2, 2) / 3).norm() < 1e-15);
  }
}

TEST_CASE("|grad| = 1 on the boundary of every normalised primitive",
          "[rf][primitives][normalised]") {
  // Boundary points from 50 random directions out of an interior point, by bisection; tolerance
  // 1e-9 covers the bisection's 1e-14 offset times the largest second derivative met (1e4, near
  // the corners of the R0 compositions).
  struct Case {
    const char* name;
    Expr e;
    Eigen::Vector3d inside;
    bool planar; // a 2D primitive (infinite along z): rays in the plane z = 0
  };
  const Case cases[] = {
      {"strip", strip(X - 0.2, 0.7), {0.2, 0, 0}, true},
      {"layer", layer(Y, -0.3, 0.9), {0, 0.1, 0}, true},
      {"halfplane", halfplane(X, Y, 1.0, 2.0, 0.5), {1, 1, 0}, true},
      {"circle", circle(X - 0.3, Y, 1.1), {0.3, 0, 0}, true},
      {"circle_smooth", circle_smooth(X, Y + 0.2, 0.8), {0, -0.2, 0}, true},
      {"rectangle", rectangle(X, Y, 1.2, 0.6), {0, 0, 0}, true},
      {"ellipse", ellipse(X, Y, 1.5, 0.5), {0, 0, 0}, true},
      {"halfspace", halfspace(X, Y, Z, 1.0, -1.0, 2.0, 1.0), {0, 0, 0}, false},
      {"sphere", sphere(X, Y, Z - 0.1, 1.3), {0, 0, 0.1}, false},
      {"cuboid", cuboid(X, Y, Z, 1.0, 0.5, 0.8), {0, 0, 0}, false},
      {"cylinder", cylinder(X, Y, Z, 0.7, 1.1), {0, 0, 0}, false},
      {"cone", cone(X, Y, Z, 1.0, 2.0), {0, 0, 0.5}, false},
      {"torus", torus(X, Y, Z, 1.5, 0.5), {1.5, 0, 0}, false},
      {"ellipsoid", ellipsoid(X, Y, Z, 1.5, 1.0, 0.6), {0, 0, 0}, false},
  };
  std::mt19937 rng(2);
  std::normal_distribution<double> g;
  for (const Case& c : cases) {
    INFO(c.name);
    const ImplicitFunction f = test::compiled(c.e);
    int found = 0;
    for (int i = 0; i < 50; ++i) {
      Eigen::Vector3d d(g(rng), g(rng), g(rng));
      if (c.planar)
        d.z() = 0;
      d.normalize();
      if (c.name == std::string("torus")) // stay in the tube's meridian half-plane
        d = Eigen::Vector3d(d.x(), 0, d.z()).normalized();
      const auto p = boundary_point(f, c.inside, d, 10);
      if (!p)
        continue;
      ++found;
      CHECK(gradient_at(f, p->x(), p->y(), p->z()).norm() == Approx(1).epsilon(0).margin(1e-9));
    }
    CHECK(found >= 15); // every primitive met on enough rays
  }
}

TEST_CASE("Normal function of a segment is the distance to it", "[rf][primitives]") {
  const ImplicitFunction s = test::compiled(segment(X, Y, -1, 0.5, 2, 1.5));
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-4, 4);
  const Eigen::Vector2d a(-1, 0.5), b(2, 1.5);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector2d p(u(rng), u(rng));
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    CHECK(value_at(s, p.x(), p.y()) == Approx((p - a - t * (b - a)).norm()).epsilon(0).margin(1e-13));
  }
}

TEST_CASE("Normalisation (2.26) of R^2 - x^2 - y^2: digest 000 T14", "[rf][normalised]") {
  const Expr w1 = 4 - X * X - Y * Y, w = normalize(w1);
  const ImplicitFunction f = test::compiled(w), f1 = test::compiled(w1);
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-3, 3), ang(0, 2 * M_PI);
  for (int i = 0; i < 100; ++i) {
    const double t = ang(rng);
    CHECK(gradient_at(f, 2 * std::cos(t), 2 * std::sin(t)).norm() == Approx(1).epsilon(0).margin(1e-14));
    const double x = u(rng), y = u(rng);
    CHECK((value_at(f, x, y) > 0) == (value_at(f1, x, y) > 0)); // sign unchanged
    // closed form: w1 / sqrt(w1^2 + 4 r^2)
    const double v1 = 4 - x * x - y * y;
    CHECK(value_at(f, x, y) == Approx(v1 / std::sqrt(v1 * v1 + 4 * (x * x + y * y))).epsilon(0).margin(1e-15));
  }
  // (2.27): w1 / |grad w1| = (4 - r^2) / (2r)
  CHECK(value_at(normalize_by_gradient(w1), 1, 0) == Approx(1.5).epsilon(0).margin(1e-15));
}

TEST_CASE("Piece of a curve (2.34): digest 000 T13", "[rf][piece]") {
  // f = sqrt(y^2 + z^2), phi = (a^2 - x^2)/(2a), a = 5
  const Expr w = piece(sqrt(Y * Y + Z * Z), (25 - X * X) / 10);
  const double pts[][3] = {{0, 0.1, 0.1000000}, {0, 1, 1.0046253}, {0, 3, 4.5496194},    {5, 0, 0},
                           {6, 0, 1.1},         {7, 0, 2.4},       {5.5, 0.5, 0.7457059}};
  for (const auto& p : pts)
    CHECK(value_at(w, p[0], p[1]) == Approx(p[2]).epsilon(0).margin(kPrinted));
  CHECK(value_at(w, 2, 0) == 0.0); // zero on the piece
}

TEST_CASE("Walls of a given thickness", "[rf][wall]") {
  const Expr s = sphere(X, Y, Z, 1.0);
  const ImplicitFunction w = test::compiled(wall(s, 0.1)), iw = test::compiled(inner_wall(s, 0.1));
  // sphere (1 - r^2)/2 is 0.1 at r = sqrt(0.8); the wall |s| <= 0.1 spans r in [sqrt(0.8),
  // sqrt(1.2)]
  CHECK(value_at(w, std::sqrt(0.8), 0, 0) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(w, std::sqrt(1.2), 0, 0) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(w, 1, 0, 0) == Approx(0.1).epsilon(0).margin(1e-15));
  CHECK(value_at(w, 0.5, 0, 0) < 0);
  // inner wall: 0 <= s <= 0.1, normalised on both faces
  CHECK(value_at(iw, 0.95, 0, 0) > 0);
  CHECK(value_at(iw, 0.5, 0, 0) < 0);
  CHECK(value_at(iw, 1.05, 0, 0) < 0);
  CHECK(gradient_at(iw, 1, 0, 0).norm() == Approx(1).epsilon(0).margin(1e-15));
  CHECK(gradient_at(iw, std::sqrt(0.8), 0, 0).norm() == Approx(std::sqrt(0.8)).epsilon(0).margin(1e-15));
}
