// Element quality against closed forms, and seed 003's corner functional (digest §6.4, §11.5):
// the corner tables on the reference elements, and the local smoothing untangling and improving
// distorted meshes.
#include "interlin/reconstruction/meshing/volume_quality.h"
#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

using namespace interlin;

namespace {

const double kPi = 3.14159265358979323846;

Eigen::MatrixXd unit_cube() {
  Eigen::MatrixXd P(8, 3);
  P << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  return P;
}

Eigen::MatrixXd reference_tet() {
  Eigen::MatrixXd P(4, 3);
  P << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  return P;
}

Eigen::MatrixXd regular_tet() {
  Eigen::MatrixXd P(4, 3);
  P << 1, 1, 1, -1, 1, -1, 1, -1, -1, -1, -1, 1; // positively oriented
  return P;
}

// A structured n^3 hexahedral grid of [0, 1]^3: nodes, cells (VTK order), boundary flags.
void hex_grid(int n, Eigen::MatrixXd& V, Eigen::MatrixXi& C, std::vector<char>& boundary) {
  const int m = n + 1;
  V.resize(m * m * m, 3);
  boundary.assign(size_t(m * m * m), 0);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const int id = i + m * (j + m * k);
        V.row(id) << double(i) / n, double(j) / n, double(k) / n;
        boundary[size_t(id)] = i == 0 || j == 0 || k == 0 || i == n || j == n || k == n;
      }
  C.resize(n * n * n, 8);
  for (int k = 0, e = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++e) {
        auto id = [&](int a, int b, int c) { return (i + a) + m * ((j + b) + m * (k + c)); };
        C.row(e) << id(0, 0, 0), id(1, 0, 0), id(1, 1, 0), id(0, 1, 0), id(0, 0, 1), id(1, 0, 1),
            id(1, 1, 1), id(0, 1, 1);
      }
}

} // namespace

TEST_CASE("Corner tables: every corner alpha is 1 on the reference elements (digest §11.5)",
          "[volume][quality]") {
  CHECK(corner_alphas(unit_cube(), Eigen::RowVectorXi::LinSpaced(8, 0, 7)).isOnes(0));
  CHECK(corner_alphas(reference_tet(), Eigen::RowVectorXi::LinSpaced(4, 0, 3)).isOnes(0));
  // The seed's own hexahedron order (i,j,k), (i,j,k+1), (i+1,j,k+1), (i+1,j,k), then j+1, is a
  // relabelling of the same cube; in VTK order its corners are positive too.
  CHECK_THROWS_AS(corner_table(5), std::invalid_argument);
}

TEST_CASE("Element quality of the regular tetrahedron, the cube and distorted elements",
          "[volume][quality]") {
  ElementQuality q = element_quality(regular_tet());
  CHECK(q.min_dihedral_deg == Approx(std::acos(1.0 / 3) * 180 / kPi).epsilon(1e-12)); // 70.53
  CHECK(q.max_dihedral_deg == Approx(std::acos(1.0 / 3) * 180 / kPi).epsilon(1e-12));
  CHECK(q.scaled_jacobian == Approx(1).epsilon(1e-12));
  CHECK(q.radius_ratio == Approx(1).epsilon(1e-12));
  CHECK(q.volume == Approx(8.0 / 3).epsilon(1e-12)); // edge 2 sqrt 2: a^3 / (6 sqrt 2)
  CHECK_FALSE(q.inverted);
  // The reference (right-corner) tetrahedron: dihedral angles 90 (3 edges at the origin) and
  // acos(1/sqrt 3) = 54.74 (the other 3); r_in = 1 / (3 + sqrt 3), R = sqrt(3) / 2.
  q = element_quality(reference_tet());
  CHECK(q.min_dihedral_deg == Approx(std::acos(1 / std::sqrt(3.0)) * 180 / kPi).epsilon(1e-12));
  CHECK(q.max_dihedral_deg == Approx(90).epsilon(1e-12));
  CHECK(q.radius_ratio == Approx(3 / (3 + std::sqrt(3.0)) / (std::sqrt(3.0) / 2)).epsilon(1e-12));
  CHECK(q.scaled_jacobian == Approx(std::sqrt(2.0) / 2).epsilon(1e-12)); // corner with 1,1,sqrt2^2
  // Swapping two vertices inverts it.
  Eigen::MatrixXd P = reference_tet();
  P.row(1).swap(P.row(2));
  q = element_quality(P);
  CHECK(q.inverted);
  CHECK(q.volume == Approx(-1.0 / 6).epsilon(1e-12));
  CHECK(q.scaled_jacobian < 0);
  // The cube: right angles, scaled Jacobian 1, volume 1; a parallelepiped sheared by s:
  // volume 1, dihedral angles 90 -/+ atan(s).
  q = element_quality(unit_cube());
  CHECK(q.min_dihedral_deg == Approx(90).epsilon(1e-12));
  CHECK(q.max_dihedral_deg == Approx(90).epsilon(1e-12));
  CHECK(q.scaled_jacobian == Approx(1).epsilon(1e-12));
  CHECK(q.volume == Approx(1).epsilon(1e-12));
  CHECK(std::isnan(q.radius_ratio));
  Eigen::MatrixXd S = unit_cube();
  S.col(0) += 0.5 * S.col(2); // x += 0.5 z
  q = element_quality(S);
  CHECK(q.volume == Approx(1).epsilon(1e-12));
  CHECK(q.min_dihedral_deg == Approx(90 - std::atan(0.5) * 180 / kPi).epsilon(1e-12));
  CHECK(q.max_dihedral_deg == Approx(90 + std::atan(0.5) * 180 / kPi).epsilon(1e-12));
  CHECK(q.scaled_jacobian == Approx(1 / std::sqrt(1.25)).epsilon(1e-12));
  // A trilinear element: the volume is exact (top face z = 1 + x y / 2: 1 + 1/8).
  Eigen::MatrixXd T = unit_cube();
  for (int i = 4; i < 8; ++i)
    T(i, 2) += 0.5 * T(i, 0) * T(i, 1);
  CHECK(element_quality(T).volume == Approx(1.125).epsilon(1e-12));
  // A hexahedron pinched at one corner until it folds: inverted.
  Eigen::MatrixXd F = unit_cube();
  F.row(6) << -0.2, -0.2, -0.2;
  CHECK(element_quality(F).inverted);
}

TEST_CASE("A hexahedron folded at its centre with 8 convex corners counts as inverted",
          "[volume]") {
  // Found by random search from the unit cube: every corner alpha > 0.4, but the trilinear map's
  // Jacobian at the centre (the principal axes) is negative, so the element overlaps itself.
  Eigen::MatrixXd P(8, 3);
  P << -0.07, 0.2, -0.7, 0.7, -0.26, -0.73, 0.48, 0.75, 0.81, 1.4, -0.5, 1.27, //
      -0.57, -0.34, 1.21, 0.58, 0.3, 1.4, 1.91, 1.66, 0.84, 0.54, 1.6, 0.72;
  const Eigen::MatrixXi C = Eigen::RowVectorXi::LinSpaced(8, 0, 7);
  CHECK(corner_alphas(P, C).minCoeff() > 0.4);
  const ElementQuality q = element_quality(P);
  CHECK(q.scaled_jacobian < 0);
  CHECK(q.inverted);
  CHECK(volume_quality(P, C).inverted == 1);
}

TEST_CASE("Local smoothing untangles a randomly distorted hexahedral grid", "[volume][smooth]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi C;
  std::vector<char> boundary;
  hex_grid(6, V, C, boundary);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> shift(-0.6 / 6, 0.6 / 6);
  const Eigen::MatrixXd V0 = V;
  for (long v = 0; v < V.rows(); ++v)
    if (!boundary[size_t(v)])
      for (int a = 0; a < 3; ++a)
        V(v, a) += shift(rng);
  REQUIRE(volume_quality(V, C).inverted > 0);
  VolumeSmoothingOptions o;
  o.sweeps = 16; // digest: degenerate elements fixed after <= 16 iterations
  const VolumeSmoothingReport r = smooth_volume(V, C, boundary, o);
  CHECK(r.inverted.back() == 0);
  CHECK(volume_quality(V, C).inverted == 0);
  for (size_t s = 1; s < r.energy.size(); ++s) // Gauss-Seidel on a convex local functional
    CHECK(r.energy[s] <= r.energy[s - 1] * (1 + 1e-12));
  for (long v = 0; v < V.rows(); ++v)
    if (boundary[size_t(v)])
      CHECK(V.row(v) == V0.row(v));
  // The uniform grid is the minimiser: the nodes return close to it (all corners equal).
  CHECK((V - V0).cwiseAbs().maxCoeff() < 0.02);
}

TEST_CASE("Local smoothing leaves a uniform tetrahedral grid where it is", "[volume][smooth]") {
  // Kuhn split of the unit cube grid: every interior node is a stationary point by symmetry.
  Eigen::MatrixXd V;
  Eigen::MatrixXi H;
  std::vector<char> boundary;
  hex_grid(4, V, H, boundary);
  // Six tetrahedra per cube around the diagonal 0-6 (VTK numbering), positively oriented.
  const int kuhn[6][4] = {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                          {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};
  Eigen::MatrixXi C(6 * H.rows(), 4);
  for (long e = 0; e < H.rows(); ++e)
    for (int t = 0; t < 6; ++t)
      for (int j = 0; j < 4; ++j)
        C(6 * e + t, j) = H(e, kuhn[t][j]);
  REQUIRE(volume_quality(V, C).inverted == 0);
  const Eigen::MatrixXd V0 = V;
  smooth_volume(V, C, boundary);
  CHECK((V - V0).cwiseAbs().maxCoeff() < 1e-12);
}

TEST_CASE("smooth_volume and volume_quality reject bad input", "[volume][smooth]") {
  Eigen::MatrixXd V = unit_cube();
  const Eigen::MatrixXi C = Eigen::RowVectorXi::LinSpaced(8, 0, 7);
  VolumeSmoothingOptions o;
  o.sweeps = -1;
  CHECK_THROWS_AS(smooth_volume(V, C, {}, o), std::invalid_argument);
  CHECK_THROWS_AS(smooth_volume(V, C, std::vector<char>(3, 0)), std::invalid_argument);
  CHECK_THROWS_AS(volume_quality(V, Eigen::MatrixXi::Constant(1, 8, 9)), std::invalid_argument);
  CHECK_THROWS_AS(volume_quality(V, Eigen::MatrixXi::Zero(1, 5)), std::invalid_argument);
  CHECK_THROWS_AS(element_quality(Eigen::MatrixXd::Zero(5, 3)), std::invalid_argument);
}
