// interlin eval as a user meets it: values (and gradients) at the points of a CSV file, parameter
// overrides, and one error line with FILE:LINE (points) or FILE:LINE:COLUMN (model) and exit 1.
#include "support/cli_runner.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

using namespace interlin::test;

namespace {

std::string model(const std::string& name) {
  return std::string(INTERLIN_DATA_DIR) + "/models/" + name;
}

// Rows of a CSV text, split at commas.
std::vector<std::vector<std::string>> rows(const std::string& csv) {
  std::vector<std::vector<std::string>> r;
  std::istringstream in(csv);
  std::string line;
  while (std::getline(in, line)) {
    r.emplace_back();
    std::istringstream l(line);
    std::string f;
    while (std::getline(l, f, ','))
      r.back().push_back(f);
  }
  return r;
}

// expect_error, and nothing on stdout.
void expect_eval_error(const Run& r, int status, const std::string& what) {
  expect_error(r, status, what);
  CHECK(r.out.empty());
}

} // namespace

TEST_CASE("CLI eval: values and gradients of the impeller at digest points", "[cli][eval]") {
  TempDir d("eval");
  // any column order, extra columns ignored, comments and blank lines skipped
  write_file(d / "p.csv", "# points\nid,z,x,y\n\na,2,10,0\nb,0,0,0\nc,2,0.5,0\n");
  Run r = run("eval " + model("impeller.rf") + " " + d / "p.csv -q");
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  const auto t = rows(r.out);
  REQUIRE(t.size() == 4);
  CHECK(t[0] == std::vector<std::string>{"x", "y", "z", "F"});
  CHECK(t[1][0] == "10");
  CHECK(std::stod(t[1][3]) == Approx(0.2023382).epsilon(0).margin(5e-8)); // digest 000 T18
  CHECK(std::stod(t[2][3]) == Approx(0.2744834).epsilon(0).margin(5e-8));
  CHECK(std::stod(t[3][3]) == Approx(-0.3914788).epsilon(0).margin(5e-8));
  // with the gradient, into a file
  r = run("eval " + model("impeller.rf") + " " + d / "p.csv --gradient -o " + d / "v.csv");
  REQUIRE(r.status == 0);
  CHECK(r.out.empty());
  CHECK_THAT(r.err, Catch::Contains("evaluating at 3 points")); // progress on stderr
  const auto g = rows(slurp(d / "v.csv"));
  REQUIRE(g.size() == 4);
  CHECK(g[0] == std::vector<std::string>{"x", "y", "z", "F", "Fx", "Fy", "Fz"});
  CHECK(std::stod(g[1][3]) == Approx(0.2023382).epsilon(0).margin(5e-8));
  CHECK(g[1].size() == 7);
}

TEST_CASE("CLI eval: --set and --var", "[cli][eval]") {
  TempDir d("eval");
  const Run h = run("eval --help");
  CHECK(h.status == 0);
  CHECK_THAT(h.out, Catch::Contains("Usage: interlin eval MODEL POINTS.csv"));
  CHECK_THAT(run("--help").out, Catch::Contains("interlin eval MODEL POINTS.csv"));
  write_file(d / "p.csv", "x,y,z\n0,-14.5,2\n");
  Run r = run("eval " + model("car.rf") + " " + d / "p.csv --var fig5 -q");
  REQUIRE(r.status == 0);
  CHECK(std::stod(rows(r.out)[1][3]) > 0); // Fig. 5a trunk reaches y = -14.5
  r = run("eval " + model("car.rf") + " " + d / "p.csv --var fig5 -q --set y2=14 --set a1=9");
  REQUIRE(r.status == 0);
  CHECK(std::stod(rows(r.out)[1][3]) < 0); // Fig. 5b trunk ends at y = -14
  expect_eval_error(run("eval " + model("car.rf") + " " + d / "p.csv --set yy=1 -q"), 1,
                    "interlin: " + model("car.rf") + ": parameter 'yy' is not declared");
  expect_eval_error(run("eval " + model("car.rf") + " " + d / "p.csv --var nothing -q"), 1,
                    "does not assign the output variable 'nothing'");
  expect_eval_error(run("eval " + model("car.rf") + " " + d / "p.csv --set y2 -q"), 2,
                    "interlin eval: --set y2: expected NAME=VALUE");
  expect_eval_error(run("eval " + model("car.rf") + " -q"), 2, "expected MODEL POINTS.csv");
}

TEST_CASE("CLI eval: bad points and bad models give one error line", "[cli][eval]") {
  TempDir d("eval");
  const std::string m = model("uav.rf");
  struct Case {
    std::string points, message;
  };
  const Case cases[] = {
      {"x,y\n1,2\n", "p.csv:1: header lacks the column(s) z"},
      {"x,y,z\n1,2\n",
       "p.csv:2: expected 3 comma-separated fields (as in the header on line 1), found 2"},
      {"x,y,z\n1,abc,2\n", "p.csv:2: column y: 'abc' is not a number"},
      {"x,y,z\n1,2,nan\n", "p.csv:2: column z: 'nan' is not a finite value"},
      {"x,y,z\n1e999,2,3\n", "p.csv:2: column x: '1e999' is out of the range of a double"},
      {"x,y,z,x\n1,2,3,4\n", "p.csv:1: column x appears twice in the header (fields 1 and 4)"},
      {"x,y,z\n", "p.csv: no points after the header on line 1"},
      {"# nothing\n", "p.csv: no header"},
  };
  for (const Case& c : cases) {
    INFO(c.points);
    write_file(d / "p.csv", c.points);
    expect_eval_error(run("eval " + m + " " + d / "p.csv -q"), 1, c.message);
  }
  write_file(d / "p.csv", "x,y,z\n0,0,0\n");
  write_file(d / "bad.rf", "box(-1,-1,-1,1,1,1);\nres = sphere(x, y, z);\n");
  expect_eval_error(run("eval " + d / "bad.rf " + d / "p.csv -q"), 1,
                    "bad.rf:2:7: sphere expects 4 argument(s), got 3");
  expect_eval_error(run("eval " + d / "missing.rf " + d / "p.csv -q"), 1,
                    "missing.rf: cannot open");
  // a failed run leaves no output file
  expect_eval_error(run("eval " + d / "bad.rf " + d / "p.csv -o " + d / "out.csv -q"), 1,
                    "bad.rf:2:7");
  CHECK(!fs::exists(d / "out.csv"));
  expect_eval_error(run("eval " + m + " " + d / "p.csv -o " + d / "no/dir/out.csv -q"), 1,
                    "does not exist");
}
