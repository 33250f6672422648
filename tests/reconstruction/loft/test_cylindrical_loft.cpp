// The seed's cylindrical model x = R cos t, y = R sin t, z = z for star-shaped bodies.
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/loft/cylindrical_loft.h"

#include "support/test_sections.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::VectorXd;

namespace {

const Eigen::Vector2d kCenter(0.5, -0.2);

// Star-shaped body around kCenter: polar radius R(t, z), dented (concave) near t = pi/2, 3pi/2.
double R(double t, double z) {
  return (1 + 0.35 * std::cos(2 * t) + 0.05 * std::sin(t)) * (1 + 0.2 * std::sin(2 * z));
}

// Its point at polar angle t (about kCenter) and height z.
Eigen::Vector3d star_point(double t, double z) {
  return {kCenter(0) + R(t, z) * std::cos(t), kCenter(1) + R(t, z) * std::sin(t), z};
}

std::vector<Section> star(Index K, Index n) {
  std::vector<Section> in;
  for (Index k = 0; k < K; ++k)
    in.push_back(
        test::angle_section(double(k) / double(K - 1), n + 7 * (k % 3), 0.1 * k, 0.02, star_point));
  return in;
}

Guide meridian(const std::string& id, double t, Index K, Index extra) {
  // Points on every section height plus `extra` points between consecutive sections.
  Guide g;
  g.id = id;
  std::vector<double> zs;
  for (Index k = 0; k + 1 < K; ++k)
    for (Index e = 0; e <= extra; ++e)
      zs.push_back((double(k) + double(e) / double(extra + 1)) / double(K - 1));
  zs.push_back(1.0);
  g.points.resize(static_cast<Index>(zs.size()), 3);
  for (size_t j = 0; j < zs.size(); ++j) {
    g.points.row(static_cast<Index>(j)) = star_point(t, zs[j]).transpose();
    g.lines.push_back(static_cast<long>(j) + 2);
  }
  return g;
}

CylindricalLoftOptions centred() {
  CylindricalLoftOptions o;
  o.center_x = kCenter(0);
  o.center_y = kCenter(1);
  return o;
}

double max_error(const CylindricalLoft& m) {
  double e = 0;
  for (double z : VectorXd::LinSpaced(41, 0, 1))
    for (double t : VectorXd::LinSpaced(90, 0, 2 * M_PI))
      e = std::max(e, std::abs(evaluate(m.radius, t, z)(0) - R(t, z)));
  return e;
}

} // namespace

TEST_CASE("Cylindrical model reproduces every section point, O(h^4) along z", "[cylindrical]") {
  const CylindricalLoft m = cylindrical_loft(star(5, 200), GuideSet{}, centred());
  CHECK(m.max_deviation <= 1e-13 * m.bbox_diagonal); // sections are exactly planar here
  CHECK(m.z.size() == 5);
  const Eigen::Vector3d p = evaluate(m, 0.3, 0.25);
  CHECK(p(2) == 0.25);
  CHECK(std::hypot(p(0) - kCenter(0), p(1) - kCenter(1)) ==
        Approx(evaluate(m.radius, 0.3, 0.25)(0)).epsilon(1e-12));
  // Derivatives: d/dt of (R cos t, R sin t) against central differences (h = 1e-5: error
  // ~1e-10 truncation + 1e-11 round-off).
  const Eigen::Vector3d d = evaluate(m, 1.0, 0.6, 1, 0);
  const Eigen::Vector3d fd = (evaluate(m, 1.0 + 1e-5, 0.6) - evaluate(m, 1.0 - 1e-5, 0.6)) / 2e-5;
  CHECK((d - fd).norm() < 1e-8);
  // Spanwise convergence: 200+ points per section make the angular error ~1e-9, below the
  // spanwise errors measured here.
  std::vector<double> h, err;
  for (Index K : {5, 9, 17}) {
    h.push_back(1.0 / double(K - 1));
    err.push_back(max_error(cylindrical_loft(star(K, 400), GuideSet{}, centred())));
  }
  INFO("errors " << err[0] << " " << err[1] << " " << err[2]);
  CHECK(test::fitted_order(h, err) == Approx(4.0).epsilon(0).margin(0.3));
}

TEST_CASE("Cylindrical model with meridians: exact on them, smaller error between",
          "[cylindrical]") {
  GuideSet ms;
  ms.path = "m.csv";
  for (int l = 0; l < 6; ++l)
    ms.guides.push_back(meridian("M" + std::to_string(l), -2.8 + 1.05 * l, 5, 7));
  const CylindricalLoft with = cylindrical_loft(star(5, 200), ms, centred());
  const CylindricalLoft without = cylindrical_loft(star(5, 200), GuideSet{}, centred());
  CHECK(with.max_deviation <= 1e-13 * with.bbox_diagonal);
  // On a meridian the model is its trace, the spline through 29 radius samples: error of that
  // 1-D interpolation only (~1e-5), not of the 5-section blend (~1e-3).
  double on = 0;
  for (double z : VectorXd::LinSpaced(101, 0, 1))
    on = std::max(on, std::abs(evaluate(with.radius, -2.8 + 1.05 * 2, z)(0) - R(-2.8 + 2.1, z)));
  const double e_with = max_error(with), e_without = max_error(without);
  INFO("on meridian " << on << ", max error with meridians " << e_with << ", without "
                      << e_without);
  CHECK(on < 0.05 * e_without);
  CHECK(e_with < e_without);
  // Meridian off its half-plane: one error with the line.
  ms.guides[1].points(3, 0) += 0.01;
  CHECK_THROWS_WITH(cylindrical_loft(star(5, 200), ms, centred()),
                    Catch::StartsWith("m.csv:5:") && Catch::Contains("off the half-plane"));
}

TEST_CASE("Cylindrical model: convexity map of the dented body", "[cylindrical]") {
  const CylindricalLoft m = cylindrical_loft(star(9, 200), GuideSet{}, centred());
  const VectorXd t = VectorXd::LinSpaced(73, -M_PI, M_PI).head(72),
                 z = VectorXd::LinSpaced(5, 0.1, 0.9);
  const ShapeMap s = shape_map(m, t, z, 1e-3);
  for (Index i = 0; i < t.size(); ++i) {
    const double r = R(t(i), 0.5), r1 = (R(t(i) + 1e-4, 0.5) - R(t(i) - 1e-4, 0.5)) / 2e-4,
                 r2 = (R(t(i) + 1e-4, 0.5) - 2 * r + R(t(i) - 1e-4, 0.5)) / 1e-8;
    const double c = r * r + 2 * r1 * r1 - r * r2;
    if (std::abs(c) > 0.05)
      CHECK(s.along_u(i, 2) == (c > 0 ? 1 : -1));
  }
  // Along z: R = (...)(1 + 0.2 sin 2z) has R_zz < 0 on (0, pi/2): bulging outward, convex.
  CHECK((s.along_v.array() == 1).all());
}

TEST_CASE("Cylindrical model rejects non-planar and non-star-shaped sections", "[cylindrical]") {
  std::vector<Section> in = star(3, 40);
  in[1].points(7, 2) += 0.01;
  CHECK_THROWS_WITH(cylindrical_loft(in, GuideSet{}, centred()),
                    Catch::Contains("line 9") && Catch::Contains("not in a plane"));
  in = star(3, 40);
  CylindricalLoftOptions far = centred();
  far.center_x = 5; // the axis outside the sections: the polar angle turns back
  CHECK_THROWS_WITH(cylindrical_loft(in, GuideSet{}, far), Catch::Contains("not star-shaped"));
  std::swap(in[0], in[2]);
  CHECK_THROWS_WITH(cylindrical_loft(in, GuideSet{}, centred()),
                    Catch::Contains("increasing height"));
}
