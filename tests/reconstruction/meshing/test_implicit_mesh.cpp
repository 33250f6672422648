// Implicit body -> mesh (seed 002 sub-boxes, marching cubes, seed 003 projection): the same mesh
// for any sub-box and thread count, vertices on F = 0, volumes converging to closed forms
// (sphere, torus, seed 003's body (11)), bodies cut by the box closed along it.
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"

#include "support/test_implicits.h"
#include "support/test_support.h"

// OpenMesh: MeshIO.hh must come before the mesh kernel header.
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace interlin;

namespace {

double max_abs_value(const ImplicitFunction& f, const Eigen::MatrixXd& V) {
  Eigen::VectorXd F(V.rows());
  f.value(V, F);
  return F.cwiseAbs().maxCoeff();
}

} // namespace

TEST_CASE("implicit_mesh: sub-boxes and threads only renumber the vertices", "[implicit]") {
  const ImplicitFunction f = test::torus(1.0, 0.35);
  ImplicitMeshOptions o;
  o.resolution = 48;
  o.subboxes = {1, 1, 1};
  o.threads = 1;
  Eigen::MatrixXd V0;
  Eigen::MatrixXi F0;
  ImplicitMeshInfo info;
  implicit_mesh(f, o, V0, F0, &info);
  const MeshReport r = check_mesh(V0, F0);
  REQUIRE(r.watertight());
  CHECK(r.genus == 1);
  CHECK(info.subboxes.isApprox(Eigen::Array3i(1, 1, 1)));
  for (const Eigen::Array3i& k : {Eigen::Array3i(2, 2, 2), Eigen::Array3i(3, 1, 2),
                                  Eigen::Array3i(5, 5, 5), Eigen::Array3i(1, 7, 3)})
    for (int threads : {1, 2, 3}) {
      o.subboxes = k;
      o.threads = threads;
      Eigen::MatrixXd V;
      Eigen::MatrixXi F;
      implicit_mesh(f, o, V, F, &info);
      INFO("sub-boxes " << k.transpose() << ", threads " << threads);
      CHECK(test::same_mesh_up_to_order(V0, F0, V, F));
      // Shared planes are sampled by both neighbours.
      CHECK(info.samples >= info.grid.size());
    }
}

TEST_CASE("implicit_mesh: vertices on F = 0, sphere and torus volumes converge with order 2",
          "[implicit]") {
  struct Body {
    ImplicitFunction f;
    double volume, area;
  };
  const double R = 1.0, r = 0.4;
  const std::vector<Body> bodies = {
      {test::sphere(1.0), 4 * M_PI / 3, 4 * M_PI},
      {test::torus(R, r), 2 * M_PI * M_PI * R * r * r, 4 * M_PI * M_PI * R * r}};
  for (const Body& b : bodies) {
    std::vector<double> h, ev, ea;
    for (int n : {12, 24, 48, 96}) {
      const test::CheckedMesh m = test::checked_mesh(b.f, test::at_resolution(n));
      REQUIRE(m.report.watertight());
      // Projection: the bracket is cut to 1e-10 of the cell and |grad F| <= 2.4 here.
      CHECK(max_abs_value(b.f, m.V) < 1e-9 * m.info.grid.spacing(0));
      CHECK(m.info.projection_evaluations > 0);
      h.push_back(m.info.grid.spacing(0));
      ev.push_back(std::abs(m.report.volume - b.volume));
      ea.push_back(std::abs(m.report.area - b.area));
    }
    // Vertices on the surface: what is left is the chordal error of flat triangles, O(h^2).
    // Tolerance 0.3: grid-alignment wobble of the error constant.
    CHECK(test::fitted_order(h, ev) == Approx(2).epsilon(0).margin(0.3));
    CHECK(test::fitted_order(h, ea) == Approx(2).epsilon(0).margin(0.3));
  }
}

TEST_CASE("implicit_mesh: seed 003 body (11): genus 5, volume converges to its closed form",
          "[implicit]") {
  // Volume: ball(1.3) minus the six caps beyond the cube faces (height 0.3; caps are disjoint),
  // minus the union of the three cylinders (radius 0.5, inside the ball): 3 pi r^2 2 - 3 Steinmetz
  // 16 r^3/3 + tricylinder 8 (2 - sqrt 2) r^3 = 1.5 pi - sqrt 2.
  const double Rb = 1.3, H = Rb - 1;
  const double exact = 4 * M_PI * Rb * Rb * Rb / 3 - 6 * M_PI * H * H * (3 * Rb - H) / 3 -
                       (1.5 * M_PI - std::sqrt(2.0));
  REQUIRE(exact == Approx(3.868844).epsilon(0).margin(1e-6));
  const ImplicitFunction f = test::body11_function();
  std::vector<double> h, err;
  for (int n : {20, 40, 80, 160}) {
    const test::CheckedMesh m = test::checked_mesh(f, test::at_resolution(n));
    REQUIRE(m.report.watertight());
    CHECK(m.report.genus == 5);
    h.push_back(m.info.grid.spacing(0));
    err.push_back(std::abs(m.report.volume - exact));
  }
  // Creases and corners are cut off by O(h) chamfers along O(1) length: O(h^2) volume error.
  CHECK(test::fitted_order(h, err) == Approx(2).epsilon(0).margin(0.4));
  CHECK(err.back() < 2e-3 * exact);
}

TEST_CASE("implicit_mesh: a box that cuts the body closes the mesh along the box", "[implicit]") {
  const ImplicitFunction f = test::sphere(1.0);
  std::vector<double> h, err;
  for (int n : {16, 32, 64}) {
    ImplicitMeshOptions o = test::at_resolution(n);
    o.box = Eigen::AlignedBox3d(Eigen::Vector3d(-1.1, -1.1, 0), Eigen::Vector3d(1.1, 1.1, 1.1));
    const test::CheckedMesh m = test::checked_mesh(f, o);
    REQUIRE(m.report.watertight());
    CHECK(m.info.clipped > 0);
    // No vertex below the cut (the cap sits on z = 0 up to the edge clamp of 1e-6 cells).
    CHECK(m.V.col(2).minCoeff() > -1e-12);
    h.push_back(m.info.grid.spacing(0));
    err.push_back(std::abs(m.report.volume - 2 * M_PI / 3));
  }
  CHECK(test::fitted_order(h, err) == Approx(2).epsilon(0).margin(0.4));
}

TEST_CASE("implicit_mesh: NaN and infinite values are outside (+inf inside), still closed",
          "[implicit]") {
  // A sphere whose function is NaN in a slab through it and -inf beyond x = 0.8.
  const ImplicitFunction f = test::implicit(
      [](double x, double y, double z) {
        if (std::abs(y) < 0.1)
          return std::nan("");
        if (x > 0.8)
          return -std::numeric_limits<double>::infinity();
        return 1 - x * x - y * y - z * z;
      },
      test::cube_box(1.2));
  const test::CheckedMesh m = test::checked_mesh(f, test::at_resolution(40));
  CHECK(m.report.watertight());
  CHECK(m.report.components == 2); // the NaN slab splits the ball
  CHECK(m.V.allFinite());
  // Each grid node with a non-finite value counted once, whatever the sub-boxes (nodes on their
  // shared planes are sampled twice).
  const RegularGrid& g = m.info.grid;
  long expected = 0;
  Eigen::VectorXd S;
  sample_grid(f, g, S, 1);
  for (long n = 0; n < S.size(); ++n)
    expected += !std::isfinite(S(n));
  REQUIRE(expected > 0);
  CHECK(m.info.nonfinite == expected);
  ImplicitMeshOptions o = test::at_resolution(40);
  o.subboxes = Eigen::Array3i(3, 4, 5);
  CHECK(test::checked_mesh(f, o).info.nonfinite == expected);
}

TEST_CASE("implicit_mesh: grid, box and option handling", "[implicit]") {
  ImplicitFunction f = test::sphere(1.0);
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  ImplicitMeshInfo info;
  ImplicitMeshOptions o;
  o.resolution = 20;
  implicit_mesh(f, o, V, F, &info);
  // 20 cells along the longest side of the function's box (+-1.1): h = 0.11.
  CHECK(info.grid.spacing(0) == Approx(0.11).epsilon(1e-12));
  CHECK((info.grid.nodes == 21).all());
  o.cell = 0.05; // overrides the resolution: 2.2 / 0.05 = 44 cells
  implicit_mesh(f, o, V, F, &info);
  CHECK((info.grid.nodes == 45).all());
  // Progress messages come through the callback.
  std::vector<std::string> said;
  o.progress = [&](const std::string& m) { said.push_back(m); };
  o.subboxes = {3, 3, 2};
  implicit_mesh(f, o, V, F, &info);
  CHECK(said.size() >= 3);
  o.progress = nullptr;
  o.subboxes = {0, 50, 0}; // more sub-boxes than cells
  CHECK_THROWS_AS(implicit_mesh(f, o, V, F), std::invalid_argument);
  o.subboxes.setZero();
  o.cell = 0;
  o.resolution = 0;
  CHECK_THROWS_AS(implicit_mesh(f, o, V, F), std::invalid_argument);
  o.resolution = 10;
  f.box.setEmpty();
  CHECK_THROWS_AS(implicit_mesh(f, o, V, F), std::invalid_argument); // no box anywhere
  o.box = test::cube_box(1.1);
  implicit_mesh(f, o, V, F);
  CHECK(check_mesh(V, F).watertight());
}

TEST_CASE("implicit_mesh: OpenMesh builds the result as a closed half-edge mesh", "[implicit]") {
  // An independent manifold check: OpenMesh's add_face refuses a face that would make an edge or
  // a vertex non-manifold (it returns an invalid handle); a closed mesh has no boundary.
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  for (const ImplicitFunction& f : {test::body11_function(), test::torus(1.0, 0.3)}) {
    ImplicitMeshOptions o;
    o.resolution = 50;
    o.subboxes = {2, 3, 2};
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    implicit_mesh(f, o, V, F);
    Mesh m;
    std::vector<Mesh::VertexHandle> vh;
    for (Eigen::Index i = 0; i < V.rows(); ++i)
      vh.push_back(m.add_vertex(Mesh::Point(float(V(i, 0)), float(V(i, 1)), float(V(i, 2)))));
    long refused = 0;
    for (Eigen::Index t = 0; t < F.rows(); ++t)
      refused +=
          !m.add_face(vh[size_t(F(t, 0))], vh[size_t(F(t, 1))], vh[size_t(F(t, 2))]).is_valid();
    CHECK(refused == 0);
    long boundary = 0;
    for (const auto h : m.halfedges())
      boundary += m.is_boundary(h);
    CHECK(boundary == 0);
    CHECK(long(m.n_faces()) == F.rows());
  }
}

TEST_CASE("default_mesh_cell: half the sample spacing, 32 to 1024 cells, else 128",
          "[implicit_mesh]") {
  ImplicitFunction f;
  const Eigen::AlignedBox3d box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 0.5));
  CHECK(default_mesh_cell(f, box) == 2.0 / 128); // spacing unknown: the default resolution
  f.sample_spacing = 0.03;
  CHECK(default_mesh_cell(f, box) == 0.015);
  CHECK(default_mesh_cell(f, box, 3) == 0.01);
  f.sample_spacing = 1; // a sparse cloud: still 32 cells along the longest side
  CHECK(default_mesh_cell(f, box) == 2.0 / 32);
  f.sample_spacing = 1e-6; // a dense one: at most 1024
  CHECK(default_mesh_cell(f, box) == 2.0 / 1024);
  CHECK_THROWS_AS(default_mesh_cell(f, Eigen::AlignedBox3d()), std::invalid_argument);
  CHECK_THROWS_AS(default_mesh_cell(f, box, 0), std::invalid_argument);
}
