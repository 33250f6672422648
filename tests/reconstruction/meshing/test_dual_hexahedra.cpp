// Dual hexahedra (Zhang & Bajaj 2006; VolumeBoundary::dual) on a family of thin walls: discs of
// thickness T = 0.3 .. 1.5 cells at four (measured: five) orientations, where the projected layer
// (no inner cell under it) loses the whole wall.
#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "support/test_implicits.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

using namespace interlin;

namespace {

// The fraction of m's boundary points off F = 0: |F| / |grad F| (central differences, step
// 1e-6) above 1e-6 h, the distance issue 14 counts as on the surface.
double off_surface_fraction(const ImplicitFunction& f, const VolumeMesh& m, double h) {
  const Eigen::VectorXi nodes = [&] {
    std::vector<char> b(size_t(m.V.rows()), 0);
    for (long i = 0; i < m.B.size(); ++i)
      b[size_t(m.B.data()[i])] = 1;
    std::vector<int> v;
    for (size_t i = 0; i < b.size(); ++i)
      if (b[i])
        v.push_back(int(i));
    return Eigen::VectorXi(Eigen::Map<Eigen::VectorXi>(v.data(), long(v.size())));
  }();
  const double d = 1e-6;
  Points3 P(nodes.size() * 7, 3);
  for (long r = 0; r < nodes.size(); ++r)
    for (int k = 0; k < 7; ++k) {
      Eigen::RowVector3d p = m.V.row(nodes(r));
      if (k > 0)
        p((k - 1) / 2) += (k % 2 ? d : -d);
      P.row(7 * r + k) = p;
    }
  Eigen::VectorXd F(P.rows());
  f.value(P, F);
  long off = 0;
  for (long r = 0; r < nodes.size(); ++r) {
    Eigen::Vector3d grad;
    for (int a = 0; a < 3; ++a)
      grad(a) = (F(7 * r + 1 + 2 * a) - F(7 * r + 2 + 2 * a)) / (2 * d);
    off += std::abs(F(7 * r)) > 1e-6 * h * grad.norm();
  }
  return nodes.size() > 0 ? double(off) / double(nodes.size()) : 0;
}

} // namespace

TEST_CASE("volume_mesh: dual hexahedra keep walls thinner than a cell", "[volume]") {
  // The disc |n . p| <= T / 2 AND the unit ball (R0), exact volume pi (T - T^3 / 12), h = 0.08.
  const double h = 0.08;
  const Eigen::Vector3d normals[] = {{0, 0, 1}, {0, 1, 1}, {1, 2, 3}, {0.3, -0.2, 1}};
  for (const double cells : {0.3, 0.5, 1.0, 1.5})
    for (const Eigen::Vector3d& n0 : normals) {
      const Eigen::Vector3d n = n0.normalized();
      const double T = cells * h;
      const ImplicitFunction f = test::thin_disc(n, T);
      const double exact = test::thin_disc_volume(T);
      INFO("thickness " << cells << " cells, normal " << n.transpose());
      VolumeMeshOptions o;
      o.cell = h;
      o.elements = VolumeElements::hexahedra;
      o.boundary = VolumeBoundary::projected;
      const VolumeMesh layer = volume_mesh(f, o);
      const double layer_error = (volume_quality(layer.V, layer.C).volume - exact) / exact;
      CHECK(layer_error < -0.9); // measured -100 % in every case: no inner cell

      o.boundary = VolumeBoundary::dual;
      VolumeMeshInfo info;
      const VolumeMesh m = volume_mesh(f, o, &info);
      REQUIRE(m.C.rows() > 0);
      const VolumeQuality q = volume_quality(m.V, m.C);
      CHECK(q.inverted == 0);
      CHECK(q.min_scaled_jacobian >= 0.2); // the hold's threshold; measured 0.200 .. 0.50
      CHECK(boundary_facets(m.C).rows() == m.B.rows());
      CHECK(check_mesh(m.V, triangulate_quads(m.V, m.B)).boundary_edges == 0);
      CHECK(info.max_boundary_f < 1e-8);
      const double error = (q.volume - exact) / exact;
      INFO("volume error " << error << ", the projected layer's " << layer_error);
      CHECK(error > layer_error);
      if (n0.x() == 0 && n0.y() == 0) {
        // A wall on a node layer keeps its volume at any thickness but the rim, where the last
        // cells' points lie on the rim's edge: about h / 2 of the radius (h / R = 8 %), measured
        // -6.7 .. -7.7 %.
        CHECK(std::abs(error) < 0.1);
        CHECK(off_surface_fraction(f, m, h) == 0); // measured 0: no point held
      } else {
        // Oblique walls: nodes inside the wall are a staircase; cells with the wall's two faces
        // in them have one point, so the hexahedra of neighbouring nodes pinch there. Walls of a
        // cell or more keep at least 45 % (measured -51 .. +7 %); thinner ones, below the dual
        // mesh's two cells (kCellsAcrossDualWall), may lose nearly all (measured -27 .. -98 %:
        // their boundary points restored onto F = 0 land on one face; docs/benchmarks.md).
        if (cells >= 1)
          CHECK(std::abs(error) < 0.55); // measured at most 51 % (normal (0, 1, 1), one cell)
        CHECK(off_surface_fraction(f, m, h) < 0.9); // measured 24 .. 81 % off F = 0
      }
    }
}

TEST_CASE("volume_mesh: dual hexahedra on the thin-disc family (table)", "[volume][.measure]") {
  // docs/benchmarks.md (dual hexahedra, restored boundary points): one line per disc, the
  // issue's measures (the fraction off F = 0 as off_surface_fraction counts it).
  const double h = 0.08;
  const Eigen::Vector3d normals[] = {{0, 0, 1}, {0, 1, 1}, {1, 2, 3}, {0.3, -0.2, 1}, {1, 1, 1}};
  for (const double cells : {0.3, 0.5, 0.75, 1.0, 1.25, 1.5})
    for (const Eigen::Vector3d& n0 : normals) {
      const ImplicitFunction f = test::thin_disc(n0.normalized(), cells * h);
      VolumeMeshOptions o;
      o.cell = h;
      o.elements = VolumeElements::hexahedra;
      o.boundary = VolumeBoundary::dual;
      VolumeMeshInfo info;
      const VolumeMesh m = volume_mesh(f, o, &info);
      const VolumeQuality q = volume_quality(m.V, m.C);
      const double exact = test::thin_disc_volume(cells * h);
      std::printf("T %.2f cells  n (%4.1f %4.1f %4.1f)  volume %+7.2f %%  inverted %ld  min SJ "
                  "%.3f  off F=0 %5.1f %%  lost (coverage) %5.1f %%\n",
                  cells, n0.x(), n0.y(), n0.z(), 100 * (q.volume - exact) / exact, q.inverted,
                  q.min_scaled_jacobian, 100 * off_surface_fraction(f, m, h),
                  100 * info.lost_fraction());
    }
}
