// Rays against a closed mesh: first-hit distances and the ray-parity inside test on the cube
// [-1/2, 1/2]^3 (12 triangles), where both have closed forms.
#include "interlin/reconstruction/meshing/ray_cast.h"

#include <catch2/catch.hpp>
#include <random>

using namespace interlin;
using Eigen::MatrixXd;
using Eigen::MatrixXi;

namespace {

void unit_cube(MatrixXd& V, MatrixXi& F) {
  V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    V.row(i) << (i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5;
  F.resize(12, 3);
  F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1,
      3, 5, 3, 7, 5;
}

} // namespace

TEST_CASE("ray_hit_distance: rays from inside the cube hit at 1/2 / max |d_k|", "[ray_cast]") {
  MatrixXd V;
  MatrixXi F;
  unit_cube(V, F);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-0.4, 0.4), N(-1, 1);
  const int n = 400;
  MatrixXd O(n + 2, 3), D(n + 2, 3);
  for (int i = 0; i < n; ++i)
    O.row(i) << U(rng), U(rng), U(rng), D.row(i) << N(rng), N(rng), N(rng);
  // Through a vertex and along an edge of the triangulation: the boxes' slab test keeps them.
  O.row(n) << 0, 0, 0, D.row(n) << 1, 1, 1;
  O.row(n + 1) << 0, 0, 0, D.row(n + 1) << 1, -1, 0;
  const Eigen::VectorXd t = ray_hit_distance(V, F, O, D);
  for (int i = 0; i < n + 2; ++i) {
    // The exit through the face x_k = sign(d_k)/2 nearest along the ray.
    double expected = INFINITY;
    for (int k = 0; k < 3; ++k)
      if (D(i, k) != 0)
        expected = std::min(expected, (std::copysign(0.5, D(i, k)) - O(i, k)) / D(i, k));
    INFO("ray " << i);
    CHECK(t(i) == Approx(expected).epsilon(0).margin(1e-14)); // a few roundings of O(1) values
  }
  // Rays from outside pointing away hit nothing.
  const MatrixXd away = (MatrixXd(1, 3) << 2, 0, 0).finished();
  CHECK(std::isinf(ray_hit_distance(V, F, away, away)(0)));
}

TEST_CASE("inside_by_ray_parity: random points against the cube's closed form", "[ray_cast]") {
  MatrixXd V;
  MatrixXi F;
  unit_cube(V, F);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-1, 1);
  MatrixXd P(2000, 3);
  for (int i = 0; i < P.rows(); ++i)
    P.row(i) << U(rng), U(rng), U(rng);
  const std::vector<char> in = inside_by_ray_parity(V, F, P);
  int wrong = 0;
  for (int i = 0; i < P.rows(); ++i)
    wrong += (in[size_t(i)] != 0) != (P.row(i).cwiseAbs().maxCoeff() < 0.5);
  CHECK(wrong == 0);
}
