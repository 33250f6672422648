// Knot insertion changes the basis, never the curve.
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"
#include "interlin/splines/parameterization.h"

#include "support/test_surfaces.h"

#include <catch2/catch.hpp>
#include <random>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

BSplineCurve random_clamped(std::mt19937& rng, int p, Index n) {
  BSplineCurve c;
  c.degree = p;
  c.knots = test::random_clamped_knots(rng, p, n, 0.0, 1.0);
  c.ctrl = MatrixXd::Random(n, 3);
  return c;
}

// Max distance between two curves over the common domain [a, b] (dense sampling).
double curve_difference(const BSplineCurve& a, const BSplineCurve& b, double u0, double u1) {
  const VectorXd u = VectorXd::LinSpaced(2001, u0, u1);
  return (evaluate(a, u) - evaluate(b, u)).cwiseAbs().maxCoeff();
}

} // namespace

TEST_CASE("refine_knots keeps the curve (random curves, repeated insertions)", "[splines][knots]") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int p = 1; p <= 5; ++p) {
    const BSplineCurve c = random_clamped(rng, p, p + 6);
    std::vector<double> X;
    for (int i = 0; i < 15; ++i)
      X.push_back(unit(rng));
    X.push_back(X[3]);           // a repeat
    X.push_back(c.knots(p + 2)); // an existing knot
    std::sort(X.begin(), X.end());
    const BSplineCurve r = refine_knots(c, Eigen::Map<VectorXd>(X.data(), Index(X.size())));
    CHECK(r.ctrl.rows() == c.ctrl.rows() + Index(X.size()));
    // Convex combinations of O(1) control points: round-off level.
    CHECK(curve_difference(c, r, 0, 1) < 1e-14 * 50);
  }
}

TEST_CASE("periodic_to_clamped keeps the closed curve for any window start", "[splines][knots]") {
  MatrixXd P(17, 3);
  for (Index i = 0; i < P.rows(); ++i) {
    const double t = 2 * M_PI * i / P.rows();
    P.row(i) << std::cos(t) * (1 + 0.3 * std::sin(3 * t)), std::sin(t), 0.2 * std::cos(2 * t);
  }
  const VectorXd u = chord_parameters(P, true);
  for (int p : {2, 3, 4, 5}) {
    const BSplineCurve c = interpolate_closed(P, u, p);
    for (double a : {0.0, u(5), 0.123, 0.999}) {
      const BSplineCurve k = periodic_to_clamped(c, a);
      CHECK(!k.periodic);
      CHECK(k.knots(0) == k.knots(p));
      CHECK(k.knots(k.knots.size() - 1) == k.knots(k.knots.size() - 1 - p));
      const double len = k.knots(k.knots.size() - 1) - k.knots(0);
      CHECK(len == Approx(1.0).epsilon(1e-14));
      // Compare at the same parameters (the periodic curve wraps).
      const VectorXd s = VectorXd::LinSpaced(1501, k.knots(0), k.knots(k.knots.size() - 1));
      const double diff = (evaluate(c, s) - evaluate(k, s)).cwiseAbs().maxCoeff();
      INFO("p " << p << " a " << a << " diff " << diff);
      // a = 0.999 inserts a knot 0.001 from the knot at 1: a 60:1 span ratio, which the explicit
      // form's forward integration (docs/formulas.md) turns into ~1e-11 for degree 5.
      CHECK(diff < (a == 0.999 ? 5e-11 : 1e-13));
      // The clamped curve is closed: both ends are the same point.
      CHECK((k.ctrl.row(0) - k.ctrl.row(k.ctrl.rows() - 1)).norm() < 1e-14);
    }
  }
}

TEST_CASE("make_compatible gives one knot vector and unchanged curves", "[splines][knots]") {
  std::mt19937 rng(9);
  std::vector<BSplineCurve> cs;
  for (int i = 0; i < 4; ++i)
    cs.push_back(random_clamped(rng, 3, 8 + i));
  const std::vector<BSplineCurve> out = make_compatible(cs);
  for (size_t i = 0; i < cs.size(); ++i) {
    CHECK(out[i].knots == out[0].knots);
    const double diff = curve_difference(cs[i], out[i], 0, 1);
    INFO("curve " << i << " diff " << diff);
    // Random knot vectors merged: spans of 1e-3 beside 0.2, so a few hundred ulps.
    CHECK(diff < 1e-12);
  }
  VectorXd a(5), b(6);
  a << 0, 0, 0.5, 1, 1;
  b << 0, 0, 0.5, 0.5, 1, 1;
  const VectorXd un = knot_union({a, b});
  CHECK(un.size() == 6);
  BSplineCurve p = cs[0];
  p.periodic = true;
  CHECK_THROWS(make_compatible({p}));
}
