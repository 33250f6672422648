// Seed 003's adaptive refinement (digest §7.2, §11.6): the indicator's worked value, element
// counts against the indicator and delta, conformity (no face used more than twice, no node at
// the midpoint of a remaining edge, the outer surface unchanged), the boundary followed on F = 0.
#include "interlin/reconstruction/meshing/adaptive_refinement.h"
#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "support/test_implicits.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <utility>

using namespace interlin;

namespace {

// The unit cube as n^3 cubes of 6 Kuhn tetrahedra each.
void cube_mesh(int n, Eigen::MatrixXd& V, Eigen::MatrixXi& C) {
  RegularGrid g;
  g.origin.setZero();
  g.spacing.setConstant(1.0 / n);
  g.nodes.setConstant(n + 1);
  std::vector<long> ids(size_t(6 * n * n * n));
  std::iota(ids.begin(), ids.end(), 0L);
  C = background_cell_nodes(g, BackgroundCells::tetrahedra, ids);
  V.resize(long(n + 1) * (n + 1) * (n + 1), 3);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        V.row(g.index(i, j, k)) = g.point(i, j, k).transpose();
}

// Conformity: no face used by more than two elements, and no node at the midpoint of an edge of
// the mesh (a hanging node); returns the number of such faces plus hanging nodes.
long nonconforming(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
  std::map<std::array<int, 3>, int> faces;
  std::set<std::pair<int, int>> edges;
  for (long e = 0; e < C.rows(); ++e)
    for (int s = 0; s < 4; ++s) {
      std::array<int, 3> f;
      for (int j = 0, k = 0; j < 4; ++j)
        if (j != s)
          f[size_t(k++)] = C(e, j);
      std::sort(f.begin(), f.end());
      ++faces[f];
      for (int j = s + 1; j < 4; ++j)
        edges.insert(std::minmax(C(e, s), C(e, j)));
    }
  long bad = 0;
  for (const auto& [f, n] : faces)
    bad += n > 2;
  std::map<std::array<double, 3>, int> at; // exact coordinates (midpoints of dyadic grids)
  for (long v = 0; v < V.rows(); ++v)
    at[{V(v, 0), V(v, 1), V(v, 2)}] = int(v);
  for (const auto& [a, b] : edges) {
    const Eigen::RowVector3d m = 0.5 * (V.row(a) + V.row(b));
    bad += at.count({m(0), m(1), m(2)});
  }
  return bad;
}

double facet_area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
  return check_mesh(V, boundary_facets(C)).area;
}

} // namespace

TEST_CASE("refinement_indicator: the digest's worked value", "[volume][adapt]") {
  // §11.6: nodal C = {0, 0.1, 0.5} on a triangle, global range 1 (a fourth node with C = 1).
  Eigen::MatrixXi T(2, 3);
  T << 0, 1, 2, 1, 2, 3;
  Eigen::VectorXd c(4);
  c << 0, 0.1, 0.5, 1;
  const Eigen::VectorXd e = refinement_indicator(T, c);
  CHECK(e(0) == Approx(0.5).epsilon(1e-15));
  CHECK(e(1) == Approx(0.9).epsilon(1e-15));
  CHECK(refinement_indicator(T, Eigen::VectorXd::Constant(4, 3.0)).isZero()); // no range
  // Two separate tetrahedra: A with C = {0, 0.1, 0.5, 0.3} (indicator 0.5, as the triangle), B
  // with {0.6, 0.7, 0.8, 1} (0.4); the range is 1. A refined at delta 0.2 and 0.45 (into 8: all
  // its vertices refined), B only at 0.2, neither at 0.6.
  Eigen::MatrixXd V(8, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 0, 0, 6, 0, 0, 5, 1, 0, 5, 0, 1;
  Eigen::MatrixXi C(2, 4);
  C << 0, 1, 2, 3, 4, 5, 6, 7;
  Eigen::VectorXd v(8);
  v << 0, 0.1, 0.5, 0.3, 0.6, 0.7, 0.8, 1;
  const struct {
    double delta;
    long flagged, elements;
  } rows[] = {{0.2, 2, 16}, {0.45, 1, 9}, {0.6, 0, 2}};
  for (const auto& row : rows) {
    Eigen::MatrixXd W = V;
    Eigen::MatrixXi D = C;
    Eigen::VectorXd w = v;
    std::vector<char> b(8, 0);
    const RefinementReport r = refine_tetrahedra(W, D, b, w, row.delta);
    INFO("delta " << row.delta);
    CHECK(r.flagged == row.flagged);
    CHECK(D.rows() == row.elements);
    CHECK(W.rows() == 8 + 6 * row.flagged); // 6 edge midpoints per refined tetrahedron
    CHECK(volume_quality(W, D).volume == Approx(2.0 / 6).epsilon(1e-14));
  }
}

TEST_CASE("refine_tetrahedra: element counts follow the indicator, the mesh stays conforming",
          "[volume][adapt]") {
  Eigen::MatrixXd V0;
  Eigen::MatrixXi C0;
  cube_mesh(4, V0, C0); // 384 tetrahedra, 125 nodes
  REQUIRE(C0.rows() == 384);
  const double area0 = facet_area(V0, C0);
  REQUIRE(area0 == Approx(6).epsilon(1e-14));
  auto field = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi&) { // a front at x = 0.4
    return Eigen::VectorXd(((V.col(0).array() - 0.4) / 0.05).tanh());
  };
  SECTION("delta 0 and a field varying in every element: every element into 8") {
    Eigen::MatrixXd V = V0;
    Eigen::MatrixXi C = C0;
    std::vector<char> b(size_t(V.rows()), 0);
    Eigen::VectorXd x = V.col(0) + 0.1 * V.col(1) + 0.01 * V.col(2);
    const RefinementReport r = refine_tetrahedra(V, C, b, x, 0);
    CHECK(r.flagged == 384);
    CHECK(C.rows() == 8 * 384);
    CHECK(r.new_nodes == V.rows() - 125);
    CHECK(V.rows() == 9 * 9 * 9); // the cube's edges halved: the 8^3-cell grid's nodes
    CHECK(nonconforming(V, C) == 0);
    CHECK(volume_quality(V, C).inverted == 0);
    CHECK(volume_quality(V, C).volume == Approx(1).epsilon(1e-12));
  }
  SECTION("a front: refinement where the field changes, counts monotone in delta") {
    long previous = -1;
    for (double delta : {0.9, 0.5, 0.2, 0.05}) {
      Eigen::MatrixXd V = V0;
      Eigen::MatrixXi C = C0;
      std::vector<char> b(size_t(V.rows()), 0);
      const std::vector<RefinementReport> reps = adapt_tetrahedra(V, C, b, field, delta, 3);
      INFO("delta " << delta << ": " << C.rows() << " elements after " << reps.size() << " passes");
      CHECK(C.rows() >= previous); // a smaller delta refines at least as much
      previous = C.rows();
      CHECK(nonconforming(V, C) == 0);
      CHECK(volume_quality(V, C).inverted == 0);
      CHECK(volume_quality(V, C).volume == Approx(1).epsilon(1e-12));
      CHECK(facet_area(V, C) == Approx(area0).epsilon(1e-12)); // the outer surface, no holes
      // Elements far from the front (every vertex beyond 2 coarse cells) are never split.
      long far_small = 0;
      const double h0 = 0.25;
      for (long e = 0; e < C.rows(); ++e) {
        double lo = 1, hi = 0;
        for (int j = 0; j < 4; ++j)
          lo = std::min(lo, V(C(e, j), 0)), hi = std::max(hi, V(C(e, j), 0));
        if ((lo > 0.4 + 2 * h0 || hi < 0.4 - 2 * h0) && hi - lo < h0 - 1e-12)
          ++far_small;
      }
      CHECK(far_small == 0);
      // The largest indicator left is below the first pass's (the front is resolved).
      if (delta <= 0.5)
        CHECK(refinement_indicator(C, field(V, C)).maxCoeff() <
              refinement_indicator(C0, field(V0, C0)).maxCoeff());
    }
  }
}

TEST_CASE("refine_tetrahedra: new boundary nodes go onto F = 0 (sphere)", "[volume][adapt]") {
  const ImplicitFunction f = test::sphere(1.0);
  VolumeMeshOptions o;
  o.resolution = 10;
  VolumeMesh m = volume_mesh(f, o);
  const double exact = 4 * 3.14159265358979323846 / 3;
  const double before = std::abs(volume_quality(m.V, m.C).volume - exact);
  // Refine towards +x: C = x.
  auto field = [](const Eigen::MatrixXd& V, const Eigen::MatrixXi&) {
    return Eigen::VectorXd(V.col(0));
  };
  const std::vector<RefinementReport> reps = adapt_tetrahedra(m.V, m.C, m.boundary, field, 0, 1, f);
  REQUIRE(reps.size() == 1);
  CHECK(reps[0].projected > 0);
  CHECK(nonconforming(m.V, m.C) == 0);
  const VolumeQuality q = volume_quality(m.V, m.C);
  CHECK(q.inverted == 0);
  CHECK(std::abs(q.volume - exact) < 0.5 * before); // halved edges on the sphere: ~4x closer
  const Eigen::MatrixXi B = boundary_facets(m.C);
  Eigen::MatrixXd P(B.size(), 3);
  for (long i = 0; i < B.size(); ++i)
    P.row(i) = m.V.row(B.data()[i]);
  Eigen::VectorXd F(P.rows());
  f.value(P, F);
  CHECK(F.cwiseAbs().maxCoeff() < 1e-9);
  CHECK(check_mesh(m.V, B).boundary_edges == 0);
}

TEST_CASE("refine_tetrahedra: bad arguments", "[volume][adapt]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi C;
  cube_mesh(1, V, C);
  std::vector<char> b(size_t(V.rows()), 0);
  Eigen::VectorXd wrong(3);
  CHECK_THROWS_AS(refine_tetrahedra(V, C, b, wrong, 0.2), std::invalid_argument);
  Eigen::VectorXd nan = Eigen::VectorXd::Constant(V.rows(), std::nan(""));
  CHECK_THROWS_AS(refine_tetrahedra(V, C, b, nan, 0.2), std::invalid_argument);
  Eigen::VectorXd ok = V.col(0);
  CHECK_THROWS_AS(refine_tetrahedra(V, C, b, ok, 1.0), std::invalid_argument);
}

TEST_CASE("refine_tetrahedra: the clipped grid's small boundary elements stay valid (body 11)",
          "[volume][adapt]") {
  // volume_mesh's cut boundary has elements much smaller than the cell next to F = 0: a midpoint
  // projected the full way can fold one (measured: 21 of 222 144 at resolution 20). Each
  // midpoint goes the largest fraction of the way that folds none; those held short are few.
  const ImplicitFunction f = test::body11_function();
  VolumeMeshOptions o;
  o.resolution = 16;
  VolumeMesh m = volume_mesh(f, o);
  const double before = volume_quality(m.V, m.C).volume;
  Eigen::VectorXd values = m.V.col(0); // delta 0: every element where x varies, i.e. all
  const RefinementReport rep = refine_tetrahedra(m.V, m.C, m.boundary, values, 0.0, f);
  const VolumeQuality q = volume_quality(m.V, m.C);
  INFO("projected " << rep.projected << ", held short " << rep.held);
  CHECK(q.inverted == 0);
  CHECK(rep.projected > 1000);
  CHECK(rep.held < 0.01 * rep.projected);
  // The refined boundary follows F = 0 more closely: the volume grows towards 3.868844.
  CHECK(q.volume > before);
  CHECK(q.volume < 3.868844 * 1.001);
}
