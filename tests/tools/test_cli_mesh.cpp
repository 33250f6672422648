// interlin mesh as a user meets it: a model file in, a closed mesh and a preview out, the
// summary, and one clear error line with the right exit status for every kind of bad input.
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/meshing/mesh_check.h"

#include "support/cli_runner.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

using namespace interlin::test;

namespace {

// A ball of radius 1 (F = 1 - r^2) in a box with margin.
const char* const kBall = "% unit ball\nbox(-1.2, -1.2, -1.2, 1.2, 1.2, 1.2);\n"
                          "res = 1 - x^2 - y^2 - z^2;\n";

} // namespace

TEST_CASE("CLI mesh: help and usage errors", "[cli][mesh]") {
  TempDir d("climesh");
  Run r = run("--help");
  CHECK_THAT(r.out, Catch::Contains("interlin mesh MODEL -o"));
  r = run("mesh --help");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("--resolution N") && Catch::Contains("--subboxes"));
  write_file(d / "ball.rf", kBall);
  const std::string m = d / "ball.rf";
  for (const std::string& bad : std::vector<std::string>{
           "mesh " + m,                                           // no output
           "mesh -o x.stl",                                       // no model
           "mesh " + m + " -o x.xyz",                             // unknown format
           "mesh " + m + " -o x.stl --resolution 10 --cell 0.1",  // both
           "mesh " + m + " -o x.stl --resolution 0",              // range
           "mesh " + m + " -o x.stl --cell -1",                   // range
           "mesh " + m + " -o x.stl --box 0,0,0,1,1",             // 5 numbers
           "mesh " + m + " -o x.stl --box 0,0,0,1,1,abc",         // not a number
           "mesh " + m + " -o x.stl --box 1,0,0,0,1,1",           // empty box
           "mesh " + m + " -o x.stl --subboxes 2,2",              // 2 numbers
           "mesh " + m + " -o x.stl --resolution 8 --subboxes 9", // more than cells
           "mesh " + m + " -o x.stl --set r",                     // not NAME=VALUE
           "mesh " + m + " -o x.stl --bogus"}) {
    r = run(bad + " -q");
    INFO(bad << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_THAT(r.err, Catch::StartsWith("interlin mesh: "));
  }
  CHECK(files_in(d) == 1); // only the model
}

TEST_CASE("CLI mesh: a model becomes a closed mesh, a preview and a summary", "[cli][mesh]") {
  TempDir d("climesh");
  write_file(d / "ball.rf", kBall);
  const Run r = run("mesh " + (d / "ball.rf") + " -o " + (d / "b.stl") + " -o " + (d / "b.ply") +
                    " -o " + (d / "b.png") + " --resolution 40");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("41 x 41 x 41 nodes") && Catch::Contains("watertight") &&
                        Catch::Contains("genus 0") && Catch::Contains("vertices on F = 0"));
  CHECK_THAT(r.err, Catch::Contains("merged") && Catch::Contains("projecting")); // progress
  // The written mesh is closed and holds the ball (volume to O(h^2), h = 0.06: < 1 %).
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  interlin::read_mesh(d / "b.ply", V, F);
  const interlin::MeshReport m = interlin::check_mesh(V, F);
  CHECK(m.watertight());
  CHECK(m.volume == Approx(4 * M_PI / 3).epsilon(0.01));
  CHECK(slurp(d / "b.png").substr(1, 3) == "PNG");
  CHECK(fs::file_size(d / "b.stl") == 84 + 50 * std::uintmax_t(F.rows()));
  // Sub-boxes and threads change nothing but the vertex order: same counts, same volume.
  const Run s = run("mesh " + (d / "ball.rf") + " -o " + (d / "c.stl") +
                    " --resolution 40 --subboxes 3,2,5 --threads 3 -q");
  REQUIRE(s.status == 0);
  CHECK(s.err.empty());
  auto line = [](const std::string& out, const std::string& key) {
    const auto p = out.find(key);
    return out.substr(p, out.find('\n', p) - p);
  };
  CHECK(line(s.out, "  mesh") == line(r.out, "  mesh"));
  CHECK(line(s.out, "  geometry") == line(r.out, "  geometry"));
}

TEST_CASE("CLI mesh: shipped model with smoothing and flips, a cutting box", "[cli][mesh]") {
  TempDir d("climesh");
  Run r = run("mesh " INTERLIN_DATA_DIR "/models/valve.rf -o " + (d / "v.obj") +
              " --resolution 24 --smooth 1 --flip -q");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("watertight"));
  // The box cuts the valve: warned, closed along the box.
  write_file(d / "ball.rf", kBall);
  r = run("mesh " + (d / "ball.rf") + " -o " + (d / "h.off") +
          " --box -1.2,-1.2,0,1.2,1.2,1.2 --resolution 30");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("warning: the body reaches the box"));
  CHECK_THAT(r.out, Catch::Contains("watertight"));
}

TEST_CASE("CLI mesh: bad input gives one error line, exit 1, no output", "[cli][mesh]") {
  TempDir d("climesh");
  // Missing model file.
  Run r = run("mesh " + (d / "none.rf") + " -o " + (d / "x.stl") + " -q");
  CHECK(r.status == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Catch::StartsWith("interlin: ") && Catch::Contains("none.rf"));
  // A syntax error: FILE:LINE:COLUMN from the model reader.
  write_file(d / "bad.rf", "box(-1,-1,-1,1,1,1);\nres = 1 - x^2 +* y;\n");
  r = run("mesh " + (d / "bad.rf") + " -o " + (d / "x.stl") + " -q");
  CHECK(r.status == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Catch::Contains("bad.rf:2:"));
  // No surface inside the box.
  write_file(d / "empty.rf", "box(-1,-1,-1,1,1,1);\nres = -1 - x^2;\n");
  r = run("mesh " + (d / "empty.rf") + " -o " + (d / "x.stl") + " -q");
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("empty.rf: no surface in the box"));
  // Output directory missing: checked before the work.
  write_file(d / "ball.rf", kBall);
  r = run("mesh " + (d / "ball.rf") + " -o " + (d / "no/x.stl") + " -q");
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("does not exist"));
  CHECK(files_in(d) == 3); // bad.rf, empty.rf, ball.rf: no output, no temporary
}
