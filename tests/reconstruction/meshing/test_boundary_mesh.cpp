// Seed 003's projection method: the published surface counts of body (11) on the 21^3 grid
// (digest §5.2 / §11.1), the node census, genus 5, projection onto F = 0, and the cleanup of
// touching configurations.
#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"

#include "support/test_implicits.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;

namespace {

// The seed's background: 21 x 21 x 21 nodes at -1 + 0.1 i on [-1, 1]^3 (9261 nodes, 8000 cubes).
RegularGrid seed_grid() {
  RegularGrid g;
  g.origin.setConstant(-1);
  g.spacing.setConstant(0.1);
  g.nodes.setConstant(21);
  return g;
}

Eigen::MatrixXi triangles(const BoundaryMesh& m) {
  return m.P.cols() == 4 ? triangulate_quads(m.V, m.P) : m.P;
}

} // namespace

TEST_CASE("boundary_mesh: seed 003 body (11) on 21^3 nodes gives the published counts",
          "[boundary]") {
  struct Row {
    BackgroundCells cells;
    ZeroRule rule;
    long inside, surviving, nodes, facets;
  };
  // Published: tets (strict) 2158 nodes / 4332 triangles, hexes (inclusive) 3064 / 3072 quads.
  // The other two rules and the census (3344 nodes with F > 0, 1284 more with F = 0) are the
  // digest's own reproduction [V].
  const Row rows[] = {
      {BackgroundCells::tetrahedra, ZeroRule::strict, 3344, 12948, 2158, 4332},
      {BackgroundCells::hexahedra, ZeroRule::inclusive, 4628, 2976, 3064, 3072},
      {BackgroundCells::hexahedra, ZeroRule::strict, 3344, 1992, 2416, 2424},
      {BackgroundCells::tetrahedra, ZeroRule::inclusive, 4628, 19512, 2614, 5244},
  };
  const ImplicitFunction f = test::body11_function();
  for (const Row& row : rows) {
    BoundaryMeshOptions o;
    o.cells = row.cells;
    o.rule = row.rule;
    const BoundaryMesh m = boundary_mesh(f, seed_grid(), o);
    INFO((row.cells == BackgroundCells::tetrahedra ? "tetrahedra" : "hexahedra")
         << (row.rule == ZeroRule::strict ? ", strict" : ", inclusive"));
    CHECK(m.inside_nodes == row.inside);
    CHECK(m.cells == row.surviving);
    CHECK(m.removed == 0); // digest: stage 2 removes nothing here
    CHECK(m.V.rows() == row.nodes);
    CHECK(m.P.rows() == row.facets);
    // Genus 5: V - F = -8 for quads, V - F/2 = -8 for triangles.
    CHECK(2 * (m.V.rows() - m.P.rows()) + (m.P.cols() == 3 ? m.P.rows() : 0) == -16);
    const MeshReport r = check_mesh(m.V, triangles(m));
    CHECK(r.watertight());
    CHECK(r.genus == 5);
    // Projection: every node on F = 0 (digest §11.2: |F| < 1e-6), none left behind.
    CHECK(m.unprojected == 0);
    for (long v = 0; v < m.V.rows(); ++v)
      CHECK(std::abs(test::body11(m.V(v, 0), m.V(v, 1), m.V(v, 2))) < 1e-9);
  }
}

TEST_CASE("boundary_mesh: without projection the nodes are the grid nodes", "[boundary]") {
  const RegularGrid g = seed_grid();
  Eigen::VectorXd S;
  sample_grid(test::body11_function(), g, S, 1);
  BoundaryMeshOptions o;
  o.cells = BackgroundCells::tetrahedra;
  const BoundaryMesh m = boundary_mesh(g, S, o);
  CHECK(m.V.rows() == 2158);
  const long nx = g.nodes(0), ny = g.nodes(1);
  for (long v = 0; v < m.V.rows(); ++v) {
    const long n = m.node(v);
    CHECK(m.V.row(v).isApprox(g.point(n % nx, (n / nx) % ny, n / (nx * ny)).transpose(), 0));
    CHECK(S(n) > o.epsilon); // strict rule
  }
}

TEST_CASE("boundary_mesh: cells touching along an edge or at a node are cleaned up", "[boundary]") {
  // Inside nodes: two cubes of the grid meeting only along an edge, or only at a node, placed so
  // that no tetrahedron of the Kuhn split bridges them (every tetrahedron of the cubes between
  // them has an outside node).
  RegularGrid g;
  g.nodes = {6, 6, 6};
  for (const bool at_node : {false, true})
    for (const BackgroundCells cells : {BackgroundCells::hexahedra, BackgroundCells::tetrahedra}) {
      Eigen::VectorXd S = Eigen::VectorXd::Constant(g.size(), -1.0);
      auto cube = [&](int i0, int j0, int k0) {
        for (int c = 0; c < 8; ++c)
          S(g.index(i0 + (c & 1), j0 + ((c >> 1) & 1), k0 + (c >> 2))) = 1;
      };
      cube(1, 2, 1);
      if (at_node)
        cube(2, 1, 2);
      else
        cube(2, 1, 1);
      BoundaryMeshOptions o;
      o.cells = cells;
      const BoundaryMesh m = boundary_mesh(g, S, o);
      INFO((at_node ? "node" : "edge")
           << ", " << (cells == BackgroundCells::hexahedra ? "hex" : "tet"));
      CHECK(m.removed >= 1);
      const MeshReport r = check_mesh(m.V, triangles(m));
      CHECK(r.watertight());
      CHECK(r.genus == 0);
    }
}

TEST_CASE("boundary_mesh: a block of cubes, triangulate_quads, errors", "[boundary]") {
  RegularGrid g;
  g.nodes = {6, 5, 7};
  Eigen::VectorXd S = Eigen::VectorXd::Constant(g.size(), 1.0);
  const BoundaryMesh m = boundary_mesh(g, S); // every node inside: the box's own surface
  CHECK(m.P.rows() == 2 * (5 * 4 + 4 * 6 + 5 * 6));
  const MeshReport r = check_mesh(m.V, triangulate_quads(m.V, m.P));
  CHECK(r.watertight());
  CHECK(r.volume == Approx(5.0 * 4 * 6).epsilon(1e-12)); // outward: positive volume
  CHECK_THROWS_AS(boundary_mesh(g, Eigen::VectorXd::Zero(3)), std::invalid_argument);
  CHECK_THROWS_AS(triangulate_quads(m.V, Eigen::MatrixXi::Constant(1, 4, 100000)),
                  std::invalid_argument);
}
