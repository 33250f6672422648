// Section preparation: winding, edges, start alignment.
#include "interlin/reconstruction/loft/section_prep.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;

namespace {

// A cambered airfoil-like closed profile in the plane z = z0: NACA-4 style thickness (round
// leading edge at chord 0, sharp trailing edge at chord 1, maximum thickness at 30 %), circular-arc
// camber. Points: upper side from the trailing edge to the leading edge, then the lower side back
// (cosine spacing, clustered at both edges); `rotate` turns the profile in its plane.
MatrixXd airfoil(int half, double z0, double rotate = 0) {
  MatrixXd P(2 * half, 3);
  const auto thick = [](double x) {
    return 0.6 * (0.2969 * std::sqrt(x) - 0.126 * x - 0.3516 * x * x + 0.2843 * x * x * x -
                  0.1036 * x * x * x * x);
  };
  const auto camber = [](double x) { return 0.08 * x * (1 - x); };
  const double c = std::cos(rotate), s = std::sin(rotate);
  for (int i = 0; i < 2 * half; ++i) {
    const bool upper = i < half;
    const double t = upper ? double(i) / half : double(i - half) / half;
    const double x = upper ? 0.5 * (1 + std::cos(M_PI * t)) : 0.5 * (1 - std::cos(M_PI * t));
    const double y = camber(x) + (upper ? 1 : -1) * thick(x);
    P.row(i) << c * x - s * y, s * x + c * y, z0;
  }
  return P;
}

Section make(const std::string& id, const MatrixXd& P) {
  Section s;
  s.id = id;
  s.points = P;
  for (Index i = 0; i < P.rows(); ++i)
    s.lines.push_back(100 + i);
  return s;
}

} // namespace

TEST_CASE("vector_area of planar and non-planar polygons", "[prep]") {
  MatrixXd Q(4, 3);
  Q << 0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0; // 2 x 1 rectangle, counter-clockwise about +z
  CHECK(vector_area(Q).isApprox(Eigen::Vector3d(0, 0, 2)));
  MatrixXd R = Q.colwise().reverse();
  CHECK(vector_area(R).isApprox(Eigen::Vector3d(0, 0, -2)));
  Q(2, 2) = 0.5; // lift a corner: the z component (projected area) is unchanged
  CHECK(vector_area(Q)(2) == Approx(2.0).epsilon(1e-12));
}

TEST_CASE("Edges of a cambered profile: nose tips found, leading edge by maximum thickness",
          "[prep]") {
  const MatrixXd P = airfoil(60, 0.0);
  const auto [a, b] = profile_edges(P);
  // Row 0 is the trailing edge (x = 1), row 60 the leading edge (x = 0).
  const Index te = P(a, 0) > P(b, 0) ? a : b, le = te == a ? b : a;
  CHECK(P(te, 0) == Approx(1.0).epsilon(0).margin(1e-3));
  CHECK(std::abs(P(le, 0)) < 2e-3); // within the first point spacing (cosine spacing ~7e-4)
  CHECK(max_thickness_position(P, le, te) == Approx(0.30).epsilon(0).margin(0.03));
  CHECK(max_thickness_position(P, te, le) == Approx(0.70).epsilon(0).margin(0.03));
}

TEST_CASE("prepare_sections: reversal keeps the start, alignment rolls to the edges", "[prep]") {
  std::vector<Section> in;
  for (int k = 0; k < 5; ++k) {
    MatrixXd P = airfoil(50, k * 0.5, 0.15 * k);
    if (k == 2) { // reversed winding, same start point
      MatrixXd R(P.rows(), 3);
      for (Index i = 0; i < P.rows(); ++i)
        R.row(i) = P.row((P.rows() - i) % P.rows());
      P = R;
    }
    if (k == 3) { // rolled: starts 17 points later
      MatrixXd Q(P.rows(), 3);
      for (Index i = 0; i < P.rows(); ++i)
        Q.row(i) = P.row((i + 17) % P.rows());
      P = Q;
    }
    in.push_back(make(std::to_string(k), P));
  }
  std::vector<std::string> notes;
  const auto first = prepare_sections(in, StartAlign::first, notes);
  REQUIRE(notes.size() == 1);
  CHECK_THAT(notes[0], Catch::Contains("section 2: reversed"));
  CHECK(first[2].reversed);
  CHECK(first[2].points.row(0) == in[2].points.row(0)); // start kept
  for (const PreparedSection& s : first) {
    CHECK(vector_area(s.points).dot(vector_area(first[0].points)) > 0);
    for (Index i = 0; i < s.points.rows(); ++i) // source maps back to the input rows
      CHECK(s.points.row(i) == in[std::stoul(s.id)].points.row(s.source[size_t(i)]));
  }
  notes.clear();
  const auto le = prepare_sections(in, StartAlign::leading_edge, notes);
  for (const PreparedSection& s : le) {
    CHECK(s.le == 0);
    // Undo the in-plane rotation: the start is the leading edge (chord position ~0).
    const double k = std::stod(s.id), c = std::cos(0.15 * k), sn = std::sin(0.15 * k);
    const double x = c * s.points(0, 0) + sn * s.points(0, 1);
    CHECK(std::abs(x) < 2e-3);
    const double xt = c * s.points(s.te, 0) + sn * s.points(s.te, 1);
    CHECK(xt == Approx(1.0).epsilon(0).margin(1e-3));
    CHECK(s.lines[0] == 100 + s.source[0]);
  }
  const auto te = prepare_sections(in, StartAlign::trailing_edge, notes);
  for (const PreparedSection& s : te)
    CHECK(s.te == 0);
}
