// Coordinate transforms, folding symmetry and blending on a frame: digest 000 T15-T17 and the
// defining property of each transform (the transformed body at the moved point equals the
// original at the point).
#include "rf_eval.h"

#include "interlin/interflatation/rfunctions/folding.h"
#include "interlin/interflatation/rfunctions/frame_blending.h"
#include "interlin/interflatation/rfunctions/primitives.h"
#include "interlin/interflatation/rfunctions/r_operations.h"
#include "interlin/interflatation/rfunctions/transforms.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

using namespace interlin;
using namespace interlin::rf;
using std::numbers::pi;
using test::gradient_at;
using test::value_at;

namespace {

const Expr X = Expr::x(), Y = Expr::y(), Z = Expr::z();
constexpr double kPrinted = 5e-8; // the digests print 7 decimals

// An asymmetric test body: an ellipsoid off the origin.
Expr lump() {
  return ellipsoid(X - 0.2, Y + 0.1, Z - 0.05, 0.5, 0.3, 0.2);
}

} // namespace

TEST_CASE("Translational folding functions: digest 000 T15", "[rf][folding]") {
  const ImplicitFunction m = test::compiled(mu(X, 2)), m4 = test::compiled(mu_fourier(X, 2, 4));
  const double t[] = {0.5, 1, 1.5, 2, -0.3, 3.7};
  const double e[] = {0.5, 1, 0.5, 0, -0.3, -0.3};
  for (int i = 0; i < 6; ++i)
    CHECK(value_at(m, t[i], 0) == Approx(e[i]).epsilon(0).margin(1e-14));
  CHECK(value_at(m4, 0.5, 0) == Approx(0.4982456).epsilon(0).margin(kPrinted));
  CHECK(value_at(m4, 1, 0) == Approx(0.9495978).epsilon(0).margin(kPrinted));
  CHECK(value_at(m4, -0.3, 0) == Approx(-0.3045505).epsilon(0).margin(kPrinted));
  CHECK(value_at(mu_fourier(X, 2, 50), 1, 0) == Approx(0.9959473).epsilon(0).margin(kPrinted));
  // slope at a copy: 1 exactly, (4/pi)(1 - 1/3 + 1/5 - 1/7) = 0.92158 for N = 4 (T16)
  CHECK(gradient_at(m, 0, 0).x() == Approx(1).epsilon(0).margin(1e-15));
  CHECK(gradient_at(m4, 0, 0).x() ==
        Approx(4 / pi * (1 - 1.0 / 3 + 1.0 / 5 - 1.0 / 7)).epsilon(0).margin(1e-15));
  CHECK(gradient_at(m4, 0, 0).x() == Approx(0.92158).epsilon(0).margin(5e-6));
}

TEST_CASE("Cyclic folding functions: digest 000 T16", "[rf][folding]") {
  const ImplicitFunction m = test::compiled(mu_cyclic(X, 24));
  const ImplicitFunction m4 = test::compiled(mu_cyclic_fourier(X, 24, 4));
  CHECK(value_at(m, pi / 24, 0) == Approx(pi / 24).epsilon(0).margin(1e-15));
  CHECK(value_at(m, pi / 24, 0) == Approx(0.1308997).epsilon(0).margin(kPrinted));
  CHECK(value_at(m, pi / 12, 0) == Approx(0).epsilon(0).margin(1e-15));
  CHECK(value_at(m, pi / 48, 0) == Approx(0.0654498).epsilon(0).margin(kPrinted));
  CHECK(value_at(m4, pi / 24, 0) == Approx(0.1243021).epsilon(0).margin(kPrinted));
  CHECK(value_at(m4, pi / 48, 0) == Approx(0.0652202).epsilon(0).margin(kPrinted));
  CHECK(value_at(m4, 0.05, 0) == Approx(0.0509157).epsilon(0).margin(kPrinted));
  // the thesis's program: coefficient 8/(pi n) with pi = 3.1415 (seed 000 Appendix B)
  CHECK(value_at(mu_cyclic_fourier(X, 24, 4) * (pi / 3.1415), pi / 24, 0) ==
        Approx(0.1243057).epsilon(0).margin(kPrinted));
}

TEST_CASE("Translational folding repeats the copy, the asymmetric form does not mirror it",
          "[rf][folding]") {
  // A disk of radius 0.4 at the origin repeated with period h = 2 (Theorem 1).
  const Expr disk = circle(X, Y, 0.4);
  const ImplicitFunction f = test::compiled(fold_x(disk, 2)), d = test::compiled(disk);
  // An off-centre disk: Theorem 1 mirrors the odd copies, Theorem 2 (2.39) translates all.
  const Expr off = circle(X - 0.3, Y, 0.4);
  const ImplicitFunction mirrored = test::compiled(fold_x(off, 2));
  const ImplicitFunction shifted = test::compiled(fold_x_asym(off, 2));
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  for (int k = -3; k <= 3; ++k)
    for (int i = 0; i < 30; ++i) {
      const double dx = u(rng), y = u(rng) * 0.6;
      CHECK(value_at(f, 2 * k + dx, y) == Approx(value_at(d, dx, y)).epsilon(0).margin(1e-12));
      const double original = value_at(test::compiled(off), dx, y);
      if (std::abs(original) > 1e-9) {
        CHECK((value_at(shifted, 2 * k + dx, y) > 0) == (original > 0));
        const double mirror_dx = (k % 2) ? -dx : dx; // odd copies of Theorem 1 are mirrored
        CHECK((value_at(mirrored, 2 * k + mirror_dx, y) > 0) == (original > 0));
      }
    }
  // finitely many copies (2.41): h = 3, l = 12 gives copies at 0, 3, ..., 12 only
  const ImplicitFunction fin = test::compiled(fold_x_finite(disk, 3, 12.0));
  for (int k = 0; k <= 4; ++k)
    CHECK(value_at(fin, 3.0 * k, 0) > 0);
  CHECK(value_at(fin, -3, 0) < 0);
  CHECK(value_at(fin, 15, 0) < 0);
  CHECK(value_at(fin, 1.5, 0) < 0);
}

TEST_CASE("Cyclic folding: n rotated copies (Theorems 4 and 5)", "[rf][folding]") {
  const int n = 6;
  const Expr sym = ellipse(X - 2, Y, 0.5, 0.3);    // symmetric about y = 0
  const Expr asym = circle(X - 2, Y - 0.15, 0.25); // not symmetric
  const ImplicitFunction fs = test::compiled(fold_cyclic(sym, n));
  const ImplicitFunction fa = test::compiled(fold_cyclic_asym(asym, n));
  const ImplicitFunction s0 = test::compiled(sym), a0 = test::compiled(asym);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.6, 0.6);
  for (int k = 0; k < n; ++k) {
    const Eigen::Rotation2Dd R(2 * pi * k / n);
    for (int i = 0; i < 30; ++i) {
      const Eigen::Vector2d p(2 + u(rng), u(rng) * 0.8), q = R * p;
      CHECK(value_at(fs, q.x(), q.y()) ==
            Approx(value_at(s0, p.x(), p.y())).epsilon(0).margin(1e-12));
      const double original = value_at(a0, p.x(), p.y());
      if (std::abs(original) > 1e-9)
        CHECK((value_at(fa, q.x(), q.y()) > 0) == (original > 0));
    }
  }
  // The Fourier form with N = 4 keeps the copy count: 2n sign changes around the circle r = 2.
  const ImplicitFunction f4 = test::compiled(fold_cyclic_fourier(sym, n, 4));
  int changes = 0;
  for (int i = 0; i < 3600; ++i) {
    const double t0 = 2 * pi * i / 3600, t1 = 2 * pi * (i + 1) / 3600;
    changes += (value_at(f4, 2 * std::cos(t0), 2 * std::sin(t0)) > 0) !=
               (value_at(f4, 2 * std::cos(t1), 2 * std::sin(t1)) > 0);
  }
  CHECK(changes == 2 * n);
}

TEST_CASE("Translation, rotation and scaling move the body", "[rf][transforms]") {
  const Expr b = lump();
  const ImplicitFunction f0 = test::compiled(b);
  const Eigen::Vector3d d(0.3, -1.1, 0.7), axis = Eigen::Vector3d(1, 2, -0.5).normalized();
  const double angle = 0.83, s = 1.7;
  const ImplicitFunction tr = test::compiled(translate(b, d.x(), d.y(), d.z()));
  const ImplicitFunction rx = test::compiled(rotate_x(b, angle));
  const ImplicitFunction ry = test::compiled(rotate_y(b, angle));
  const ImplicitFunction rz = test::compiled(rotate_z(b, angle));
  const ImplicitFunction ra = test::compiled(rotate(b, axis.x(), axis.y(), axis.z(), angle));
  const ImplicitFunction sc = test::compiled(scale(b, s));
  const Eigen::Matrix3d Rx = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Ra = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), u(rng));
    const double v = value_at(f0, p.x(), p.y(), p.z());
    auto at = [&](const ImplicitFunction& f, const Eigen::Vector3d& q) {
      return value_at(f, q.x(), q.y(), q.z());
    };
    CHECK(at(tr, p + d) == Approx(v).epsilon(0).margin(1e-13));
    CHECK(at(rx, Rx * p) == Approx(v).epsilon(0).margin(1e-13));
    CHECK(at(ry, Ry * p) == Approx(v).epsilon(0).margin(1e-13));
    CHECK(at(rz, Rz * p) == Approx(v).epsilon(0).margin(1e-13));
    CHECK(at(ra, Ra * p) == Approx(v).epsilon(0).margin(1e-13));
    CHECK(at(sc, s * p) ==
          Approx(s * v).epsilon(0).margin(1e-13)); // s F(x/s): distances scale by s
    // a normalised body stays normalised: equal gradient lengths at corresponding points
    const Eigen::Vector3d q = s * p;
    CHECK(gradient_at(sc, q.x(), q.y(), q.z()).norm() ==
          Approx(gradient_at(f0, p.x(), p.y(), p.z()).norm()).epsilon(0).margin(1e-12));
  }
}

TEST_CASE("Twist about an axis turns each section by phi(z)", "[rf][transforms]") {
  const Expr section = rectangle(X - 0.5, Y, 0.3, 0.1); // a bar off the axis
  const double alpha = 1.3;
  const ImplicitFunction tw = test::compiled(twist_z(section, alpha * Z));
  const ImplicitFunction f0 = test::compiled(section);
  const ImplicitFunction twx = test::compiled(twist_x(rectangle(Y - 0.5, Z, 0.3, 0.1), alpha * X));
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < 100; ++i) {
    const double x = u(rng), y = u(rng), z = 2 * u(rng);
    const Eigen::Vector2d q = Eigen::Rotation2Dd(alpha * z) * Eigen::Vector2d(x, y);
    CHECK(value_at(tw, q.x(), q.y(), z) == Approx(value_at(f0, x, y, 0)).epsilon(0).margin(1e-13));
    // about x: (y, z) turn by alpha x
    const Eigen::Vector2d r = Eigen::Rotation2Dd(alpha * z) * Eigen::Vector2d(x, y);
    CHECK(value_at(twx, z, r.x(), r.y()) == Approx(value_at(f0, x, y, 0)).epsilon(0).margin(1e-13));
  }
}

TEST_CASE("Revolution (2.46), smooth revolution (2.47), similar sections, cone, loft (2.48)",
          "[rf][transforms]") {
  // profile in (x, y): a disk of radius 0.3 at height 1 -> a torus about the x axis
  const Expr prof = circle(X, Y - 1, 0.3);
  const ImplicitFunction rev = test::compiled(revolve_x(prof)), p0 = test::compiled(prof);
  for (double t : {0.0, 0.7, 2.0, 4.0})
    for (double x : {-0.2, 0.1})
      CHECK(value_at(rev, x, 1.1 * std::cos(t), 1.1 * std::sin(t)) ==
            Approx(value_at(p0, x, 1.1)).epsilon(0).margin(1e-14));
  const ImplicitFunction revz = test::compiled(revolve_z(prof)); // about z: u radial, v = z
  CHECK(value_at(revz, 0.1 * std::cos(1.0), 0.1 * std::sin(1.0), 1.2) ==
        Approx(value_at(p0, 0.1, 1.2)).epsilon(0).margin(1e-14));
  // smooth revolution: the profile 1 - x^2 - 2y crosses the axis with slope -2; revolved plainly
  // it has a cone point (one-sided slope -2 in every direction), smoothly it has slope 0
  const Expr slab = 1 - X * X - 2 * Y;
  const double h = 1e-6;
  const ImplicitFunction plain = test::compiled(revolve_x(slab)),
                         smooth = test::compiled(revolve_x_smooth(slab));
  CHECK((value_at(plain, 0.2, 0, h) - value_at(plain, 0.2, 0, 0)) / h ==
        Approx(-2).epsilon(0).margin(1e-6));
  CHECK((value_at(smooth, 0.2, 0, h) - value_at(smooth, 0.2, 0, 0)) / h ==
        Approx(0).epsilon(0).margin(1e-4));
  CHECK(gradient_at(smooth, 0.2, 0, 0).tail<2>().norm() == Approx(0).epsilon(0).margin(1e-12));
  // similar sections: radius 1/k(z) with k = 1 + z
  const ImplicitFunction sim = test::compiled(similar_z(circle(X, Y, 1.0), 1 + Z));
  CHECK(value_at(sim, 1 / 1.5, 0, 0.5) == Approx(0).epsilon(0).margin(1e-14));
  CHECK(value_at(sim, 0.6, 0, 0.5) > 0);
  // cone over the unit circle with apex (0, 0, 2): radius (2 - z)/2
  const ImplicitFunction cm = test::compiled(cone_map(circle(X, Y, 1.0), 0.0, 0.0, 2.0));
  CHECK(value_at(cm, 0.75, 0, 0.5) == Approx(0).epsilon(0).margin(1e-14));
  CHECK(value_at(cm, 0, 0.7, 0.5) > 0);
  CHECK(value_at(cm, 0, 0.8, 0.5) < 0);
  // loft (2.48): rectangle a x b at z = 0 to c x d at z = H, R0 of un-normalised strips
  const double a = 2, b = 1, c = 1, d = 3, H = 4;
  const Expr t = Z / H;
  const Expr loft = and0(pow(lerp(a, c, t), 2) - X * X, pow(lerp(b, d, t), 2) - Y * Y);
  const ImplicitFunction lf = test::compiled(loft);
  CHECK(value_at(lf, a, 0, 0) == Approx(0).epsilon(0).margin(1e-14));
  CHECK(value_at(lf, 0, d, H) == Approx(0).epsilon(0).margin(1e-14));
  CHECK(value_at(lf, 1.5 - 1e-3, 0, 2) > 0); // half-width (a + c)/2 = 1.5 at mid-height
  CHECK(value_at(lf, 1.5 + 1e-3, 0, 2) < 0);
}

TEST_CASE("Blended fuselage on a segment frame: digest 000 T17", "[rf][frame]") {
  // (2.49) with a = 5, a1 = 5.2, a2 = 5, p1 = 20, p2 = 0, revolved about x
  const ImplicitFunction wp =
      test::compiled(blend_segment(X, hypot(Y, Z), 5.0, 5.2, 5.0, 20.0, 0.0));
  CHECK(value_at(wp, 0, 0, 0) == Approx(1.3).epsilon(0).margin(1e-15));
  const double xs[] = {-4, -2, 0, 2, 4, 5};
  const double rs[] = {0.4598368, 1.0700919, 1.2771740, 1.1076225, 0.5395121, 0.0998755};
  for (int i = 0; i < 6; ++i) { // the surface radius: wp(x, r, 0) = 0, by bisection
    double lo = 0, hi = 3;
    REQUIRE(value_at(wp, xs[i], lo, 0) > 0);
    REQUIRE(value_at(wp, xs[i], hi, 0) < 0);
    for (int it = 0; it < 100; ++it) {
      const double m = 0.5 * (lo + hi);
      (value_at(wp, xs[i], m, 0) > 0 ? lo : hi) = m;
    }
    CHECK(lo == Approx(rs[i]).epsilon(0).margin(kPrinted));
    // radially symmetric about the x axis
    CHECK(value_at(wp, xs[i], lo * std::cos(1.1), lo * std::sin(1.1)) ==
          Approx(0).epsilon(0).margin(1e-12));
  }
}

TEST_CASE("Arc frame (reconstruction of seed 000 §2.9's arc): zero exactly on the arc",
          "[rf][frame]") {
  const double R = 2, beta = 0.6;
  const ImplicitFunction f = test::compiled(arc_frame(X, Y, R, beta));
  for (double t : {-0.55, -0.3, 0.0, 0.2, 0.59}) {
    CHECK(value_at(f, R * std::cos(t), R * std::sin(t)) == Approx(0).epsilon(0).margin(1e-12));
    // normal to the arc inside its span: |R - r| (the wedge selector is large there)
    if (std::abs(t) < 0.3)
      CHECK(value_at(f, 2.1 * std::cos(t), 2.1 * std::sin(t)) ==
            Approx(0.1).epsilon(0).margin(1e-3));
  }
  // the circle beyond the arc's ends is not part of the frame
  for (double t : {0.8, 1.5, -1.0, 3.0})
    CHECK(value_at(f, R * std::cos(t), R * std::sin(t)) > 0.1);
  CHECK_THROWS_AS(arc_frame(X, Y, R, 3.5), std::invalid_argument);
}
