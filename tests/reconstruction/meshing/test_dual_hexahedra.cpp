// Dual hexahedra (Zhang & Bajaj 2006; VolumeBoundary::dual) on a family of thin walls: discs of
// thickness T = 0.3 .. 1.5 cells at four orientations, where the projected layer (no inner cell
// under it) loses the whole wall.
#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "support/test_implicits.h"

#include <catch2/catch.hpp>

#include <cmath>

using namespace interlin;

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
      CHECK(q.min_scaled_jacobian >= 0.2); // the hold's threshold; measured 0.21 .. 0.79
      CHECK(boundary_facets(m.C).rows() == m.B.rows());
      CHECK(check_mesh(m.V, triangulate_quads(m.V, m.B)).boundary_edges == 0);
      CHECK(info.max_boundary_f < 1e-8);
      const double error = (q.volume - exact) / exact;
      INFO("volume error " << error << ", the projected layer's " << layer_error);
      if (n0.x() == 0 && n0.y() == 0) {
        // A wall on a node layer keeps its volume at any thickness but the rim, where the last
        // cells' points lie on the rim's edge: about h / 2 of the radius (h / R = 8 %), measured
        // -6.7 .. -7.7 %.
        CHECK(std::abs(error) < 0.1);
      } else {
        // Oblique walls: nodes inside the wall are a staircase; cells with the wall's two faces
        // in them have one point, so the hexahedra of neighbouring nodes pinch there (Zhang &
        // Bajaj give such cells one point per side: not done). Measured -82 .. +27 %: more than
        // the projected layer keeps, by at least 18 % of the wall.
        CHECK(error > layer_error + 0.15);
        if (cells >= 1)
          CHECK(std::abs(error) < 0.55); // measured at most 49 % (normal (0, 1, 1), one cell)
      }
    }
}
