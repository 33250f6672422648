// interlin mesh --volume as a user meets it: a model in, .msh/.vtu/.inp and the boundary surface
// out, the quality summary, the seed's counts with --seed-rule, and usage errors.
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/meshing/mesh_check.h"

#include "support/cli_runner.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

using namespace interlin::test;

namespace {

const char* const kBall = "% unit ball\nbox(-1.2, -1.2, -1.2, 1.2, 1.2, 1.2);\n"
                          "res = 1 - x^2 - y^2 - z^2;\n";

// The summary's boundary line "B nodes, Z on F = 0 (P %, max |F| M), U not projected, H held
// ...": Z is B less the held and not projected nodes (the projected layer holds the nodes it
// could not project, dual hexahedra count them apart), P = 100 Z / B to the 3 digits printed;
// ", max |F| M" only when Z > 0 (no maximum over no node).
void check_boundary_line(const std::string& out) {
  const size_t at = out.find("  boundary     ");
  REQUIRE(at != std::string::npos);
  const std::string line = out.substr(at, out.find('\n', at) - at);
  INFO(line);
  long boundary = 0, on_zero = 0, unprojected = 0, held = 0;
  double percent = 0;
  REQUIRE(std::sscanf(line.c_str(), "  boundary     %ld nodes, %ld on F = 0 (%lf %%", &boundary,
                      &on_zero, &percent) == 3);
  CHECK((line.find(" %, max |F| ") != std::string::npos) == (on_zero > 0));
  const size_t rest = line.find("), ");
  REQUIRE(rest != std::string::npos);
  REQUIRE(std::sscanf(line.c_str() + rest, "), %ld not projected, %ld held short of it",
                      &unprojected, &held) == 2);
  CHECK(on_zero <= boundary - held);
  CHECK(on_zero >= boundary - held - unprojected);
  CHECK(percent == Approx(100.0 * double(on_zero) / double(boundary)).epsilon(5e-3));
}

} // namespace

TEST_CASE("CLI mesh --volume: usage errors", "[cli][mesh][volume]") {
  TempDir d("climeshvol");
  write_file(d / "ball.rf", kBall);
  const std::string m = d / "ball.rf";
  for (const std::string& bad : std::vector<std::string>{
           "mesh " + m + " -o x.msh --volume prism",                         // unknown kind
           "mesh " + m + " -o x.xyz --volume tet",                           // unknown format
           "mesh " + m + " -o x.stl --margin 0.2",                           // needs --volume
           "mesh " + m + " -o x.msh --volume tet --margin 1",                // range
           "mesh " + m + " -o x.msh --volume tet --seed-rule --margin 0.1",  // exclusive
           "mesh " + m + " -o x.msh --volume hex --subboxes 2",              // surface only
           "mesh " + m + " -o x.msh --volume hex --sweeps -1",               // range
           "mesh " + m + " -o x.msh --volume hex --adapt 0",                 // range
           "mesh " + m + " -o x.msh --volume tet --adapt 1 --adapt-delta 1", // range
           "mesh " + m + " -o x.msh --volume tet --adapt-delta 0.1",         // needs --adapt
           "mesh " + m + " -o x.msh --volume tet --lattice fcc",             // unknown lattice
           "mesh " + m + " -o x.msh --volume hex --lattice bcc",             // tetrahedra only
           "mesh " + m + " -o x.msh --volume tet --boundary projected --lattice kuhn", // cut only
           "mesh " + m + " -o x.stl --lattice bcc", // needs --volume
           "mesh " + m + " -o x.stl --adapt 1"}) {  // needs --volume
    const Run r = run(bad + " -q");
    INFO(bad << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_THAT(r.err, Catch::StartsWith("interlin mesh: "));
  }
  CHECK(files_in(d) == 1);
}

TEST_CASE("CLI mesh --volume: a ball in every format with the quality summary",
          "[cli][mesh][volume]") {
  TempDir d("climeshvol");
  write_file(d / "ball.rf", kBall);
  for (const std::string kind : {"tet", "hex"}) {
    const Run r = run("mesh " + (d / "ball.rf") + " --volume " + kind + " --resolution 16 -o " +
                      (d / "b.msh") + " -o " + (d / "b.vtu") + " -o " + (d / "b.inp") + " -o " +
                      (d / "b.ply"));
    INFO(kind << ": " << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("inverted 0") && Catch::Contains("0 not projected") &&
                          Catch::Contains("dihedral angles"));
    CHECK_THAT(r.out, Catch::Contains(kind == "tet" ? "tetrahedra" : "hexahedra"));
    CHECK_THAT(slurp(d / "b.msh"), Catch::StartsWith("$MeshFormat\n4.1 0 8\n"));
    CHECK_THAT(slurp(d / "b.vtu"), Catch::Contains("<VTKFile type=\"UnstructuredGrid\""));
    CHECK_THAT(slurp(d / "b.inp"), Catch::Contains(kind == "tet" ? "TYPE=C3D4" : "TYPE=C3D8"));
    // The boundary surface: closed, genus 0, the ball's volume to a few per cent (h = 0.15).
    Eigen::MatrixXd V;
    Eigen::MatrixXi F;
    interlin::read_mesh(d / "b.ply", V, F);
    const interlin::MeshReport s = interlin::check_mesh(V, F);
    CHECK(s.watertight());
    CHECK(s.genus == 0);
    CHECK(s.volume == Approx(4 * M_PI / 3).epsilon(0.03));
  }
}

TEST_CASE("CLI mesh --volume --seed-rule: seed 003's counts for body (11)", "[cli][mesh][volume]") {
  TempDir d("climeshvol");
  // Digest 003 §11.1: 12,948 inner tetrahedra + 3 x 4332 layer, 2158 boundary nodes; 2976 inner
  // hexahedra + 3072 layer, 3064 boundary nodes. The seed's rule (margin 0) leaves layer elements
  // of zero thickness where nodes lie on F = 0 (its §6.3: "minimum angle 1 degree, degenerate
  // hexahedra"): the summary is printed, and a mesh with an inverted element is refused (exit 1,
  // nothing written).
  const struct {
    std::string kind, counts, boundary;
  } cases[] = {{"tet", "25944 tetrahedra (12948 inner cells, 12996 in the boundary layer)",
                "boundary     2158 nodes, "},
               {"hex", "6048 hexahedra (2976 inner cells, 3072 in the boundary layer)",
                "boundary     3064 nodes, "}};
  for (const auto& c : cases) {
    const Run r = run("mesh " INTERLIN_DATA_DIR "/models/body11.rf -o " + (d / "m.inp") +
                      " --volume " + c.kind + " --resolution 20 --seed-rule --sweeps 0 -q");
    INFO(c.kind << ": " << r.out << r.err);
    CHECK_THAT(r.out, Catch::Contains(c.counts) && Catch::Contains(c.boundary));
    check_boundary_line(r.out);
    CHECK((r.status == 0 || r.err.find("inverted elements") != std::string::npos));
    CHECK(files_in(d) == (r.status == 0 ? 1u : 0u));
    fs::remove(d / "m.inp");
  }
}

TEST_CASE("CLI mesh --volume tet --adapt: refinement where the model's field varies",
          "[cli][mesh][volume]") {
  // A peak of g at (0.5, 0, 0): the first pass splits the elements where g changes by more than
  // 0.2 of its range (near the peak) and their vertex neighbours; the mesh stays valid, its new
  // boundary nodes on F = 0.
  TempDir d("climeshvol");
  write_file(d / "ball.rf", std::string(kBall) + "g = 1 / (0.05 + (x - 0.5)^2 + y^2 + z^2);\n");
  const std::string base =
      "mesh " + (d / "ball.rf") + " --volume tet --resolution 12 -o " + (d / "b.vtu");
  const Run plain = run(base);
  const Run adapted = run(base + " --adapt 2 --adapt-var g");
  INFO(plain.out << adapted.out << adapted.err);
  REQUIRE(plain.status == 0);
  REQUIRE(adapted.status == 0);
  CHECK_THAT(adapted.out,
             Catch::Contains("adapted      2 passes") && Catch::Contains("inverted 0"));
  auto count = [](const std::string& out) {
    const size_t at = out.find("elements     ");
    return std::stol(out.substr(at + 13));
  };
  CHECK(count(adapted.out) > count(plain.out));
  const size_t f = adapted.out.find("max |F| ");
  REQUIRE(f != std::string::npos);
  CHECK(std::stod(adapted.out.substr(f + 8)) < 1e-9);
  // An unknown variable is an input error naming the model.
  const Run bad = run(base + " --adapt 1 --adapt-var nosuch -q");
  CHECK(bad.status == 1);
  CHECK_THAT(bad.err, Catch::Contains("ball.rf"));
}

TEST_CASE("CLI mesh --volume hex --adapt: 3-refinement where the model's field varies",
          "[cli][mesh][volume]") {
  // The same peak on the default hexahedra: both passes split elements near it, the closure's
  // widening is reported, the mesh stays valid and its new boundary nodes reach F = 0.
  TempDir d("climeshvol");
  write_file(d / "ball.rf", std::string(kBall) + "g = 1 / (0.05 + (x - 0.5)^2 + y^2 + z^2);\n");
  const std::string base =
      "mesh " + (d / "ball.rf") + " --volume hex --resolution 10 -o " + (d / "b.vtu");
  const Run plain = run(base);
  const Run adapted = run(base + " --adapt 2 --adapt-var g");
  INFO(plain.out << adapted.out << adapted.err);
  REQUIRE(plain.status == 0);
  REQUIRE(adapted.status == 0);
  CHECK_THAT(adapted.out,
             Catch::Contains("adapted      2 passes") && Catch::Contains(" hexahedra (flagged") &&
                 Catch::Contains("nodes added by the closure") && Catch::Contains("inverted 0"));
  auto count = [](const std::string& out) {
    const size_t at = out.find("elements     ");
    return std::stol(out.substr(at + 13));
  };
  CHECK(count(adapted.out) > 2 * count(plain.out));
  check_boundary_line(adapted.out);
  CHECK(files_in(d) == 2u); // the model and the mesh
  // a pass that would exceed --max-elements: one line, exit 1, no file (the limit is checked
  // before the pass allocates its children: 2 passes of 27 per element otherwise)
  fs::remove(d / "b.vtu");
  expect_error(run(base + " --adapt 2 --adapt-delta 0 --max-elements 20000 -q"), 1,
               "--adapt: the refinement would make");
  CHECK(files_in(d) == 1u);
}

TEST_CASE("CLI mesh --volume hex --adapt: a pass that leaves children folded is undone",
          "[cli][mesh][volume][heavy]") {
  // The valve at cell 0.4 or 0.5: pass 2 splits children in walls thinner than a cell, some stay
  // folded; the mesh after pass 1 is written with a warning (before: refused, exit 1, no mesh).
  TempDir d("climeshvol");
  const Run r = run("mesh " + std::string(INTERLIN_DATA_DIR) +
                    "/models/valve.rf --volume hex --cell 0.5 --adapt 2 -o " + (d / "v.vtu"));
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("adapted      1 passes") &&
                        Catch::Contains("; pass 2 undone: ") && Catch::Contains("inverted 0"));
  CHECK_THAT(r.err, Catch::Contains("warning: --adapt: pass 2 left ") &&
                        Catch::Contains("the mesh after pass 1 is written"));
  CHECK(files_in(d) == 1u);
}

TEST_CASE("CLI mesh --volume: the volume the projected layer loses is reported",
          "[cli][mesh][volume]") {
  // A spherical shell 0.1 thick: at cell 0.05 the hexahedral layer has almost no cell to stand on
  // (measured: 95.8 % of the volume lost): a coverage line, and one warning naming the fix; -q
  // keeps the summary but not the warning. At cell 0.1 no cell is inside: the error names it.
  TempDir d("climeshvol");
  write_file(d / "shell.rf", "box(-0.32, -0.32, -0.32, 0.32, 0.32, 0.32);\n"
                             "r = sqrt(x^2 + y^2 + z^2) - 0.25;\nres = 0.0025 - r^2;\n");
  const std::string mesh = "mesh " + (d / "shell.rf") + " -o " + (d / "s.vtu") + " --volume ";
  const Run r = run(mesh + "hex --cell 0.05 --boundary projected");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("coverage     95.8 % of the body's volume left out"));
  CHECK_THAT(r.err, Catch::Contains("\nwarning: the mesh leaves out 96 % of the body's volume "
                                    "(walls about 0.0962 thick have no inner cell under the "
                                    "boundary layer: use --cell 0.021 or smaller, or --volume "
                                    "tet)\n"));
  check_boundary_line(r.out); // measured: 48 nodes, all held
  const Run quiet = run(mesh + "hex --cell 0.05 --boundary projected -q");
  CHECK(quiet.err.empty());
  CHECK_THAT(quiet.out, Catch::Contains("coverage"));
  const Run none = run(mesh + "hex --cell 0.1 --boundary projected -q");
  CHECK(none.status == 1);
  CHECK_THAT(none.err, Catch::Contains("no grid cell lies inside the body (walls about") &&
                           Catch::Contains("or --volume tet)"));
  // Dual hexahedra keep the wall's node layers (measured: 6.0 % left out where the wall holds no
  // node) and the warning says so.
  const Run dual = run(mesh + "hex --cell 0.05 --boundary dual");
  REQUIRE(dual.status == 0);
  CHECK_THAT(dual.out, Catch::Contains("inverted 0\n"));
  check_boundary_line(dual.out); // measured: 564 of 988 on F = 0
  const size_t c = dual.out.find("coverage     ");
  REQUIRE(c != std::string::npos);
  CHECK(std::stod(dual.out.substr(c + 13)) < 10);
  CHECK_THAT(dual.err, Catch::Contains("slivers under held boundary points): use --cell"));
  // Pillowed hexahedra: every boundary node on F = 0 (the wall is 2 cells thick: one or two node
  // layers, each face with its own surface points), none inverted.
  const Run pillow = run(mesh + "hex --cell 0.05 --boundary pillow -q");
  REQUIRE(pillow.status == 0);
  CHECK_THAT(pillow.out, Catch::Contains("inverted 0\n"));
  check_boundary_line(pillow.out);
  CHECK_THAT(pillow.out, Catch::Contains(" on F = 0 (100 %, max |F| "));
  CHECK_THAT(pillow.out, Catch::Contains("0 not projected, 0 held"));
  // The clipped grid (default tetrahedra) loses nothing: no coverage line.
  const Run cut = run(mesh + "tet --cell 0.05 -q");
  CHECK(cut.status == 0);
  CHECK_THAT(cut.out, !Catch::Contains("coverage"));
}

TEST_CASE("CLI mesh --volume: a body that reaches the box is warned about as for surfaces",
          "[cli][mesh][volume]") {
  // The ball cut by --box at z = 0: the surface mesh and both volume meshes name the same grid
  // nodes (the same grid and the same check), once; -q keeps the summary and drops the warning.
  // Kuhn tetrahedra and hexahedra with the projected layer: BCC tetrahedra (the default) and the
  // dual and pillowed hexahedra pad the grid by a cell, so they name the padded grid's outer
  // nodes.
  TempDir d("climeshvol");
  write_file(d / "ball.rf", kBall);
  const std::string base =
      "mesh " + (d / "ball.rf") + " --resolution 12 --box -1.2,-1.2,0,1.2,1.2,1.2";
  const Run surface = run(base + " -o " + (d / "b.stl"));
  REQUIRE(surface.status == 0);
  const size_t at = surface.err.find("warning: the body reaches the box at ");
  REQUIRE(at != std::string::npos);
  const std::string warning = surface.err.substr(at, surface.err.find('\n', at) + 1 - at);
  CHECK_THAT(warning, Catch::EndsWith(" grid nodes; the mesh is cut by the box there\n"));
  for (const std::string kind : {"tet", "hex"}) {
    const std::string layer = kind == "hex" ? " --boundary projected" : " --lattice kuhn";
    const Run r = run(base + " -o " + (d / "b.vtu") + " --volume " + kind + layer);
    INFO(kind << ": " << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.err, Catch::Contains(warning));
    CHECK(r.err.find("warning: the body reaches") == r.err.rfind("warning: the body reaches"));
    const Run quiet = run(base + " -o " + (d / "b.vtu") + " --volume " + kind + layer + " -q");
    CHECK(quiet.err.empty());
    CHECK_THAT(quiet.out, Catch::Contains("inverted 0"));
  }
  const Run bcc = run(base + " -o " + (d / "b.vtu") + " --volume tet");
  CHECK(bcc.status == 0);
  CHECK_THAT(bcc.err, Catch::Contains("warning: the body reaches the box at "));
  // In the model's own box the ball reaches nothing: no warning.
  const Run inside =
      run("mesh " + (d / "ball.rf") + " --resolution 12 --volume tet -o " + (d / "b.vtu"));
  CHECK_THAT(inside.err, !Catch::Contains("reaches the box"));
}

TEST_CASE("CLI mesh: a rod 3 default cells across is meshed again at a finer cell for the "
          "facets' sag, with the cell given a warning names one",
          "[cli][mesh][volume][sag]") {
  // Radius 0.05, length 4: volume 0.01 pi. On the default grid (128 cells along z, 3 across) the
  // tetrahedra's facets leave out 3.7 % and the surface's 13 % (facet_sag); the default grid is
  // refined until within 0.5 % (measured -0.33 % and -0.43 %).
  TempDir d("climeshsag");
  write_file(d / "rod.rf", "box(-0.1, -0.1, -2.1, 0.1, 0.1, 2.1);\n"
                           "res = rfAND(1 - (x^2 + y^2) / 0.0025, 1 - z^2 / 4);\n");
  const double exact = 0.01 * M_PI;
  for (const std::string& kind : {std::string(" --volume tet"), std::string("")}) {
    const std::string out = d / (kind.empty() ? "r.stl" : "r.vtu");
    const Run r = run("mesh " + (d / "rod.rf") + " -o " + out + kind);
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains("(the default cell 0.03281 refined: its facets left out"));
    CHECK(r.err.find("warning") == std::string::npos);
    const size_t at = r.out.find("  geometry     volume ");
    REQUIRE(at != std::string::npos);
    const double volume = std::stod(r.out.substr(at + 22));
    CHECK(std::abs(volume - exact) < 0.005 * exact);
    CHECK_THAT(r.out, Catch::Contains("  sag          facets up to "));
    const Run given = run("mesh " + (d / "rod.rf") + " -o " + out + kind + " --resolution 128");
    INFO(given.out << given.err);
    CHECK(given.status == 0);
    CHECK_THAT(given.out, Catch::Contains(" nodes, cell 0.03281, "));
    CHECK_THAT(given.err, Catch::Contains("of the body's volume: use --cell 0.0"));
  }
}
