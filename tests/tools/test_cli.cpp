// The interlin executable as a user meets it: outputs, summaries, and one clear error line with
// a non-zero exit and no output file for every kind of bad input.
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

// A valid 3-section CSV body (square-ish profiles at z = 0, 1, 2).
std::string good_csv() {
  std::string s = "section,index,x,y,z\n";
  for (int k = 0; k < 3; ++k) {
    const double r = 1 + 0.1 * k;
    const double pts[6][2] = {{r, 0},  {0.5 * r, 0.8 * r},   {-0.5 * r, 0.8 * r},
                              {-r, 0}, {-0.5 * r, -0.8 * r}, {0.5 * r, -0.8 * r}};
    for (int i = 0; i < 6; ++i)
      s += std::to_string(k) + "," + std::to_string(i) + "," + std::to_string(pts[i][0]) + "," +
           std::to_string(pts[i][1]) + "," + std::to_string(k) + "\n";
  }
  return s;
}

// Exactly one line on stderr, starting with "interlin: " and containing `what`; exit 1; the
// directory holds nothing but the input file(s) (no output, no temporary).
void expect_one_error(const TempDir& d, const Run& r, const std::string& what, size_t files = 1) {
  INFO("stderr: " << r.err);
  CHECK(r.status == 1);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Catch::StartsWith("interlin: ") && Catch::Contains(what));
  CHECK(files_in(d) == files);
}

} // namespace

TEST_CASE("CLI: help and usage errors", "[cli]") {
  TempDir d("cli");
  Run r = run("--help");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("interlin loft"));
  r = run("loft --help");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("--samples NU,NV") && Catch::Contains("--align first|le|te"));
  r = run("");
  CHECK(r.status == 2);
  r = run("frobnicate");
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("unknown command"));
  write_file(d / "s.csv", good_csv());
  for (const std::string& bad :
       std::vector<std::string>{"loft " + (d / "s.csv") + " -o x.stl --bogus",
                                "loft " + (d / "s.csv") + " -o x.stl --samples 2,9",
                                "loft " + (d / "s.csv") + " -o x.xyz",
                                "loft " + (d / "s.csv") + " -o x.stl --align middle",
                                "loft " + (d / "s.csv"), std::string("loft -o x.stl")}) {
    r = run(bad);
    INFO(bad << " -> " << r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  }
}

TEST_CASE("CLI: the main job writes every output and reports exactness", "[cli]") {
  TempDir d("cli");
  const Run r = run("loft " INTERLIN_DATA_DIR "/rotor37/sections.csv -o " + (d / "b.stl") + " -o " +
                    (d / "b.igs") + " -o " + (d / "b.json") + " -o " + (d / "b.png") + " -o " +
                    (d / "b.obj") + " -o " + (d / "b.step") + " --units cm --cap -q");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty()); // -q: nothing on stderr
  CHECK_THAT(r.out, Catch::Contains("13 (2574 points)") && Catch::Contains("watertight"));
  for (const char* f : {"b.stl", "b.igs", "b.json", "b.png", "b.obj", "b.step"})
    CHECK(fs::file_size(d / f) > 1000);
  // --cap: the STEP file is one solid (OpenCASCADE reads it back in test_occt_step), in cm.
  const std::string step = slurp(d / "b.step");
  CHECK_THAT(step, Catch::StartsWith("ISO-10303-21;") && Catch::Contains("MANIFOLD_SOLID_BREP") &&
                       Catch::Contains("CLOSED_SHELL") &&
                       Catch::Contains("SI_UNIT(.CENTI.,.METRE.)"));
  CHECK(slurp(d / "b.png").substr(1, 3) == "PNG");
  CHECK(slurp(d / "b.igs").find("128,") != std::string::npos);
  // Deterministic: the same run gives the same bytes.
  TempDir e("cli");
  REQUIRE(run("loft " INTERLIN_DATA_DIR "/rotor37/sections.csv -o " + (e / "b.stl") + " -o " +
              (e / "b.png") + " --cap -q")
              .status == 0);
  CHECK(slurp(d / "b.stl") == slurp(e / "b.stl"));
  CHECK(slurp(d / "b.png") == slurp(e / "b.png"));
}

TEST_CASE("CLI: hold-out study prints per-section and overall distances", "[cli]") {
  TempDir d("cli");
  const Run r = run("loft " INTERLIN_DATA_DIR "/rotor37/sections.csv --holdout 2 -o " +
                    (d / "h.csv") + " -q");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("all 6 withheld sections: max 0.01899"));
  const std::string report = slurp(d / "h.csv");
  CHECK(std::count(report.begin(), report.end(), '\n') == 1 + 6 * 198);
  CHECK_THAT(report, Catch::StartsWith("section,index,line,x,y,z,distance\n"));
  const Run w = run("loft " INTERLIN_DATA_DIR "/rotor37/sections.csv --withhold 5 -q");
  CHECK(w.status == 0);
  CHECK_THAT(w.out, Catch::Contains("all 1 withheld sections"));
}

TEST_CASE("CLI: bad input gives one error line naming file and line, exit 1, no output", "[cli]") {
  TempDir d("cli");
  const std::string in = d / "s.csv", out = " -o " + (d / "o.stl") + " -o " + (d / "o.igs");
  struct Case {
    std::string name, content, expect;
  };
  const std::string head = "section,index,x,y,z\n";
  const std::vector<Case> cases = {
      {"empty file", "", "s.csv: "},
      {"no header", "1,2,3,4,5\n", "s.csv:1: "},
      {"non-numeric", head + "0,0,1,abc,0\n", "s.csv:2: "},
      {"NaN", head + "0,0,1,nan,0\n", "s.csv:2: "},
      {"infinity", head + "0,0,1,inf,0\n", "s.csv:2: "},
      {"too few points", good_csv() + "3,0,0,0,5\n3,1,1,0,5\n3,2,0,1,5\n", "s.csv:20: "},
      {"one section", head + "0,0,1,0,0\n0,1,0,1,0\n0,2,-1,0,0\n0,3,0,-1,0\n",
       "need at least 2 sections"},
      {"ragged row", head + "0,0,1,0\n", "s.csv:2: "},
      {"split runs without index", "section,x,y,z\n0,1,0,0\n0,0,1,0\n1,1,0,1\n0,-1,0,0\n",
       "s.csv:5: "},
      {"identical sections",
       [] {
         std::string s = "section,index,x,y,z\n";
         for (int k = 0; k < 2; ++k)
           for (int i = 0; i < 4; ++i)
             s += std::to_string(k) + "," + std::to_string(i) + "," + std::to_string(i % 2) + "," +
                  std::to_string(i / 2) + ",0\n";
         return s;
       }(),
       "identical"},
  };
  for (const Case& c : cases) {
    INFO(c.name);
    write_file(in, c.content);
    expect_one_error(d, run("loft " + in + out + " -q"), c.expect);
  }
  fs::remove(in);
  expect_one_error(d, run("loft " + (d / "missing.csv") + out + " -q"), "missing.csv: cannot open",
                   0);
  // A degree the sections cannot carry is a property of the file: named with the file.
  write_file(in, good_csv());
  expect_one_error(d, run("loft " + in + out + " --degree 7 -q"), "s.csv: ");
  // Unwritable output: nothing is written, not even the outputs that could be.
  expect_one_error(d, run("loft " + in + " -o " + (d / "o.stl") + " -o " + (d / "no/dir/o.igs")),
                   "no/dir");
}

TEST_CASE("CLI: repeated points are dropped with a warning naming the line", "[cli]") {
  TempDir d("cli");
  // No index column: file order. Line 9 repeats line 8 (section 1, second point).
  std::string csv = "section,x,y,z\n";
  const char* profile[] = {"1,0", "0.5,0.8", "-0.5,0.8", "-1,0", "-0.5,-0.8", "0.5,-0.8"};
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 6; ++i) {
      csv += std::to_string(k) + "," + profile[i] + "," + std::to_string(k) + "\n";
      if (k == 1 && i == 1)
        csv += std::to_string(k) + "," + profile[i] + "," + std::to_string(k) + "\n";
    }
  write_file(d / "s.csv", csv);
  const Run r = run("loft " + (d / "s.csv") + " -o " + (d / "o.json"));
  INFO(r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("warning: ") && Catch::Contains("s.csv:10:"));
  CHECK(fs::exists(d / "o.json"));
}
