// The volume a mesh leaves out of the body (uncovered_volume): exact on meshes made of the clipped
// grid's own pieces, the grid's inside cubes for hexahedra, and on a family of thin discs the
// projected layer's loss it reports in VolumeMeshInfo (lost above 0.5 % at a coarse cell, below
// at the cell it suggests).
#include "interlin/reconstruction/meshing/cut_tetrahedra.h"
#include "interlin/reconstruction/meshing/uncovered_volume.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "support/test_implicits.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

using namespace interlin;

namespace {

struct Clipped {
  RegularGrid g;
  Eigen::VectorXd S;
  CutTetrahedra body;
};

Clipped clipped(const ImplicitFunction& f, int resolution) {
  Clipped c;
  c.g = grid_with_resolution(f.box, resolution);
  sample_grid(f, c.g, c.S);
  c.body = cut_tetrahedra(f, c.g, c.S, 1e-12);
  return c;
}

double tet_volume(const Eigen::MatrixXd& V, const Eigen::RowVector4i& t) {
  const Eigen::Vector3d a = V.row(t(0)), b = V.row(t(1)), c = V.row(t(2)), d = V.row(t(3));
  return (b - a).cross(c - a).dot(d - a) / 6;
}

} // namespace

TEST_CASE("uncovered_volume: a mesh of some of the clipped pieces leaves out exactly the others",
          "[volume]") {
  // The pieces do not overlap and each contains its centroid: the lost volume is the sum of the
  // pieces left out, up to round-off.
  for (const ImplicitFunction& f : {test::sphere(1.0), test::torus(1.0, 0.4)}) {
    const Clipped c = clipped(f, 14);
    const Eigen::MatrixXi& T = c.body.C;
    double all = 0, rest = 0;
    std::vector<int> kept;
    for (long e = 0; e < T.rows(); ++e) {
      const double v = tet_volume(c.body.V, T.row(e));
      const Eigen::RowVector3d mid = (c.body.V.row(T(e, 0)) + c.body.V.row(T(e, 1)) +
                                      c.body.V.row(T(e, 2)) + c.body.V.row(T(e, 3))) /
                                     4;
      all += v;
      if (mid(0) + 0.5 * mid(1) < 0.1)
        kept.push_back(int(e));
      else
        rest += v;
    }
    Eigen::MatrixXi part(long(kept.size()), 4);
    for (size_t r = 0; r < kept.size(); ++r)
      part.row(long(r)) = T.row(kept[r]);
    const UncoveredVolume whole = uncovered_volume(c.body, c.g, c.body.V, T);
    CHECK(whole.body == Approx(all).epsilon(1e-12));
    CHECK(whole.lost == 0);
    CHECK(whole.thickness() == 0);
    const UncoveredVolume some = uncovered_volume(c.body, c.g, c.body.V, part, 1);
    CHECK(some.body == Approx(all).epsilon(1e-12));
    CHECK(some.lost == Approx(rest).epsilon(1e-12));
    CHECK(some.lost_area > 0);
    CHECK(uncovered_volume(c.body, c.g, c.body.V, part, 3).lost == some.lost); // any threads
  }
}

TEST_CASE("uncovered_volume: an element whose box spans the grid is tried apart", "[volume]") {
  // A needle along the box's diagonal from 1e6 out, 7 away from the ball's centre, overlaps every
  // cube (8,000 > 4,096: tried for every point instead of filling a pair per cube; a pillow node
  // run 300 cells off once filled memory so) and contains no piece's centroid; a tetrahedron
  // 100 across holding the box covers every piece.
  const Clipped c = clipped(test::sphere(1.0), 20);
  Eigen::MatrixXd V = c.body.V;
  const long n = V.rows();
  V.conservativeResize(n + 8, 3);
  V.row(n) << -1e6 + 5, -1e6 - 5, -1e6;
  V.row(n + 1) << 1e6 + 5, 1e6 - 5, 1e6;
  V.row(n + 2) << 1e6 + 5, 1e6 - 5 + 1e-3, 1e6;
  V.row(n + 3) << 1e6 + 5, 1e6 - 5, 1e6 + 1e-3;
  V.row(n + 4) << -10, -10, -10;
  V.row(n + 5) << 100, -10, -10;
  V.row(n + 6) << -10, 100, -10;
  V.row(n + 7) << -10, -10, 100;
  Eigen::MatrixXi needle(1, 4), all(1, 4);
  needle << int(n), int(n + 1), int(n + 2), int(n + 3);
  all << int(n + 4), int(n + 5), int(n + 6), int(n + 7);
  const UncoveredVolume none = uncovered_volume(c.body, c.g, V, needle);
  CHECK(none.lost == Approx(none.body).epsilon(1e-12));
  CHECK(uncovered_volume(c.body, c.g, V, all).lost == 0);
}

TEST_CASE("uncovered_volume: hexahedra of the inside cubes leave out the rest of the body",
          "[volume]") {
  // The grid's cubes with 8 inside nodes as hexahedra: lost = body - (their number) h^3, up to the
  // grid nodes warped onto F = 0 (cut_tetrahedra: within 0.2 of an edge from its cut point), whose
  // pieces reach into a neighbouring cube.
  const Clipped c = clipped(test::sphere(1.0), 14);
  const RegularGrid& g = c.g;
  std::vector<Eigen::Matrix<int, 1, 8>> cubes;
  Eigen::MatrixXd V(g.size(), 3);
  for (long k = 0; k < g.nodes(2); ++k)
    for (long j = 0; j < g.nodes(1); ++j)
      for (long i = 0; i < g.nodes(0); ++i)
        V.row(g.index(i, j, k)) = g.point(i, j, k).transpose();
  for (long k = 0; k + 1 < g.nodes(2); ++k)
    for (long j = 0; j + 1 < g.nodes(1); ++j)
      for (long i = 0; i + 1 < g.nodes(0); ++i) {
        Eigen::Matrix<int, 1, 8> h; // VTK order
        h << int(g.index(i, j, k)), int(g.index(i + 1, j, k)), int(g.index(i + 1, j + 1, k)),
            int(g.index(i, j + 1, k)), int(g.index(i, j, k + 1)), int(g.index(i + 1, j, k + 1)),
            int(g.index(i + 1, j + 1, k + 1)), int(g.index(i, j + 1, k + 1));
        bool inside = true;
        for (int n = 0; n < 8; ++n)
          inside = inside && c.S(h(n)) > 1e-12;
        if (inside)
          cubes.push_back(h);
      }
  Eigen::MatrixXi C(long(cubes.size()), 8);
  for (size_t r = 0; r < cubes.size(); ++r)
    C.row(long(r)) = cubes[r];
  const UncoveredVolume u = uncovered_volume(c.body, g, V, C);
  const double cube = g.spacing.prod(), expected = u.body - double(C.rows()) * cube;
  CHECK(std::abs(u.lost - expected) < 0.02 * expected); // measured 1.1 %
}

TEST_CASE("cell_keeping: the largest candidate cell whose predicted loss fits the budget",
          "[volume]") {
  // Candidates h 2^(-k / 32). Walls of local thickness 0.1 and 0.2 (volumes 0.3, 0.2) at h = 0.05,
  // budget 0.25: the 0.1 wall must stay, so the cell is the largest candidate <= 0.1 / 4.5 (the
  // 0.2 wall stays too); budget 0.35: only the 0.2 wall must stay, <= 0.2 / 4.5.
  UncoveredVolume u;
  u.body = 10, u.lost = 0.5;
  u.lost_by_thickness = {{0.1, 0.3}, {0.2, 0.2}};
  const double h = 0.05, step = std::exp2(-1.0 / 32);
  for (const auto& [budget, thickness] : {std::pair{0.25, 0.1}, std::pair{0.35, 0.2}}) {
    const double cell = cell_keeping(u, h, budget, 4.5, 6);
    CHECK(cell <= thickness / 4.5);
    CHECK(cell > step * thickness / 4.5);
  }
  CHECK(cell_keeping(u, h, 0.5, 4.5, 6) == 0); // all within the budget
  // A loss from a wall 10 cells thick (an edge) shrinks as the cell: half the cell halves it.
  u.lost_by_thickness = {{10 * h, 0.5}};
  CHECK(cell_keeping(u, h, 0.25, 4.5, 6) == h / 2);
}

namespace {

// The projected layer's mesh of f at cell h, its info and volume.
struct Layered {
  VolumeMeshInfo info;
  double volume = 0;
};

Layered layered(const ImplicitFunction& f, VolumeElements e, double h) {
  VolumeMeshOptions o;
  o.elements = e;
  o.boundary = VolumeBoundary::projected;
  o.cell = h;
  Layered out;
  const VolumeMesh m = volume_mesh(f, o, &out.info);
  out.volume = m.C.rows() > 0 ? volume_quality(m.V, m.C).volume : 0;
  return out;
}

} // namespace

TEST_CASE("volume_mesh: the projected layer reports the thin walls it loses", "[volume]") {
  // A spherical shell of radius 0.25 and thickness T = 0.1 (every wall orientation, smooth): at
  // h = T / 2 no cell lies inside the wall and the layer loses it (measured: hexahedra 96 %,
  // tetrahedra 50 %), the diagnostic says so and measures T (0.0962: 2 V / A of the shell is
  // 0.974 T); the cell it suggests (cell_keeping: T / 4.65 from the local thickness) keeps the
  // wall (measured 0 lost; on shells of radius 0.4, T = 0.1 and 0.06: 0 lost at T / 4.5, 28-35 %
  // at T / 4 on two of the three; docs/benchmarks.md).
  for (const double T : {0.1}) {
    const ImplicitFunction shell = test::implicit(
        [T](double x, double y, double z) {
          const double r = std::sqrt(x * x + y * y + z * z) - 0.25;
          return T * T / 4 - r * r;
        },
        test::cube_box(0.32));
    for (const VolumeElements e : {VolumeElements::hexahedra, VolumeElements::tetrahedra}) {
      INFO("shell T = " << T << (e == VolumeElements::hexahedra ? ", hex" : ", tet"));
      const Layered coarse = layered(shell, e, T / 2);
      CHECK(coarse.info.lost_fraction() > 20 * kLostVolumeWarning);
      CHECK(coarse.info.suggested_cell > 0);
      if (e == VolumeElements::hexahedra) { // (nearly) all lost: the thickness is T's
        CHECK(coarse.info.coverage.thickness() == Approx(T).epsilon(0.05));
        CHECK(coarse.info.suggested_cell == Approx(T / kCellsAcrossWall).epsilon(0.05));
      }
      if (e == VolumeElements::tetrahedra)
        continue; // the same at the suggested cell, measured (0 lost); 4x the time under ASan
      const Layered fine = layered(shell, e, coarse.info.suggested_cell);
      CHECK(fine.info.lost_fraction() < kLostVolumeWarning);
      // Nothing lost, and the mesh's volume is the clipped grid's (measured: within 0.02 %).
      CHECK(std::abs(fine.info.coverage.body - fine.volume) < 0.002 * fine.info.coverage.body);
    }
  }
  // Flat discs (a slab AND a ball, R0; T = 0.2, radius 0.5) skew to the grid, 2 cells thick: lost
  // and said so. (Their sharp rims cost the layer 0.5-1.7 % even at T / 12: the smoothed normals
  // cut the 90-degree edges; docs/benchmarks.md.)
  for (const Eigen::Vector3d& n0 :
       {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.3, -0.2, 1), Eigen::Vector3d(1, 1, 1)}) {
    const Eigen::Vector3d n = n0.normalized();
    const ImplicitFunction disc = test::implicit(
        [n](double x, double y, double z) {
          const double s = n.dot(Eigen::Vector3d(x, y, z));
          return test::r0_and(0.01 - s * s, 0.25 - x * x - y * y - z * z);
        },
        test::cube_box(0.55));
    for (const VolumeElements e : {VolumeElements::hexahedra, VolumeElements::tetrahedra}) {
      INFO("disc, normal " << n.transpose()
                           << (e == VolumeElements::hexahedra ? ", hex" : ", tet"));
      const Layered coarse = layered(disc, e, 0.1);
      CHECK(coarse.info.lost_fraction() > 20 * kLostVolumeWarning); // measured 57-100 %
      CHECK(coarse.info.coverage.thickness() > 0.1);
      CHECK(coarse.info.coverage.thickness() < 0.2);
    }
  }
}
