// interlin implicit on point clouds as a user meets it: unstructured scans of sphere, torus and
// a thin ellipsoid in .xyz (no normals), .csv (x,y,z,nx,ny,nz) and .ply -> .ifl whose zero set
// passes through the points and whose sign is right, read by eval and mesh; a sectioned scan ->
// fitted sections -> the lofted body; the .csv rule (sections or a cloud); one error line and
// exit 1 (bad input) or 2 (wrong usage) without an output file.
#include "support/cli_runner.h"
#include "support/sliced_scans.h"
#include "support/test_clouds.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

using namespace interlin::test;

namespace {

std::string row(const Eigen::RowVector3d& p, const char* sep) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%.17g%s%.17g%s%.17g", p(0), sep, p(1), sep, p(2));
  return buf;
}

// The points as a CSV points file for `interlin eval`.
std::string points_csv(const Eigen::MatrixX3d& P) {
  std::string s = "x,y,z\n";
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    s += row(P.row(i), ",") + "\n";
  return s;
}

// Column 3 (F) of eval's output.
std::vector<double> eval_F(const std::string& model, const std::string& points_file) {
  const Run r = run("eval " + model + " " + points_file + " -q");
  INFO(r.err);
  REQUIRE(r.status == 0);
  std::vector<double> F;
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line))
    F.push_back(std::stod(line.substr(line.rfind(',') + 1)));
  return F;
}

// The cloud in the format of `name`'s extension (.xyz: points only; .csv and .ply: with
// normals).
void write_cloud(const std::string& path, const interlin::PointCloud& c) {
  std::string s;
  const std::string e = fs::path(path).extension().string();
  if (e == ".csv")
    s = "x,y,z,nx,ny,nz\n";
  if (e == ".ply")
    s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(c.points.rows()) +
        "\nproperty double x\nproperty double y\nproperty double z\nproperty double nx\n"
        "property double ny\nproperty double nz\nend_header\n";
  const char* sep = e == ".csv" ? "," : " ";
  for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
    s += row(c.points.row(i), sep);
    if (e != ".xyz")
      s += sep + row(c.normals.row(i), sep);
    s += "\n";
  }
  write_file(path, s);
}

// clean.xyz and noisy.xyz (sigma 0.01): n points of the unit sphere in a new directory d, and
// the output options o (" -o d/x.ifl -q").
struct SphereScans {
  TempDir d;
  std::string o;
  SphereScans(const std::string& tag, int n, unsigned seed) : d(tag), o(" -o " + d / "x.ifl -q") {
    write_cloud(d / "clean.xyz", sample_shape({Shape::sphere}, n, 0, seed));
    write_cloud(d / "noisy.xyz", sample_shape({Shape::sphere}, n, 0.01, seed));
  }
};

} // namespace

TEST_CASE("CLI implicit: unstructured clouds -> .ifl through the points, signed, meshed",
          "[cli][implicit][clouds]") {
  TempDir d("implicitcloud");
  const std::vector<std::pair<Shape, std::string>> cases = {
      {Shape::sphere, "scan.xyz"}, {Shape::torus, "scan.csv"}, {Shape::ellipsoid, "scan.ply"}};
  for (const auto& [shape, name] : cases) {
    INFO(name);
    const SampledShape truth{shape};
    constexpr double kSigma = 0.002;
    write_cloud(d / name, sample_shape(truth, 3000, kSigma, 41));
    Run r = run("implicit " + d / name + " -o " + d / "scan.ifl -q");
    INFO(r.out << r.err);
    REQUIRE(r.status == 0);
    CHECK(r.err.empty());
    CHECK_THAT(r.out, Catch::Contains("slices       none found: unstructured fit") &&
                          Catch::Contains("octree       ") &&
                          Catch::Contains("wrote        " + d / "scan.ifl"));
    // Clean surface points and offsets along the exact normals (+-0.05, 25 sigma: the sign is
    // the body's). On the surface the fit's first-order distance is about 0.6 sigma + 0.5
    // spacing^2 = 0.003 rms (test_cloud_implicit): 0.01 leaves a margin of 3.
    const interlin::PointCloud clean = sample_shape(truth, 300, 0, 42);
    write_file(d / "on.csv", points_csv(clean.points));
    write_file(d / "in.csv", points_csv(clean.points - 0.05 * clean.normals));
    write_file(d / "out.csv", points_csv(clean.points + 0.05 * clean.normals));
    const std::vector<double> on = eval_F(d / "scan.ifl", d / "on.csv");
    double s2 = 0;
    for (double v : on)
      s2 += v * v;
    CHECK(std::sqrt(s2 / double(on.size())) <= 0.01);
    const std::vector<double> in = eval_F(d / "scan.ifl", d / "in.csv");
    const std::vector<double> out = eval_F(d / "scan.ifl", d / "out.csv");
    CHECK(std::count_if(in.begin(), in.end(), [](double v) { return v > 0; }) == 300);
    CHECK(std::count_if(out.begin(), out.end(), [](double v) { return v < 0; }) == 300);
    r = run("mesh " + d / "scan.ifl -o " + d / "scan_mesh.stl --resolution 40 -q");
    CHECK(r.status == 0);
    CHECK_THAT(r.out, Catch::Contains(", watertight,"));
  }
}

TEST_CASE("CLI implicit: sheet normals on clean clouds by default, --sheet-normals off|on",
          "[cli][implicit][clouds]") {
  const SphereScans scans("implicitsheets", 2000, 45);
  const TempDir& d = scans.d;
  const std::string& o = scans.o;
  const std::string kept = "; kept to one sheet, ";
  Run r = run("implicit " + d / "clean.xyz" + o);
  REQUIRE(r.status == 0);
  // a sphere is one smooth sheet everywhere: its sheet normals are PCA's
  CHECK_THAT(r.out, Catch::Contains(kept + "0 more than 20 degrees from PCA's) and oriented"));
  r = run("implicit " + d / "clean.xyz" + o + " --sheet-normals off");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, !Catch::Contains(kept) && Catch::Contains("k = 16) and oriented"));
  r = run("implicit " + d / "noisy.xyz" + o);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, !Catch::Contains(kept));
  r = run("implicit " + d / "noisy.xyz" + o + " --sheet-normals on");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains(kept));
}

TEST_CASE("CLI implicit: noisy scans' points smoothed by default, --smooth-points off",
          "[cli][implicit][clouds]") {
  const SphereScans scans("implicitsmooth", 3000, 46);
  const TempDir& d = scans.d;
  const std::string& o = scans.o;
  const std::string smoothed = "  smoothing    3000 points moved onto local quadrics (median ";
  Run r = run("implicit " + d / "noisy.xyz" + o);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains(smoothed));
  r = run("implicit " + d / "noisy.xyz" + o + " --smooth-points off");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, !Catch::Contains("smoothing"));
  r = run("implicit " + d / "clean.xyz" + o);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, !Catch::Contains("smoothing"));
  expect_error(run("implicit " + d / "noisy.xyz" + o + " --smooth-points sometimes"), 2,
               "--smooth-points");
  expect_error(run("implicit " + d / "noisy.xyz" + o + " --slices planar --smooth-points off"), 2,
               "--smooth-points applies to the unstructured fit (not with --slices planar)");
  expect_error(run("implicit " + d / "noisy.xyz" + o + " --fit hrbf --smooth-points off"), 2,
               "--smooth-points applies to the partition of unity");
}

TEST_CASE("CLI implicit: a cloud's .ifl is meshed at half the detail it resolves by default, "
          "points per fit",
          "[cli][implicit][clouds]") {
  TempDir d("implicitcloudcell");
  write_cloud(d / "scan.xyz", sample_shape(SampledShape{Shape::sphere}, 3000, 0.002, 44));
  Run r = run("implicit " + d / "scan.xyz -o " + d / "scan.ifl -q");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  auto number_after = [](const std::string& text, const std::string& key) {
    const size_t at = text.find(key);
    REQUIRE(at != std::string::npos);
    return std::stod(text.substr(at + key.size()));
  };
  // 3000 points on the unit sphere: spacing about sqrt(4 pi / 3000) = 0.065
  const double spacing = number_after(r.out, "point spacing ");
  // noise 0.002 = 0.03 spacings: a noisy scan, 20 points per fit; a clean cloud (noise-free
  // samples) gets 10
  CHECK_THAT(r.out, Catch::Contains(", 20 points per fit"));
  write_cloud(d / "clean.csv", sample_shape(SampledShape{Shape::sphere}, 3000, 0, 45));
  const Run clean = run("implicit " + d / "clean.csv -o " + d / "clean.ifl -q");
  INFO(clean.out << clean.err);
  REQUIRE(clean.status == 0);
  CHECK_THAT(clean.out, Catch::Contains(", 10 points per fit"));
  CHECK(spacing == Approx(std::sqrt(4 * M_PI / 3000)).epsilon(0.15));
  r = run("mesh " + d / "scan.ifl -o " + d / "scan.stl -q");
  REQUIRE(r.status == 0);
  // both printed with 4 significant digits; the noisy scan's points were smoothed, so its F
  // resolves twice the spacing and the default cell is the spacing; the clean cloud's is half
  CHECK(number_after(r.out, "nodes, cell ") == Approx(spacing).epsilon(1e-3));
  r = run("mesh " + d / "clean.ifl -o " + d / "clean.stl -q");
  REQUIRE(r.status == 0);
  CHECK(number_after(r.out, "nodes, cell ") ==
        Approx(number_after(clean.out, "point spacing ") / 2).epsilon(1e-3));
  CHECK_THAT(r.out, Catch::Contains(", watertight,"));
  // an explicit resolution still rules
  r = run("mesh " + d / "scan.ifl -o " + d / "scan.stl --resolution 20 -q");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("21 x 21 x 21 nodes"));
}

TEST_CASE("CLI implicit: a sectioned scan -> fitted sections -> the lofted body",
          "[cli][implicit][clouds]") {
  TempDir d("implicitslices");
  constexpr double kSigma = 0.002, kThick = 0.1;
  const Scan s = scan(false, 12, 400, kSigma, kThick, 43);
  std::string text;
  for (Eigen::Index i = 0; i < s.P.rows(); ++i)
    text += row(s.P.row(i), " ") + "\n";
  write_file(d / "slices.xyz", text);
  Run r = run("implicit " + d / "slices.xyz -o " + d / "blade.ifl --resolution 32");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.err, Catch::Contains("fitting 12 sections")); // progress lines without -q
  CHECK_THAT(r.out, Catch::Contains("slices       planar, 12 along") &&
                        Catch::Contains("span         smoothed: the sections are isocurves") &&
                        Catch::Contains("sections     12 fitted") &&
                        Catch::Contains("exactness    max |omega|"));
  // The scan points lie within the noise of the surface: omega is the signed distance near the
  // loft, whose fitted sections are within 1.5 sigma rms of the truth (test_sliced_scan), more
  // at the sharp noses of this thin profile (measured: 2.4 sigma rms over the points).
  write_file(d / "scan.csv", points_csv(s.P));
  const std::vector<double> on = eval_F(d / "blade.ifl", d / "scan.csv");
  double s2 = 0;
  for (double v : on)
    s2 += v * v;
  CHECK(std::sqrt(s2 / double(on.size())) <= 3 * kSigma);
  // Between the slices: the mean line's midpoint is inside, 0.3 chord above it outside.
  std::string q = "x,y,z\n";
  for (int k = 0; k + 1 < 12; ++k) {
    const double t = (k + 0.5) / 11;
    const Eigen::Vector2d top = profile(M_PI / 2, t, kThick),
                          bottom = profile(-M_PI / 2, t, kThick);
    const Eigen::Vector2d mid = 0.5 * (top + bottom), away = mid + 3 * (top - mid);
    q += row(Eigen::RowVector3d(3 * t, mid(0), mid(1)), ",") + "\n" +
         row(Eigen::RowVector3d(3 * t, away(0), away(1)), ",") + "\n";
  }
  write_file(d / "q.csv", q);
  const std::vector<double> F = eval_F(d / "blade.ifl", d / "q.csv");
  for (size_t i = 0; i < F.size(); ++i)
    CHECK((i % 2 == 0 ? F[i] > 0 : F[i] < 0));
  r = run("mesh " + d / "blade.ifl -o " + d / "blade.stl --resolution 48 -q");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains(", watertight,"));
  // Without smoothing along the span: each section on its own.
  r = run("implicit " + d / "slices.xyz -o " + d / "alone.ifl --resolution 32 -q " +
          "--span-smoothing off");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("span         each section fitted to its slice alone"));
  // The same points forced unstructured: the partition of unity.
  r = run("implicit " + d / "slices.xyz -o " + d / "pu.ifl --slices none -q");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("octree       "));
}

TEST_CASE("CLI implicit: .csv and .txt inputs are sections or clouds by a stated rule",
          "[cli][implicit][clouds]") {
  TempDir d("implicitcsv");
  // x,y,z with blank lines between groups: a plain section file; without: a cloud.
  std::string sections = "x,y,z\n", cloud = "x,y,z\n";
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < 24; ++i) {
      const double a = 2 * M_PI * i / 24;
      const std::string p = row(Eigen::RowVector3d(std::cos(a), 0.5 * std::sin(a), k), ",");
      sections += p + "\n";
      cloud += p + "\n";
    }
    sections += "\n";
  }
  write_file(d / "s.csv", sections);
  Run r = run("implicit " + d / "s.csv -o " + d / "s.ifl --resolution 16 -q");
  INFO(r.out << r.err);
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("sections     3, loft"));
  write_file(d / "c.csv", cloud);
  r = run("implicit " + d / "c.csv -o " + d / "c.ifl --resolution 16 -q");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("input        a point cloud (header x, y, z; no blank lines"));
  // cloud options for sections are wrong usage
  r = run("implicit " + d / "s.csv -o " + d / "t.ifl --slices auto");
  expect_error(r, 2, "--slices applies to point clouds only");
  r = run("implicit " + d / "s.csv -o " + d / "t.ifl --span-smoothing off");
  expect_error(r, 2, "--span-smoothing applies to point clouds only");
  // undecidable: no header and no blank lines, or a header naming neither
  write_file(d / "h.csv", "1,2,3\n4,5,6\n");
  expect_error(run("implicit " + d / "h.csv -o " + d / "h.ifl"), 1,
               "h.csv:1: a .csv file without a header and without blank lines");
  write_file(d / "a.csv", "a,b,c\n1,2,3\n");
  expect_error(run("implicit " + d / "a.csv -o " + d / "a.ifl"), 1,
               "a.csv:1: the header names neither a section column");
  CHECK_FALSE(fs::exists(d / "t.ifl"));
  CHECK_FALSE(fs::exists(d / "h.ifl"));
  CHECK_FALSE(fs::exists(d / "a.ifl"));
}

TEST_CASE(
    "CLI implicit: a sparse cloud with normals gets the hold-out's choice or the --fit asked for",
    "[cli][implicit][clouds]") {
  TempDir d("implicitsparse");
  const SampledShape truth{Shape::torus};
  const interlin::PointCloud c = sample_shape(truth, 300, 0, 46);
  write_cloud(d / "sparse.csv", c);
  Run r = run("implicit " + d / "sparse.csv -o " + d / "auto.ifl -q");
  INFO(r.out << r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("choice       hold-out mean |F| / |grad F|: partition of "
                                    "unity ") &&
                        Catch::Contains("-> Hermite RBF") &&
                        Catch::Contains("fit          Hermite RBF through 300 points"));
  // the interpolant: F = 0 at every input point (to round-off of a 1204-unknown Cholesky and
  // eval's 17 digits), the sign right at offsets of 0.05 along the exact normals
  write_file(d / "on.csv", points_csv(c.points));
  for (double v : eval_F(d / "auto.ifl", d / "on.csv"))
    CHECK(std::abs(v) < 1e-9);
  const interlin::PointCloud probe = sample_shape(truth, 300, 0, 47);
  write_file(d / "in.csv", points_csv(probe.points - 0.05 * probe.normals));
  write_file(d / "out.csv", points_csv(probe.points + 0.05 * probe.normals));
  const std::vector<double> in = eval_F(d / "auto.ifl", d / "in.csv");
  const std::vector<double> out = eval_F(d / "auto.ifl", d / "out.csv");
  CHECK(std::count_if(in.begin(), in.end(), [](double v) { return v > 0; }) == 300);
  CHECK(std::count_if(out.begin(), out.end(), [](double v) { return v < 0; }) == 300);
  r = run("mesh " + d / "auto.ifl -o " + d / "auto.stl -q");
  CHECK(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains(", watertight,"));
  // --fit pu and --fit hrbf skip the choice
  r = run("implicit " + d / "sparse.csv -o " + d / "pu.ifl -q --fit pu");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("octree       ") && !Catch::Contains("choice"));
  r = run("implicit " + d / "sparse.csv -o " + d / "hrbf.ifl -q --fit hrbf");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out,
             Catch::Contains("Hermite RBF through 300 points") && !Catch::Contains("choice"));
  // the same points without normals: estimated normals are not interpolated by default
  write_cloud(d / "bare.xyz", c);
  r = run("implicit " + d / "bare.xyz -o " + d / "bare.ifl -q");
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("octree       ") && !Catch::Contains("choice"));
  // too many points for the interpolant, bad choices: one line, no output
  write_cloud(d / "dense.csv", sample_shape(truth, 1200, 0, 48)); // some may go as outliers
  expect_error(run("implicit " + d / "dense.csv -o " + d / "x.ifl -q --fit hrbf"), 1,
               "dense.csv: --fit hrbf takes at most 1000 points, the cloud has 1");
  expect_error(run("implicit " + d / "sparse.csv -o " + d / "x.ifl -q --fit rbf"), 2, "--fit");
  expect_error(run("implicit " + d / "sparse.csv -o " + d / "x.ifl -q --fit hrbf --max-depth 4"), 2,
               "--max-depth applies to the partition of unity");
  CHECK_FALSE(fs::exists(d / "x.ifl"));
}

TEST_CASE("CLI implicit: bad clouds and options give one line, exit 1 or 2, no output",
          "[cli][implicit][clouds]") {
  TempDir d("implicitbad");
  write_cloud(d / "ok.xyz", sample_shape({Shape::sphere}, 500, 0, 44));
  write_file(d / "three.xyz", "0 0 0\n1 0 0\n0 1 0\n");
  write_file(d / "nan.xyz", "0 0 0\n1 nan 0\n0 1 0\n");
  std::string plane;
  for (int i = 0; i < 50; ++i)
    plane += std::to_string(i % 7) + " " + std::to_string(i / 7) + " 0\n";
  write_file(d / "plane.xyz", plane);
  const std::string o = " -o " + d / "x.ifl -q";
  expect_error(run("implicit " + d / "three.xyz" + o), 1, "only 3 distinct point(s)");
  expect_error(run("implicit " + d / "nan.xyz" + o), 1, "nan.xyz:2: column y");
  expect_error(run("implicit " + d / "plane.xyz" + o), 1, "lie on one plane");
  expect_error(run("implicit " + d / "missing.xyz" + o), 1, "missing.xyz");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --slices planar"), 1,
               "ok.xyz: no planar slices found");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --slices diagonal"), 2, "--slices");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --noise -1"), 2, "--noise");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --slices none --resolution 64"), 2,
               "--resolution applies to sections and sectioned scans");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --span-smoothing always"), 2,
               "--span-smoothing: expected auto or off");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --slices none --span-smoothing off"), 2,
               "--span-smoothing applies to sections and sectioned scans");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --set a=1"), 2,
               "--set applies to R-function models");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --normals file"), 1,
               "the file has no normals");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --sheet-normals yes"), 2, "--sheet-normals");
  expect_error(run("implicit " + d / "ok.xyz" + o + " --normal-neighbours 2"), 2,
               "--normal-neighbours expects auto or an integer in [3, 1000], got '2'");
  CHECK(files_in(d) == 4); // the inputs only
}
