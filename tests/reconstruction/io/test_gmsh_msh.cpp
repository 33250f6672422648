// Independent check of the .msh writer: Gmsh's own library (libgmsh-dev) reads our MSH 4.1 files
// back: the same nodes (exact doubles), elements of the right types with our node order, the
// physical groups "solid" and "boundary", and Gmsh's Jacobian determinants positive at every
// element's corners (its orientation convention agrees with ours) and, for tetrahedra, equal to
// 6 x our element volume. Built only when Gmsh is found.
#include "interlin/reconstruction/io/volume_mesh_io.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "support/test_implicits.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <gmsh.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

using namespace interlin;

TEST_CASE("Gmsh reads our .msh volume meshes back", "[gmsh][volume]") {
  test::TempDir tmp("gmsh-msh");
  gmsh::initialize();
  gmsh::option::setNumber("General.Terminal", 0);
  for (const VolumeElements e : {VolumeElements::tetrahedra, VolumeElements::hexahedra}) {
    VolumeMeshOptions o;
    o.elements = e;
    o.resolution =
        20; // the seed's grid (at 10 the cylinders are 2.5 cells wide: inverted elements)
    const VolumeMesh m = volume_mesh(test::body11_function(), o);
    const bool tets = e == VolumeElements::tetrahedra;
    const std::string path = tmp.file(tets ? "tets.msh" : "hexes.msh");
    write_volume_mesh(path, m.V, m.C, m.B);
    gmsh::clear();
    gmsh::open(path);
    INFO((tets ? "tetrahedra" : "hexahedra"));
    // Nodes: every tag, coordinates bit for bit (17 significant digits).
    std::vector<std::size_t> tags;
    std::vector<double> coord, param;
    gmsh::model::mesh::getNodes(tags, coord, param, -1, -1, false, false);
    REQUIRE(long(tags.size()) == m.V.rows());
    bool same = true;
    for (size_t k = 0; k < tags.size(); ++k)
      for (int a = 0; a < 3; ++a)
        same = same && coord[3 * k + size_t(a)] == m.V(long(tags[k]) - 1, a);
    CHECK(same);
    // Elements by type, with our node order.
    const int vol_type = tets ? 4 : 5, face_type = tets ? 2 : 3;
    std::vector<std::size_t> etags, enodes;
    gmsh::model::mesh::getElementsByType(vol_type, etags, enodes);
    REQUIRE(long(etags.size()) == m.C.rows());
    bool order = true;
    for (size_t k = 0; k < etags.size(); ++k) {
      const long e = long(etags[k] - std::size_t(m.B.rows())) - 1; // tags after the facets
      for (long j = 0; j < m.C.cols(); ++j)
        order = order && long(enodes[k * size_t(m.C.cols()) + size_t(j)]) - 1 == m.C(e, j);
    }
    CHECK(order);
    etags.clear(); // Gmsh 4.8 appends to non-empty outputs
    enodes.clear();
    gmsh::model::mesh::getElementsByType(face_type, etags, enodes);
    CHECK(long(etags.size()) == m.B.rows());
    // Physical groups.
    gmsh::vectorpair groups;
    gmsh::model::getPhysicalGroups(groups);
    std::map<std::string, int> dims;
    for (const auto& [dim, tag] : groups) {
      std::string name;
      gmsh::model::getPhysicalName(dim, tag, name);
      dims[name] = dim;
    }
    CHECK(dims["solid"] == 3);
    CHECK(dims["boundary"] == 2);
    // Gmsh's Jacobians at the element corners: positive, and 6 V for our tetrahedra.
    std::vector<double> local;
    if (tets)
      local = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    else
      for (int c = 0; c < 8; ++c) // reference hexahedron [-1, 1]^3, VTK/Gmsh corner order
        for (int a = 0; a < 3; ++a) {
          const int bits[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
          local.push_back(bits[c][a] ? 1.0 : -1.0);
        }
    std::vector<double> jac, det, pts;
    gmsh::model::mesh::getJacobians(vol_type, local, jac, det, pts);
    REQUIRE(det.size() == size_t(m.C.rows()) * (tets ? 4 : 8));
    CHECK(*std::min_element(det.begin(), det.end()) > 0);
    if (tets) {
      std::vector<ElementQuality> q;
      volume_quality(m.V, m.C, 1, &q);
      etags.clear();
      enodes.clear();
      gmsh::model::mesh::getElementsByType(vol_type, etags, enodes);
      double worst = 0;
      for (size_t k = 0; k < etags.size(); ++k) {
        const long e = long(etags[k] - std::size_t(m.B.rows())) - 1;
        worst = std::max(worst, std::abs(det[4 * k] - 6 * q[size_t(e)].volume) /
                                    (6 * q[size_t(e)].volume));
      }
      CHECK(worst < 1e-9);
    }
  }
  gmsh::finalize();
}
