#include "interlin/reconstruction/io/preview.h"

#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <png.h>
#include <stdexcept>
#include <string>
#include <unistd.h>

using namespace interlin;
namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

// Closed UV sphere of radius r about the origin: nlat - 1 rings of nlon vertices plus two poles.
void uv_sphere(double r, int nlat, int nlon, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  V.resize(2 + (nlat - 1) * nlon, 3);
  V.row(0) << 0, 0, r;
  V.row(1) << 0, 0, -r;
  for (int i = 1; i < nlat; ++i)
    for (int j = 0; j < nlon; ++j) {
      const double th = kPi * i / nlat, ph = 2 * kPi * j / nlon;
      V.row(2 + (i - 1) * nlon + j) << r * std::sin(th) * std::cos(ph),
          r * std::sin(th) * std::sin(ph), r * std::cos(th);
    }
  auto ring = [&](int i, int j) { return 2 + (i - 1) * nlon + (j % nlon); };
  F.resize(2 * nlon + 2 * (nlat - 2) * nlon, 3);
  int f = 0;
  for (int j = 0; j < nlon; ++j) {
    F.row(f++) << 0, ring(1, j), ring(1, j + 1);
    F.row(f++) << 1, ring(nlat - 1, j + 1), ring(nlat - 1, j);
  }
  for (int i = 1; i < nlat - 1; ++i)
    for (int j = 0; j < nlon; ++j) {
      F.row(f++) << ring(i, j), ring(i + 1, j), ring(i + 1, j + 1);
      F.row(f++) << ring(i, j), ring(i + 1, j + 1), ring(i, j + 1);
    }
}

// Closed box [0, a] x [0, b] x [0, c], 12 triangles.
void box(double a, double b, double c, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  V.resize(8, 3);
  for (int i = 0; i < 8; ++i)
    V.row(i) << (i & 1 ? a : 0), (i & 2 ? b : 0), (i & 4 ? c : 0);
  F.resize(12, 3);
  F << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1,
      3, 5, 3, 7, 5;
}

// Circle of radius rho about centre c in the plane orthogonal to n, closed (first point repeated).
Eigen::MatrixXd circle(const Eigen::Vector3d& c, const Eigen::Vector3d& e1,
                       const Eigen::Vector3d& e2, double rho, int n) {
  Eigen::MatrixXd P(n + 1, 3);
  for (int i = 0; i <= n; ++i) {
    const double t = 2 * kPi * i / n;
    P.row(i) = (c + rho * (std::cos(t) * e1 + std::sin(t) * e2)).transpose();
  }
  return P;
}

std::array<std::uint8_t, 3> pixel(const Image& im, int x, int y) {
  const std::size_t o = (static_cast<std::size_t>(y) * im.width + x) * 3;
  return {im.rgb[o], im.rgb[o + 1], im.rgb[o + 2]};
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Uniform background (top == bottom) whose 8-bit value is exact: 0.8*255 = 204, 0.6*255 = 153,
// 0.4*255 = 102.
PreviewOptions small_options() {
  PreviewOptions o;
  o.width = 160;
  o.height = 120;
  o.background_top = o.background_bottom = Eigen::Vector3d(0.8, 0.6, 0.4);
  return o;
}
const std::array<std::uint8_t, 3> kBackground{204, 153, 102};

} // namespace

TEST_CASE("render_preview fits a sphere to 85% of the frame on the background", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  uv_sphere(2.0, 32, 64, V, F);
  const PreviewOptions o = small_options();
  const Image im = render_preview(V, F, {}, o);
  REQUIRE(im.width == 160);
  REQUIRE(im.height == 120);
  REQUIRE(im.rgb.size() == 160u * 120u * 3u);

  CHECK(pixel(im, 0, 0) == kBackground);
  CHECK(pixel(im, 159, 0) == kBackground);
  CHECK(pixel(im, 0, 119) == kBackground);
  CHECK(pixel(im, 159, 119) == kBackground);
  CHECK(pixel(im, 80, 60) != kBackground);

  // Orthographic view of a sphere: a disc centred in the frame whose diameter is 85% of the
  // tighter side (120 px) = 102 px. Tolerance: anti-aliased rim pixels (+1 each side) and the
  // 64-gon approximation of the silhouette (relative shrink <= 1 - cos(pi/64) ~ 0.1%).
  int row = 0, col = 0;
  for (int x = 0; x < im.width; ++x)
    row += pixel(im, x, 60) != kBackground;
  for (int y = 0; y < im.height; ++y)
    col += pixel(im, 80, y) != kBackground;
  CHECK(row >= 100);
  CHECK(row <= 104);
  CHECK(col >= 100);
  CHECK(col <= 104);

  // Shaded, not flat: brightness varies across the disc, and the brightest point (the key light's
  // highlight; the key light comes from the upper left) lies in the upper-left quadrant.
  int lo = 255 * 3, hi = 0, hx = 0, hy = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      if ((x + 0.5 - 80) * (x + 0.5 - 80) + (y + 0.5 - 60) * (y + 0.5 - 60) > 45 * 45)
        continue; // keep well inside the disc of radius 51
      const auto p = pixel(im, x, y);
      const int g = p[0] + p[1] + p[2];
      lo = std::min(lo, g);
      if (g > hi)
        hi = g, hx = x, hy = y;
    }
  CHECK(hi - lo > 3 * 30);
  CHECK(hx < 80);
  CHECK(hy < 60);
}

TEST_CASE("render_preview default background is a vertical gradient", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  box(1, 1, 1, V, F);
  PreviewOptions o;
  o.width = 64;
  o.height = 48;
  const Image im = render_preview(V, F, {}, o);
  // Constant along a row, lighter at the top than at the bottom (defaults: 0.97 -> 0.80 green).
  CHECK(pixel(im, 0, 0) == pixel(im, 63, 0));
  CHECK(pixel(im, 0, 47) == pixel(im, 63, 47));
  CHECK(pixel(im, 0, 0)[1] > pixel(im, 0, 47)[1]);
}

TEST_CASE("render_preview is deterministic", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  uv_sphere(1.0, 24, 48, V, F);
  const std::vector<Eigen::MatrixXd> lines{
      circle(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), 1.0, 96)};
  const PreviewOptions o = small_options();
  const Image a = render_preview(V, F, lines, o);
  const Image b = render_preview(V, F, lines, o);
  CHECK(a.rgb == b.rgb);
  // Any supersampling factor gives the requested output size.
  for (int k : {1, 3}) {
    PreviewOptions ok = o;
    ok.supersample = k;
    const Image c = render_preview(V, F, lines, ok);
    CHECK(c.width == 160);
    CHECK(c.height == 120);
    CHECK(pixel(c, 0, 0) == kBackground);
    CHECK(pixel(c, 80, 60) != kBackground);
  }
}

TEST_CASE("render_preview picks the largest principal axis as up", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  box(4, 1, 0.5, V, F); // longest along x
  PreviewOptions o = small_options();
  const Image automatic = render_preview(V, F, {}, o);
  o.up = Eigen::Vector3d(3, 0, 0); // any length, same direction
  const Image explicit_up = render_preview(V, F, {}, o);
  CHECK(automatic.rgb == explicit_up.rgb);
  o.up = Eigen::Vector3d::UnitZ();
  CHECK(render_preview(V, F, {}, o).rgb != automatic.rgb);
}

TEST_CASE("render_preview view turns with the model about up", "[preview]") {
  // Azimuth 0 is the model's in-plane principal axis, so spinning (and moving) the model leaves the
  // picture unchanged (this box is also symmetric under a half turn, which covers the sign
  // ambiguity of the axis).
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  box(4, 1, 0.5, V, F);
  PreviewOptions o = small_options();
  o.up = Eigen::Vector3d::UnitZ();
  const Image a = render_preview(V, F, {}, o);
  const double t = 0.5; // radians
  Eigen::Matrix3d R;
  R << std::cos(t), -std::sin(t), 0, std::sin(t), std::cos(t), 0, 0, 0, 1;
  const Eigen::MatrixXd Vr = (V * R.transpose()).rowwise() + Eigen::RowVector3d(1e5, -3e4, 2e4);
  const Image b = render_preview(Vr, F, {}, o);
  // Rounding moves edges by ~1e-15 px, which can flip a sub-pixel sample lying exactly on an
  // edge; allow a few edge pixels to differ, none of the interior.
  int differ = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i)
    differ += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 1;
  CHECK(differ <= 20);
  // Without the spin compensation the picture would change: a different azimuth differs a lot.
  o.azimuth_deg += 30;
  const Image c = render_preview(V, F, {}, o);
  int changed = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i)
    changed += std::abs(int(a.rgb[i]) - int(c.rgb[i])) > 1;
  CHECK(changed > 1000);
}

TEST_CASE("render_preview shades both sides alike", "[preview]") {
  // Two-sided shading: reversing every triangle (normals pointing inward) shows the same picture.
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  uv_sphere(1.0, 24, 48, V, F);
  const PreviewOptions o = small_options();
  const Image a = render_preview(V, F, {}, o);
  Eigen::MatrixXi Fr = F;
  Fr.col(1).swap(Fr.col(2));
  const Image b = render_preview(V, Fr, {}, o);
  // Only the floating-point summation order changes (a 1-level rounding difference at most).
  int differ = 0;
  for (std::size_t i = 0; i < a.rgb.size(); ++i)
    differ += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 1;
  CHECK(differ == 0);
}

TEST_CASE("render_preview draws polylines on the visible side only", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  uv_sphere(1.0, 32, 64, V, F);
  PreviewOptions o = small_options();
  // up = z, azimuth 0, elevation 0: the camera looks from +x (the axis least aligned with z).
  o.up = Eigen::Vector3d::UnitZ();
  o.azimuth_deg = 0;
  o.elevation_deg = 0;
  const Image plain = render_preview(V, F, {}, o);
  // Small circles of latitude on the sphere around -x (hidden) and +x (facing the camera). Both
  // lie inside the sphere's silhouette, so the fit is unchanged.
  const double rho = 0.5, off = std::sqrt(1 - rho * rho);
  const Eigen::Vector3d ey = Eigen::Vector3d::UnitY(), ez = Eigen::Vector3d::UnitZ();
  const Image back =
      render_preview(V, F, {circle(Eigen::Vector3d(-off, 0, 0), ey, ez, rho, 128)}, o);
  CHECK(back.rgb == plain.rgb);
  const Image front =
      render_preview(V, F, {circle(Eigen::Vector3d(off, 0, 0), ey, ez, rho, 128)}, o);
  // The front circle projects to a circle of radius rho * 102 / 2 ~ 25.5 px about the centre:
  // the pixel on it to the right of the centre is darker, the centre itself is untouched.
  CHECK(front.rgb != plain.rgb);
  CHECK(pixel(front, 80, 60) == pixel(plain, 80, 60));
  const auto on = pixel(front, 80 + 25, 60), off_line = pixel(plain, 80 + 25, 60);
  CHECK(on[0] + on[1] + on[2] < off_line[0] + off_line[1] + off_line[2] - 60);
  // Line width 1.5 output pixels: crossing it at right angles touches 2 or 3 pixels of a row.
  int touched = 0;
  for (int x = 95; x < 116; ++x)
    touched += pixel(front, x, 60) != pixel(plain, x, 60);
  CHECK(touched >= 2);
  CHECK(touched <= 3);
}

TEST_CASE("write_png round-trips through libpng", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  uv_sphere(1.0, 16, 32, V, F);
  PreviewOptions o;
  o.width = 97; // odd sizes: no row padding assumptions
  o.height = 61;
  const Image im = render_preview(V, F, {}, o);
  test::TempDir dir("preview-png");
  const std::string path = (dir.path() / "sphere.png").string();
  write_png(path, im);

  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&png, path.c_str()));
  CHECK(png.width == 97u);
  CHECK(png.height == 61u);
  png.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> buffer(PNG_IMAGE_SIZE(png));
  REQUIRE(png_image_finish_read(&png, nullptr, buffer.data(), 0, nullptr));
  CHECK(buffer == im.rgb);

  // write_preview_png writes the same bytes as render_preview + write_png.
  const std::string path2 = (dir.path() / "sphere2.png").string();
  write_preview_png(path2, V, F, {}, o);
  CHECK(read_bytes(path2) == read_bytes(path));
  // Only the two targets exist: no temporary files left behind.
  CHECK(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}) == 2);
}

TEST_CASE("write_png into a missing directory throws and leaves no file", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  box(1, 2, 3, V, F);
  test::TempDir dir("preview-missing");
  const fs::path target = dir.path() / "missing" / "out.png";
  const Image im = render_preview(V, F, {}, small_options());
  try {
    write_png(target.string(), im);
    FAIL("write_png did not throw");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find(target.string()) != std::string::npos);
  }
  CHECK_THROWS_AS(write_preview_png(target.string(), V, F), std::runtime_error);
  CHECK(!fs::exists(target));
  CHECK(fs::is_empty(dir.path()));
}

TEST_CASE("render_preview rejects bad input", "[preview]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  box(1, 1, 1, V, F);
  const PreviewOptions o = small_options();
  CHECK_NOTHROW(render_preview(V, F, {}, o));
  CHECK_THROWS_AS(render_preview(Eigen::MatrixXd(0, 3), Eigen::MatrixXi(0, 3), {}, o),
                  std::invalid_argument);
  CHECK_THROWS_AS(render_preview(V, Eigen::MatrixXi(0, 3), {}, o), std::invalid_argument);
  Eigen::MatrixXi bad = F;
  bad(3, 1) = 8;
  CHECK_THROWS_AS(render_preview(V, bad, {}, o), std::invalid_argument);
  bad(3, 1) = -1;
  CHECK_THROWS_AS(render_preview(V, bad, {}, o), std::invalid_argument);
  Eigen::MatrixXd nan = V;
  nan(2, 2) = std::nan("");
  CHECK_THROWS_AS(render_preview(nan, F, {}, o), std::invalid_argument);
  CHECK_THROWS_AS(render_preview(V.leftCols(2), F, {}, o), std::invalid_argument);
  CHECK_THROWS_AS(render_preview(V, F, {Eigen::MatrixXd::Zero(4, 2)}, o), std::invalid_argument);
  for (auto change :
       {+[](PreviewOptions& p) { p.width = 0; }, +[](PreviewOptions& p) { p.height = -3; },
        +[](PreviewOptions& p) { p.supersample = 0; },
        +[](PreviewOptions& p) { p.width = p.height = 16384; },
        +[](PreviewOptions& p) { p.azimuth_deg = INFINITY; },
        +[](PreviewOptions& p) { p.up(0) = std::nan(""); }}) {
    PreviewOptions p = o;
    change(p);
    CHECK_THROWS_AS(render_preview(V, F, {}, p), std::invalid_argument);
  }
  CHECK_THROWS_AS(write_png("unused.png", Image{2, 2, std::vector<std::uint8_t>(5)}),
                  std::invalid_argument);
  CHECK(!fs::exists("unused.png"));
}
