// The volume-mesh writers: bad input, no partial files, the Abaqus/CalculiX deck's structure,
// and CalculiX itself (ccx, when installed) reading our .inp and solving on it: the element
// volumes it reports sum to ours, and it finds no element with a non-positive Jacobian.
#include "interlin/reconstruction/io/volume_mesh_io.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include "support/cli_runner.h"
#include "support/test_implicits.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

using namespace interlin;
namespace fs = std::filesystem;

namespace {

VolumeMesh small_mesh(VolumeElements e) {
  VolumeMeshOptions o;
  o.elements = e;
  o.resolution = 8;
  return volume_mesh(test::sphere(1.0), o);
}

} // namespace

TEST_CASE("write_volume_mesh: formats, bad input, no partial output", "[volume][io]") {
  test::TempDir tmp("volio");
  const VolumeMesh m = small_mesh(VolumeElements::tetrahedra);
  CHECK(is_volume_mesh_path("a.MSH"));
  CHECK(is_volume_mesh_path("a.vtu"));
  CHECK(is_volume_mesh_path("a.inp"));
  CHECK_FALSE(is_volume_mesh_path("a.stl"));
  CHECK_THROWS_AS(write_volume_mesh(tmp / "a.stl", m.V, m.C, m.B), std::invalid_argument);
  Eigen::MatrixXi bad = m.C;
  bad(0, 0) = int(m.V.rows());
  CHECK_THROWS_AS(write_volume_mesh(tmp / "a.msh", m.V, bad, m.B), std::invalid_argument);
  CHECK_THROWS_AS(write_volume_mesh(tmp / "a.msh", m.V, m.C, Eigen::MatrixXi::Zero(2, 4)),
                  std::invalid_argument);
  VolumeMeshFields f;
  f.node = {{"short", Eigen::VectorXd::Zero(3)}};
  CHECK_THROWS_AS(write_volume_mesh(tmp / "a.vtu", m.V, m.C, m.B, f), std::invalid_argument);
  CHECK(test::files_in(tmp) == 0);
  CHECK_THROWS_AS(write_volume_mesh(tmp / "missing/a.msh", m.V, m.C, m.B), std::runtime_error);
}

TEST_CASE("write_volume_mesh: the .inp deck names every boundary facet as an element face",
          "[volume][io]") {
  test::TempDir tmp("volinp");
  for (const VolumeElements e : {VolumeElements::tetrahedra, VolumeElements::hexahedra}) {
    const VolumeMesh m = small_mesh(e);
    const std::string path = tmp / "mesh.inp";
    write_volume_mesh(path, m.V, m.C, m.B);
    const std::string text = test::slurp(path);
    const bool tets = e == VolumeElements::tetrahedra;
    CHECK(text.find(tets ? "TYPE=C3D4" : "TYPE=C3D8") != std::string::npos);
    const auto surface = text.find("*SURFACE, NAME=BOUNDARY, TYPE=ELEMENT\n");
    REQUIRE(surface != std::string::npos);
    long lines = 0;
    std::istringstream rest(text.substr(surface));
    std::string line;
    std::getline(rest, line);
    while (std::getline(rest, line) && !line.empty() && line[0] != '*')
      ++lines;
    CHECK(lines == m.B.rows());
    // Node coordinates: CalculiX reads at most 20 characters per number; they read back to the
    // node within 1e-15 of the largest coordinate (only tiny numbers lose digits).
    std::istringstream nodes(text.substr(text.find("*NODE")));
    std::getline(nodes, line);
    long row = 0, too_long = 0;
    double worst = 0;
    while (std::getline(nodes, line) && line[0] != '*') {
      std::istringstream fields(line);
      std::string field;
      std::getline(fields, field, ',');
      for (int a = 0; a < 3 && std::getline(fields, field, ','); ++a) {
        const std::string number = field.substr(field.find_first_not_of(' '));
        too_long += number.size() > 20;
        worst = std::max(worst, std::abs(std::stod(number) - m.V(row, a)));
      }
      ++row;
    }
    CHECK(row == m.V.rows());
    CHECK(too_long == 0);
    CHECK(worst <= 1e-15 * m.V.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("CalculiX reads our .inp and integrates the same volume", "[volume][io][ccx]") {
  if (std::system("command -v ccx > /dev/null 2>&1") != 0) {
    WARN("ccx (calculix-ccx) not installed: CalculiX check skipped");
    return;
  }
  test::TempDir tmp("volccx");
  for (const VolumeElements e : {VolumeElements::tetrahedra, VolumeElements::hexahedra}) {
    const VolumeMesh m = small_mesh(e);
    write_volume_mesh(tmp / "mesh.inp", m.V, m.C, m.B);
    // A static step on the mesh: steel, the boundary nodes held, gravity; ccx reports the
    // element volumes (EVOL) and stops on any element with a non-positive Jacobian.
    std::ofstream(tmp / "job.inp") << "*INCLUDE, INPUT=mesh.inp\n"
                                      "*MATERIAL, NAME=STEEL\n*ELASTIC\n210000., 0.3\n"
                                      "*DENSITY\n7.85e-9\n"
                                      "*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL\n"
                                      "*STEP\n*STATIC\n*BOUNDARY\nBOUNDARY, 1, 3\n"
                                      "*DLOAD\nSOLID, GRAV, 9810., 0., 0., -1.\n"
                                      "*EL PRINT, ELSET=SOLID, TOTALS=ONLY\nEVOL\n*END STEP\n";
    const std::string cmd = "cd " + tmp.path().string() + " && ccx job > ccx.log 2>&1";
    INFO((e == VolumeElements::tetrahedra ? "tetrahedra" : "hexahedra"));
    REQUIRE(std::system(cmd.c_str()) == 0);
    const std::string log = test::slurp(tmp / "ccx.log"), dat = test::slurp(tmp / "job.dat");
    INFO(log.substr(0, 2000));
    CHECK(log.find("nonpositive jacobian") == std::string::npos);
    CHECK(log.find("*ERROR") == std::string::npos);
    // "volume (element, volume) for set SOLID ... total" then the number on the next line.
    const std::regex total(R"(volume[^\n]*\n\s*\n?\s*([-+0-9.Ee]+))");
    std::smatch match;
    REQUIRE(std::regex_search(dat, match, total));
    const double ccx_volume = std::stod(match[1].str());
    CHECK(ccx_volume == Approx(volume_quality(m.V, m.C).volume).epsilon(1e-6));
  }
}
