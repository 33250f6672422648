// seed 004 §4.1–4.2: the axial-turbine cascade profile from 13 parameters, and stacking.
// Key points are the book's formulas (digest §6.1, values [V]); the fitted suction-side
// coefficients are the digest author's numbers for his illustrative parameters (regression).
#include "interlin/splines/cascade_profile.h"
#include "interlin/splines/cascade_stack.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;

namespace {

constexpr double kDeg = M_PI / 180;

// Digest §12 illustrative parameters: B = 1, t = 0.75, beta_y = 40, beta_1 = 90, beta_2 = 13,
// gamma_1 = 30, gamma_2 = 6, r1 = 0.06, r2 = 0.01, delta = 13, a = 0.17 (max thickness: ours).
CascadeParameters digest_parameters() {
  return {0.75, 1.0, 40, 90, 13, 30, 6, 0.06, 0.01, 13, 0.35, 0.15, 0.17};
}

double coef(const PlanarNaturalCurve& c, Index j) {
  return j < c.law.poly.size() ? c.law.poly(j) : 0;
}

void check_point(const CurvePose& p, double x, double y, double deg) {
  // The digest prints 6 decimals.
  CHECK(p.point.x() == Approx(x).epsilon(0).margin(6e-7));
  CHECK(p.point.y() == Approx(y).epsilon(0).margin(6e-7));
  CHECK(p.angle == Approx(deg * kDeg).epsilon(0).margin(1e-14));
}

// Do segments p-q and r-s cross?
bool crosses(const Vector2d& p, const Vector2d& q, const Vector2d& r, const Vector2d& s) {
  const auto o = [](const Vector2d& a, const Vector2d& b, const Vector2d& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
  };
  return o(p, q, r) * o(p, q, s) < 0 && o(r, s, p) * o(r, s, q) < 0;
}

} // namespace

TEST_CASE("Cascade key points: the book's formulas (digest §6.1 values)", "[splines][cascade]") {
  const CascadeProfile P = cascade_profile(digest_parameters());
  CHECK(P.O2.x() == Approx(0.01).epsilon(0).margin(1e-15));
  CHECK(P.O2.y() == Approx(0.190811).epsilon(0).margin(6e-7));
  CHECK(P.O1.x() == Approx(0.94).epsilon(0).margin(1e-15));
  CHECK(P.O1.y() == Approx(1.273179).epsilon(0).margin(6e-7));
  check_point(P.C2, 0.000152, 0.192548, 80);
  check_point(P.C3, 0.175691, 0.870480, 67);
  check_point(P.C1, 0.955529, 1.331135, -15);
  check_point(P.K2, 0.019613, 0.188055, 74);
  check_point(P.K1, 0.955529, 1.215224, 15);
  // Independent geometry (digest [V]): the edge points lie on their circles and the tangent
  // angles are perpendicular to the radii there.
  for (const auto& [q, O, r] : {std::tuple{P.C2, P.O2, 0.01}, std::tuple{P.K2, P.O2, 0.01},
                                std::tuple{P.C1, P.O1, 0.06}, std::tuple{P.K1, P.O1, 0.06}}) {
    CHECK((q.point - O).norm() == Approx(r).epsilon(0).margin(1e-15));
    CHECK((q.point - O).dot(Vector2d(std::cos(q.angle), std::sin(q.angle))) ==
          Approx(0).epsilon(0).margin(1e-15));
  }
  // C3 lies on the throat circle about the neighbouring blade's trailing-edge centre.
  CHECK((P.C3.point - (P.O2 + Vector2d(0, 0.75))).norm() == Approx(0.18).epsilon(0).margin(1e-15));
}

TEST_CASE("Cascade suction side: §4.1 (G2) and §4.2 (G3) against the digest's numbers",
          "[splines][cascade]") {
  CascadeOptions g2;
  g2.joint = CascadeJoint::g2_quadratic;
  const CascadeProfile P = cascade_profile(digest_parameters(), g2);
  const CascadeProfile Q = cascade_profile(digest_parameters()); // G3 default
  // Digest §12 [MINE] regression values, 8 digits; our fits converge to 1e-12 miss.
  for (const CascadeProfile* X : {&P, &Q}) {
    const PlanarNaturalCurve& lin = X->suction[0];
    CHECK(coef(lin, 1) == Approx(-0.84235249).epsilon(0).margin(1e-8));
    CHECK(coef(lin, 0) == Approx(-0.02765107).epsilon(0).margin(1e-8));
    CHECK(lin.length == Approx(0.70187787).epsilon(0).margin(1e-8));
    CHECK(curvature(lin.law, lin.length) == Approx(-0.61887965).epsilon(0).margin(1e-8));
    CHECK(X->miss < 1e-10);
  }
  const PlanarNaturalCurve& q2 = P.suction[1];
  CHECK(coef(q2, 2) == Approx(2.13018337).epsilon(0).margin(1e-8));
  CHECK(coef(q2, 1) == Approx(-3.05218262).epsilon(0).margin(1e-8));
  CHECK(coef(q2, 0) == Approx(-0.61887965).epsilon(0).margin(1e-8));
  CHECK(q2.length == Approx(0.99757521).epsilon(0).margin(1e-8));
  const PlanarNaturalCurve& c3 = Q.suction[1];
  CHECK(coef(c3, 3) == Approx(7.00083498).epsilon(0).margin(1e-8));
  CHECK(coef(c3, 2) == Approx(-6.40340869).epsilon(0).margin(1e-8));
  CHECK(coef(c3, 1) == Approx(-0.84235249).epsilon(0).margin(1e-8));
  CHECK(coef(c3, 0) == Approx(-0.61887965).epsilon(0).margin(1e-8));
  CHECK(c3.length == Approx(1.00822490).epsilon(0).margin(1e-8));
  // Joints: G2 keeps k and lets k' jump (-0.842 -> -3.052); G3 keeps k and k', both sides.
  for (const auto* side : {&P.suction, &P.pressure}) {
    const PlanarNaturalCurve &a = (*side)[0], &b = (*side)[1];
    CHECK(curvature(a.law, a.length) == Approx(curvature(b.law, 0)).epsilon(0).margin(1e-13));
    CHECK(std::abs(curvature(a.law, a.length, 1) - curvature(b.law, 0, 1)) > 0.1);
  }
  for (const auto* side : {&Q.suction, &Q.pressure}) {
    const PlanarNaturalCurve &a = (*side)[0], &b = (*side)[1];
    CHECK(curvature(a.law, a.length) == Approx(curvature(b.law, 0)).epsilon(0).margin(1e-13));
    CHECK(curvature(a.law, a.length, 1) == Approx(curvature(b.law, 0, 1)).epsilon(0).margin(1e-13));
    // The joint segment starts where the linear one ends, with its tangent.
    CHECK((b.start - natural_point(a, a.length)).norm() < 1e-15);
    CHECK(b.phi0 == Approx(tangent_angle(a, a.length)).epsilon(0).margin(1e-15));
  }
  // Each side ends on its leading-edge point with the book's tangent angle.
  for (const CascadeProfile* X : {&P, &Q}) {
    const PlanarNaturalCurve& s = X->suction[1];
    const PlanarNaturalCurve& p = X->pressure[1];
    CHECK((natural_point(s, s.length) - X->C1.point).norm() < 1e-10);
    CHECK(tangent_angle(s, s.length) == Approx(X->C1.angle).epsilon(0).margin(1e-13));
    CHECK((natural_point(p, p.length) - X->K1.point).norm() < 1e-10);
    CHECK(tangent_angle(p, p.length) == Approx(X->K1.angle).epsilon(0).margin(1e-13));
  }
  // Curvature-plot data: relative arc length 0..1, k continuous across the joint.
  const MatrixXd plot = side_curvature_plot(Q.suction, 101);
  CHECK(plot(0, 0) == 0.0);
  CHECK(plot(100, 0) == Approx(1.0).epsilon(0).margin(1e-15));
  CHECK(plot(0, 5) == Approx(coef(Q.suction[0], 0)).epsilon(0).margin(1e-15));
  CHECK((plot.block(100, 2, 1, 2).transpose() - Q.C1.point).norm() < 1e-10);
}

TEST_CASE("Cascade profile: closed simple contour with edge arcs and the maximum thickness",
          "[splines][cascade]") {
  const CascadeParameters par = digest_parameters();
  CascadeOptions o;
  o.side_intervals = 40;
  o.edge_intervals = 10;
  const CascadeProfile P = cascade_profile(par, o);
  const MatrixXd& V = P.points;
  REQUIRE(V.rows() == 2 * (40 + 10));
  // The first point is the middle of the trailing-edge arc; the next ones go to C2 (suction).
  const Vector2d mid = (P.C2.point + P.K2.point) / 2 - P.O2;
  CHECK((V.row(0).transpose() - P.O2).norm() == Approx(0.01).epsilon(0).margin(1e-15));
  // The arc C2 -> K2 spans 180 - gamma_2 < 180 degrees, so its middle lies in the direction of
  // the midpoint of the chord C2 K2 as seen from O2.
  CHECK((V.row(0).transpose() - P.O2).normalized().dot(mid.normalized()) ==
        Approx(1).epsilon(0).margin(1e-12));
  CHECK((V.row(1).transpose() - P.C2.point).norm() < (V.row(0).transpose() - P.C2.point).norm());
  CHECK((V.row(5).transpose() - P.C2.point).norm() < 1e-15); // suction side starts at C2
  // Edge arcs lie on their circles: trailing-edge points 0..4 and 95..99, leading edge 45..54.
  for (Index i : {0, 1, 4, 95, 99})
    CHECK((V.row(i).transpose() - P.O2).norm() == Approx(0.01).epsilon(0).margin(1e-15));
  for (Index i = 45; i < 55; ++i)
    CHECK((V.row(i).transpose() - P.O1).norm() == Approx(0.06).epsilon(0).margin(1e-15));
  CHECK((V.row(45).transpose() - P.C1.point).norm() < 1e-10);
  CHECK((V.row(55).transpose() - P.K1.point).norm() < 1e-10);
  // No two points coincide and no two edges cross: a simple closed polygon.
  for (Index i = 0; i < V.rows(); ++i)
    for (Index j = i + 1; j < V.rows(); ++j) {
      CHECK((V.row(i) - V.row(j)).norm() > 1e-6);
      if (j > i + 1 && !(i == 0 && j == V.rows() - 1))
        CHECK_FALSE(
            crosses(V.row(i), V.row((i + 1) % V.rows()), V.row(j), V.row((j + 1) % V.rows())));
    }
  // Maximum thickness: K3 is c_m from A along the inward normal; the circle's centre sits at
  // x = B (1 - position).
  CHECK((P.K3.point - P.A.point).norm() == Approx(0.15).epsilon(0).margin(1e-14));
  const Vector2d centre = (P.A.point + P.K3.point) / 2;
  CHECK(centre.x() == Approx(1.0 * (1 - 0.35)).epsilon(0).margin(1e-10));
  CHECK(P.K3.angle == P.A.angle);
  // A throat of 0 takes the default t sin(beta_2).
  CascadeParameters d = par;
  d.throat = 0;
  CHECK(cascade_profile(d).throat == Approx(0.75 * std::sin(13 * kDeg)).epsilon(0).margin(1e-15));
}

TEST_CASE("Cascade profile rejects bad and inconsistent parameters", "[splines][cascade]") {
  const CascadeParameters good = digest_parameters();
  CascadeParameters p = good;
  p.le_radius = -0.06;
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("leading-edge radius must be > 0"));
  p = good;
  p.te_radius = 0;
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("trailing-edge radius must be > 0"));
  p = good;
  p.outlet_angle_deg = 95;
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("outlet angle"));
  p = good;
  p.throat = 0.8;
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("smaller than the pitch"));
  p = good;
  p.axial_width = NAN;
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("finite"));
  p = good;
  p.inlet_angle_deg = 175; // phi_C1 = 70 deg > phi_C3 = 67 deg: the suction side cannot turn so
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("inconsistent angles"));
  p = good;
  p.te_bend_deg = 60; // C3 swings far round: the fitted sides cross
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("crosses itself"));
  p = good;
  p.max_thickness = 0.7; // a simple contour, but thicker than the passage
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("overlaps its neighbour"));
  p = good;
  p.max_thickness_position = 0.999; // no suction-side point so close to the leading edge
  CHECK_THROWS_WITH(cascade_profile(p), Catch::Contains("maximum-thickness") ||
                                            Catch::Contains("inconsistent maximum thickness"));
  CascadeOptions o;
  o.edge_intervals = 7;
  CHECK_THROWS_WITH(cascade_profile(good, o), Catch::Contains("even"));
}

TEST_CASE("Stacking profiles along the span: equal point counts, planes z = radius, aligned",
          "[splines][cascade]") {
  std::vector<SpanStation> st;
  for (int k = 0; k < 4; ++k) {
    CascadeParameters p = digest_parameters();
    p.axial_width = 1.0 - 0.1 * k; // chord shrinks towards the tip
    p.stagger_deg = 40 + 1.0 * k;  // stagger opens
    p.max_thickness = 0.15 - 0.02 * k;
    p.throat = 0; // default, follows the pitch
    st.push_back({2.0 + 0.5 * k, p});
  }
  const std::vector<MatrixXd> S = stack_cascade_profiles(st, StackAlign::centroid);
  REQUIRE(S.size() == 4);
  for (size_t k = 0; k < 4; ++k) {
    CHECK(S[k].rows() == S[0].rows());
    CHECK((S[k].col(2).array() == 2.0 + 0.5 * k).all());
    // The stacking line is the area centroid: the centred profile's centroid is 0.
    CHECK(polygon_centroid(S[k].leftCols(2)).norm() < 1e-14);
  }
  // Centroid of a known polygon (unit square shifted) as an independent check.
  MatrixXd sq(4, 2);
  sq << 1, 2, 3, 2, 3, 4, 1, 4;
  CHECK((polygon_centroid(sq) - Vector2d(2, 3)).norm() < 1e-15);
  // Radii must increase.
  std::swap(st[1].radius, st[2].radius);
  CHECK_THROWS_WITH(stack_cascade_profiles(st, StackAlign::none), Catch::Contains("increase"));
  st[1].radius = 2.5;
  st[2].radius = 3.0;
  st[3].parameters.le_radius = -1;
  CHECK_THROWS_WITH(stack_cascade_profiles(st, StackAlign::none),
                    Catch::Contains("span station 3") && Catch::Contains("radius must be > 0"));
}
