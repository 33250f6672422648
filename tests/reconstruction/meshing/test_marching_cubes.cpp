// Marching cubes on sampled grids: closed 2-manifolds for any field (zeros, NaN, ambiguous
// faces), the asymptotic decider, vertices at the linear interpolation on their edges, O(h^2)
// volume and area against the sphere's closed forms, and thread counts that only renumber.
#include "interlin/reconstruction/meshing/marching_cubes.h"
#include "interlin/reconstruction/meshing/mesh_check.h"

#include "support/test_implicits.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

using namespace interlin;

namespace {

// Grid with the outer layer forced outside, so that every surface is closed.
Eigen::VectorXd random_field(const RegularGrid& g, std::mt19937& rng, int mode) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> sign(-1, 1);
  Eigen::VectorXd S(g.size());
  for (long k = 0; k < g.nodes(2); ++k)
    for (long j = 0; j < g.nodes(1); ++j)
      for (long i = 0; i < g.nodes(0); ++i) {
        const bool outer = i == 0 || j == 0 || k == 0 || i == g.nodes(0) - 1 ||
                           j == g.nodes(1) - 1 || k == g.nodes(2) - 1;
        double v = mode == 0   ? u(rng)                                   // generic
                   : mode == 1 ? double(sign(rng))                        // many exact zeros
                               : (u(rng) < -0.8 ? std::nan("") : u(rng)); // NaN holes
        if (mode == 3)
          v = u(rng) < 0 ? -INFINITY : (u(rng) < 0 ? INFINITY : u(rng));
        S(g.index(i, j, k)) = outer ? -1 : v;
      }
  return S;
}

} // namespace

TEST_CASE("marching_cubes: random fields give closed, manifold, oriented meshes", "[mc]") {
  std::mt19937 rng(20240501);
  long checked = 0;
  for (int trial = 0; trial < 800; ++trial) {
    RegularGrid g;
    g.nodes = {5 + trial % 6, 4 + trial % 5, 5 + trial % 4};
    g.spacing = {0.5, 0.7, 0.3};
    const Eigen::VectorXd S = random_field(g, rng, trial % 4);
    Eigen::MatrixXd V, V3;
    Eigen::MatrixXi F, F3;
    marching_cubes(g, S, V, F, nullptr, 1);
    marching_cubes(g, S, V3, F3, nullptr, 3);
    INFO("trial " << trial);
    REQUIRE(test::same_mesh_up_to_order(V, F, V3, F3));
    if (F.rows() == 0)
      continue;
    const MeshReport r = check_mesh(V, F);
    CHECK(r.watertight()); // includes: no boundary/non-manifold edge or vertex, no degenerate face
    CHECK(r.genus >= 0);
    CHECK(r.volume > 0); // normals point out of the inside region
    ++checked;
  }
  CHECK(checked > 700);
}

TEST_CASE("marching_cubes: the asymptotic decider joins or separates across an ambiguous face",
          "[mc]") {
  // Two cubes share the face x = 2; only its diagonal corners (2,1,1) and (2,2,2) are inside.
  RegularGrid g;
  g.nodes = {5, 4, 4};
  auto run = [&](double a, double c, double b, double d) {
    Eigen::VectorXd S = Eigen::VectorXd::Constant(g.size(), -1.0);
    S(g.index(2, 1, 1)) = a, S(g.index(2, 2, 2)) = c;
    S(g.index(2, 2, 1)) = b, S(g.index(2, 1, 2)) = d;
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    marching_cubes(g, S, V, F);
    const MeshReport r = check_mesh(V, F);
    CHECK(r.watertight());
    return r;
  };
  // Bilinear saddle (ac - bd) / (a + c - b - d): positive -> one surface around both nodes.
  const MeshReport joined = run(1, 1, -0.5, -0.5);
  CHECK(joined.components == 1);
  CHECK(joined.genus == 0);
  const MeshReport apart = run(0.2, 0.2, -1, -1);
  CHECK(apart.components == 2);
  // Equal products (saddle exactly 0) count as outside, like a node with F = 0.
  CHECK(run(0.5, 0.5, -0.5, -0.5).components == 2);
}

TEST_CASE("marching_cubes: vertices at the clamped linear interpolation on their edges", "[mc]") {
  RegularGrid g;
  g.origin = {-1.3, -1.2, -1.1};
  g.spacing = {0.1, 0.12, 0.15};
  g.nodes = {27, 21, 16};
  const ImplicitFunction f = test::sphere(1.0);
  Eigen::VectorXd S;
  sample_grid(f, g, S, 2);
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::vector<EdgeVertex> E;
  marching_cubes(g, S, V, F, &E);
  REQUIRE(long(E.size()) == V.rows());
  REQUIRE(V.rows() > 500);
  const long nx = g.nodes(0), ny = g.nodes(1);
  for (long v = 0; v < V.rows(); ++v) {
    const EdgeVertex& e = E[size_t(v)];
    const long i = e.node % nx, j = (e.node / nx) % ny, k = e.node / (nx * ny);
    long other[3] = {i, j, k};
    ++other[e.axis];
    CHECK(e.f0 == S(e.node));
    CHECK(e.f1 == S(g.index(other[0], other[1], other[2])));
    CHECK((e.f0 > 0) != (e.f1 > 0));
    const double t = std::clamp(e.f0 / (e.f0 - e.f1), kEdgeClamp, 1 - kEdgeClamp);
    Eigen::Vector3d p = g.point(i, j, k);
    p(e.axis) += t * g.spacing(e.axis);
    // Same formula, same doubles: equal up to the rounding of one multiply-add.
    CHECK((V.row(v).transpose() - p).norm() <= 1e-15);
  }
}

TEST_CASE("marching_cubes: exact zeros at nodes give no degenerate triangle", "[mc]") {
  // Radius 1 on a step-0.25 grid: the surface passes exactly through nodes such as (1, 0, 0).
  RegularGrid g;
  g.origin.setConstant(-1.5);
  g.spacing.setConstant(0.25);
  g.nodes.setConstant(13);
  Eigen::VectorXd S;
  sample_grid(test::sphere(1.0), g, S, 1);
  long zeros = 0;
  for (long n = 0; n < S.size(); ++n)
    zeros += S(n) == 0;
  REQUIRE(zeros >= 6);
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  marching_cubes(g, S, V, F);
  const MeshReport r = check_mesh(V, F);
  CHECK(r.watertight());
  CHECK(r.degenerate_faces == 0);
  CHECK(r.genus == 0);
}

TEST_CASE("marching_cubes: sphere volume and area converge with order 2", "[mc]") {
  // Linear interpolation puts vertices O(h^2) off the sphere and flat triangles deviate O(h^2),
  // so both errors fall like h^2. The grid is offset so that no symmetry helps.
  const double V0 = 4 * M_PI / 3, A0 = 4 * M_PI;
  std::vector<double> h, ev, ea;
  for (int n : {10, 20, 40, 80}) {
    RegularGrid g;
    g.spacing.setConstant(2.6 / n);
    g.origin = Eigen::Vector3d(-1.3, -1.3, -1.3) + Eigen::Vector3d(0.31, 0.17, 0.23) * g.spacing(0);
    g.nodes.setConstant(n + 1);
    Eigen::VectorXd S;
    sample_grid(test::sphere(1.0), g, S);
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    marching_cubes(g, S, V, F);
    const MeshReport r = check_mesh(V, F);
    REQUIRE(r.watertight());
    CHECK(r.genus == 0);
    h.push_back(g.spacing(0));
    ev.push_back(std::abs(r.volume - V0));
    ea.push_back(std::abs(r.area - A0));
  }
  // Tolerance 0.3 on the order: the error constants wobble with the grid offset.
  CHECK(test::fitted_order(h, ev) == Approx(2).epsilon(0).margin(0.3));
  CHECK(test::fitted_order(h, ea) == Approx(2).epsilon(0).margin(0.3));
  CHECK(ev.back() < 2e-3 * V0); // h = 0.0325: ~1e-3 relative
}

TEST_CASE("marching_cubes: bad input", "[mc]") {
  RegularGrid g;
  g.nodes = {3, 3, 3};
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  CHECK_THROWS_AS(marching_cubes(g, Eigen::VectorXd::Zero(26), V, F), std::invalid_argument);
  g.nodes = {1, 3, 3};
  CHECK_THROWS_AS(marching_cubes(g, Eigen::VectorXd::Zero(9), V, F), std::invalid_argument);
  // An empty field: no surface, no error.
  g.nodes = {3, 3, 3};
  marching_cubes(g, Eigen::VectorXd::Constant(27, -1.0), V, F);
  CHECK(V.rows() == 0);
  CHECK(F.rows() == 0);
}
