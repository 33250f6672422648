// interlin implicit as a user meets it: sections -> blade.ifl (omega = 0 at every input point,
// read by eval and mesh), .rf models using the .ifl as an operand, R-function models normalised,
// and one error line with exit 1 (bad input) or 2 (wrong usage) without output files.
#include "interlin/reconstruction/io/section_csv.h"
#include "support/cli_runner.h"
#include "support/test_blades.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

using namespace interlin::test;

namespace {

// Column `col` of the CSV rows after the header.
std::vector<double> column(const std::string& csv, int col) {
  std::vector<double> v;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    std::istringstream l(line);
    std::string f;
    for (int c = 0; c <= col; ++c)
      std::getline(l, f, ',');
    v.push_back(std::stod(f));
  }
  return v;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v)
    m = std::max(m, std::abs(x));
  return m;
}

} // namespace

TEST_CASE("CLI implicit: sections -> .ifl exact at the input points, meshed, combined",
          "[cli][implicit]") {
  TempDir d("implicit");
  BladeFamily fam;
  fam.sections = 5;
  fam.points = 40;
  const std::vector<interlin::Section> s = blade_sections(fam);
  interlin::write_sections_csv(d / "blade.csv", s);
  Run r = run("implicit " + d / "blade.csv -o " + d / "blade.ifl --resolution 24 -q");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK(r.err.empty());
  CHECK_THAT(r.out, Catch::Contains("exactness    max |omega| = ") &&
                        Catch::Contains("wrote        " + d / "blade.ifl"));

  // Every input point: omega = 0 to 1e-12 of the diagonal (about 2 here).
  std::string pts = "x,y,z\n";
  for (const auto& sec : s)
    for (Eigen::Index i = 0; i < sec.points.rows(); ++i) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", sec.points(i, 0), sec.points(i, 1),
                    sec.points(i, 2));
      pts += buf;
    }
  write_file(d / "points.csv", pts);
  r = run("eval " + d / "blade.ifl " + d / "points.csv --gradient -q");
  REQUIRE(r.status == 0);
  CHECK(r.out.rfind("x,y,z,F,Fx,Fy,Fz\n", 0) == 0);
  CHECK(max_abs(column(r.out, 3)) <= 2e-12);
  const std::vector<double> gx = column(r.out, 4), gy = column(r.out, 5), gz = column(r.out, 6);
  for (size_t i = 0; i < gx.size(); ++i) // the unit inward normal there
    CHECK(std::hypot(gx[i], gy[i], gz[i]) == Approx(1).epsilon(1e-9));

  // Meshed like an R-function model: closed, the body inside.
  r = run("mesh " + d / "blade.ifl -o " + d / "blade.ply --resolution 40 -q");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains(", watertight,"));
  CHECK(fs::exists(d / "blade.ply"));

  // An .rf model cuts the blade with a slab (R-conjunction keeps both zero sets exact).
  write_file(d / "cut.rf", "box(-1, -1, -0.1, 1, 1, 1.6);\n"
                           "blade = ifl(\"blade.ifl\");\n"
                           "res = and0(blade, layer(z, 0.2, 1.0));\n");
  // Sections sit at z = 0, 0.375, 0.75, 1.125, 1.5; their centroids are inside the blade.
  const Eigen::RowVector3d c2 = s[2].points.colwise().mean(), c3 = s[3].points.colwise().mean();
  char q[256];
  std::snprintf(q, sizeof q, "x,y,z\n%.17g,%.17g,%.17g\n%.17g,%.17g,%.17g\n%.17g,%.17g,%.17g\n",
                c2(0), c2(1), c2(2), c3(0), c3(1), c3(2), c2(0), c2(1) + 0.5, c2(2));
  write_file(d / "q.csv", q);
  r = run("eval " + d / "cut.rf " + d / "q.csv -q");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const std::vector<double> F = column(r.out, 3);
  CHECK(F[0] > 0); // inside blade and slab
  CHECK(F[1] < 0); // inside the blade, above the slab
  CHECK(F[2] < 0); // beside the blade
  r = run("mesh " + d / "cut.rf -o " + d / "cut.stl --resolution 48 -q");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains(", watertight,"));
}

TEST_CASE("CLI implicit: an R-function model normalised, exact on its zero set",
          "[cli][implicit]") {
  TempDir d("implicitrf");
  // An ellipsoid: the R-function is far from the distance away from the surface.
  write_file(d / "e.rf", "box(-2.5, -1.5, -1.2, 2.5, 1.5, 1.2);\n"
                         "res = 1 - (x/2)^2 - y^2 - (z/0.8)^2;\n");
  Run r = run("implicit " + d / "e.rf -o " + d / "e.ifl --resolution 32 -q");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  // Points on the ellipsoid, and offsets along its normal.
  std::string on = "x,y,z\n", off = "x,y,z\n";
  std::vector<double> delta;
  for (int i = 0; i < 40; ++i) {
    const double t = 0.37 * i, p = 0.11 + 0.07 * i;
    const double x = 2 * std::cos(t) * std::sin(p), y = std::sin(t) * std::sin(p),
                 z = 0.8 * std::cos(p);
    char buf[160];
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", x, y, z);
    on += buf;
    Eigen::Vector3d n(x / 4, y, z / 0.64);
    n.normalize();
    const double dl = 0.02 + 0.003 * i;
    delta.push_back(dl);
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", x + dl * n(0), y + dl * n(1),
                  z + dl * n(2));
    off += buf;
  }
  write_file(d / "on.csv", on);
  write_file(d / "off.csv", off);
  r = run("eval " + d / "e.ifl " + d / "on.csv -q");
  REQUIRE(r.status == 0);
  CHECK(max_abs(column(r.out, 3)) <= 1e-14);
  r = run("eval " + d / "e.ifl " + d / "off.csv -q");
  REQUIRE(r.status == 0);
  const std::vector<double> w = column(r.out, 3);
  for (size_t i = 0; i < w.size(); ++i) { // outside: -delta to first order
    CHECK(-w[i] / delta[i] > 0.95);
    CHECK(-w[i] / delta[i] < 1.05);
  }
}

TEST_CASE("CLI implicit: usage and input errors, no output file", "[cli][implicit]") {
  TempDir d("implicitbad");
  write_file(d / "bad.csv", "section,x,y,z\n1,0,0,0\n1,1,0,0\n1,x,1,0\n");
  expect_error(run("implicit " + d / "bad.csv -o " + d / "b.ifl -q"), 1, "bad.csv:4:");
  CHECK_FALSE(fs::exists(d / "b.ifl"));
  expect_error(run("implicit " + d / "bad.csv"), 2, "give -o MODEL.ifl");
  expect_error(run("implicit " + d / "bad.csv -o " + d / "b.stl"), 2, "must end in .ifl");
  expect_error(run("implicit " + d / "scan.obj -o " + d / "b.ifl"), 2, "unknown kind");
  expect_error(run("implicit " + d / "bad.csv -o " + d / "b.ifl --set a=1"), 2,
               "--set applies to R-function models");
  expect_error(run("implicit " + d / "bad.csv -o " + d / "b.ifl --band 3,1"), 2, "--band");
  expect_error(run("implicit " + d / "bad.csv -o " + d / "b.ifl --resolution 4"), 2,
               "--resolution");
  write_file(d / "broken.ifl", "interlin-ifl 1\nblock section_body model\nnumber version 1\n");
  write_file(d / "p.csv", "x,y,z\n0,0,0\n");
  expect_error(run("eval " + d / "broken.ifl " + d / "p.csv -q"), 1,
               "broken.ifl:4: unexpected end");
  write_file(d / "wrong.ifl", "interlin-ifl 1\nblock section_body model\nnumber version 1\nend\n");
  expect_error(run("eval " + d / "wrong.ifl " + d / "p.csv -q"), 1,
               "wrong.ifl:2: block section_body model: missing array 'box'");
  expect_error(run("eval " + d / "wrong.ifl " + d / "p.csv --set a=1"), 2,
               "--set and --var apply to R-function models");
  expect_error(run("mesh " + d / "model.stl -o " + d / "m.stl"), 2, "unknown kind '.stl'");
  CHECK(files_in(d) == 4);
}
