// interlin loft --guides: the Gordon surface through sections and guide lines from the CLI,
// its report and outputs, and one FILE:LINE error for bad guide files.
#include "support/cli_runner.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

using namespace interlin::test;

namespace {

const std::string kSections = INTERLIN_DATA_DIR "/rotor37/sections.csv";
const std::string kLoft = "loft " + kSections;

// The LE (point 0) and TE (point 99) lines of the Rotor 37 table, as a guide file.
std::string edges_csv() {
  std::ifstream in(kSections);
  std::string line, le, te;
  std::getline(in, line); // header section,index,x,y,z
  while (std::getline(in, line)) {
    std::stringstream f(line);
    std::string sec, idx, rest;
    std::getline(f, sec, ',');
    std::getline(f, idx, ',');
    std::getline(f, rest);
    if (idx == "0")
      le += "LE," + sec + "," + rest + "\n";
    if (idx == "99")
      te += "TE," + sec + "," + rest + "\n";
  }
  return "guide,index,x,y,z\n" + le + te;
}

double number_after(const std::string& text, const std::string& key) {
  const size_t p = text.find(key);
  REQUIRE(p != std::string::npos);
  return std::strtod(text.c_str() + p + key.size(), nullptr);
}

} // namespace

TEST_CASE("CLI --guides: Gordon surface through sections and edge lines, outputs and report",
          "[cli][guided]") {
  TempDir d("cli-guides");
  write_file(d / "edges.csv", edges_csv());
  const Run r = run(kLoft + " --guides " + (d / "edges.csv") + " -q -o " + (d / "g.igs") + " -o " +
                    (d / "g.json") + " -o " + (d / "g.csv"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("guides       2 (LE at u = 0, TE at u = 0.503)"));
  CHECK_THAT(r.out, Catch::Contains("0 crossing(s) inserted"));
  CHECK_THAT(r.out, Catch::Contains("shape        around: convex"));
  // Exactness line: sections and guides at round-off (guarantee 1e-9 x diagonal).
  CHECK(number_after(r.out, "sections and guides") >= 0); // the line exists
  CHECK(number_after(r.out, "max |S(u_i,v_k) - P_i| = ") < 1e-12);
  CHECK(fs::exists(d / "g.igs"));
  CHECK_THAT(slurp(d / "g.json"), Catch::Contains("\"guide_ids\": \"LE,TE\""));
  // Report: 2574 section rows and 26 guide rows, each with a round-off deviation.
  const std::string csv = slurp(d / "g.csv");
  CHECK(std::count(csv.begin(), csv.end(), '\n') == 1 + 2574 + 26);
  const size_t g = csv.find("guide:TE,12,");
  REQUIRE(g != std::string::npos);
  const std::string row = csv.substr(g, csv.find('\n', g) - g);
  CHECK(std::strtod(row.substr(row.rfind(',') + 1).c_str(), nullptr) < 1e-12);
}

TEST_CASE("CLI --guides with --holdout: the edge lines shrink the hold-out distance",
          "[cli][guided]") {
  TempDir d("cli-guides");
  write_file(d / "edges.csv", edges_csv());
  const Run plain = run(kLoft + " --holdout 2 -q");
  const Run guided = run(kLoft + " --holdout 2 -q --guides " + (d / "edges.csv"));
  REQUIRE(plain.status == 0);
  REQUIRE(guided.status == 0);
  const double p = number_after(plain.out, "withheld sections: max "),
               g = number_after(guided.out, "withheld sections: max ");
  INFO("max distance without guides " << p << ", with " << g);
  CHECK(g < 0.5 * p); // docs/benchmarks.md: 0.0192 -> 0.0088
}

TEST_CASE("CLI --guides: bad guide files and options", "[cli][guided]") {
  TempDir d("cli-guides");
  write_file(d / "bad.csv", "guide,x,y,z\nLE,1,2,3\nLE,1,2x,3\n");
  Run r = run(kLoft + " --guides " + (d / "bad.csv") + " -o " + (d / "out.stl"));
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::Contains("bad.csv:3: column y: '2x' is not a number"));
  CHECK_FALSE(fs::exists(d / "out.stl"));
  // A guide far from the blade: names the guide file and line.
  write_file(d / "far.csv", "guide,x,y,z\nX,0,0,0\nX,0,0,100\n");
  r = run(kLoft + " -q --guides " + (d / "far.csv") + " -o " + (d / "out.stl"));
  CHECK(r.status == 1);
  CHECK_THAT(r.err, Catch::StartsWith("interlin: " + (d / "far.csv") + ":2: guide X passes"));
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_FALSE(fs::exists(d / "out.stl"));
  r = run(kLoft + " --guide-tolerance 1e-2 -o " + (d / "out.stl"));
  CHECK(r.status == 2);
  CHECK_THAT(r.err, Catch::Contains("--guide-tolerance needs --guides"));
  r = run(kLoft + " --guides " + (d / "far.csv") + " --guide-tolerance abc -o " + (d / "out.stl"));
  CHECK(r.status == 2);
}
