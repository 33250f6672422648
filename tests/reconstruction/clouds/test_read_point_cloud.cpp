// Point-cloud readers: every format and flavour reads the same cloud, and every malformed file
// gives one InputError line naming the file (and the line for text).

#include "interlin/reconstruction/clouds/read_point_cloud.h"
#include "interlin/reconstruction/io/input_error.h"

#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <pcl/io/lzf.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

using namespace interlin;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

void write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string parse_error(const std::string& text, const std::string& path) {
  try {
    parse_point_cloud(text, path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string error_of(const std::string& path) {
  try {
    read_point_cloud(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

template <class T>
void put(std::string& s, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian)
    std::reverse(b, b + sizeof(T));
  s.append(b, sizeof(T));
}

// Three points with normals, as the tests write them in every format.
const double kP[3][6] = {
    {0.5, -1.25, 2, 0, 0, 1}, {1.5, 0.25, -3, 0, 1, 0}, {-2, 4, 0.125, 1, 0, 0}};

std::string pcd_header(const std::string& data, int points = 3) {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n"
         "FIELDS x y z normal_x normal_y normal_z\nSIZE 4 4 4 4 4 4\nTYPE F F F F F F\n"
         "COUNT 1 1 1 1 1 1\nWIDTH " +
         std::to_string(points) + "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " +
         std::to_string(points) + "\nDATA " + data + "\n";
}

std::string ply_header(const std::string& format, int vertices = 3, bool faces = true) {
  std::string h = "ply\nformat " + format + " 1.0\ncomment test\nelement vertex " +
                  std::to_string(vertices) +
                  "\nproperty double x\nproperty double y\nproperty double z\n"
                  "property float nx\nproperty float ny\nproperty float nz\n";
  if (faces)
    h += "element face 1\nproperty list uchar int vertex_indices\n";
  return h + "end_header\n";
}

void require_cloud(const PointCloud& c, bool normals = true) {
  REQUIRE(c.points.rows() == 3);
  REQUIRE(c.has_normals() == normals);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      CHECK(c.points(i, k) == kP[i][k]); // exactly representable in float and in text
      if (normals)
        CHECK(c.normals(i, k) == kP[i][k + 3]);
    }
}

} // namespace

TEST_CASE("bun0.pcd (PCL's test data): 397 points with unit normals", "[clouds][read]") {
  std::vector<std::string> notes;
  const PointCloud c = read_point_cloud(INTERLIN_DATA_DIR "/clouds/bun0.pcd", &notes);
  REQUIRE(c.points.rows() == 397);
  REQUIRE(c.has_normals());
  CHECK(c.points(0, 0) == Approx(0.0054215998).epsilon(1e-7)); // float32 in the file
  CHECK(c.points(396, 2) == Approx(-0.044399999).epsilon(1e-7));
  CHECK((c.normals.rowwise().norm().array() - 1).abs().maxCoeff() < 1e-12);
  CHECK(notes.empty());
}

TEST_CASE("every format reads the same three points and normals", "[clouds][read]") {
  test::TempDir dir("clouds");
  std::ostringstream text;
  text.precision(17);
  for (const auto& p : kP)
    text << p[0] << " " << p[1] << " " << p[2] << " " << p[3] << " " << p[4] << " " << p[5] << "\n";

  write(dir / "a.pcd", pcd_header("ascii") + text.str());
  require_cloud(read_point_cloud(dir / "a.pcd"));

  std::string bin = pcd_header("binary");
  for (const auto& p : kP)
    for (double v : p)
      put(bin, static_cast<float>(v));
  write(dir / "b.pcd", bin);
  require_cloud(read_point_cloud(dir / "b.pcd"));

  // binary_compressed: field-major values, LZF-compressed, behind their two sizes
  std::string raw;
  for (int f = 0; f < 6; ++f)
    for (const auto& p : kP)
      put(raw, static_cast<float>(p[f]));
  std::string packed(raw.size() * 2 + 16, '\0');
  const unsigned n = pcl::lzfCompress(raw.data(), static_cast<unsigned>(raw.size()), packed.data(),
                                      static_cast<unsigned>(packed.size()));
  REQUIRE(n > 0);
  std::string comp = pcd_header("binary_compressed");
  put(comp, std::uint32_t{n});
  put(comp, static_cast<std::uint32_t>(raw.size()));
  comp += packed.substr(0, n);
  write(dir / "c.pcd", comp);
  require_cloud(read_point_cloud(dir / "c.pcd"));
  comp[comp.size() - 3] ^= 0x55; // corrupt the stream: an error, never garbage
  CHECK_THAT(parse_error(comp, "c.pcd"), Contains("c.pcd:11: binary_compressed data"));

  write(dir / "a.ply", ply_header("ascii") + text.str() + "3 0 1 2\n");
  require_cloud(read_point_cloud(dir / "a.ply"));
  for (const bool big : {false, true}) {
    std::string ply = ply_header(big ? "binary_big_endian" : "binary_little_endian");
    for (const auto& p : kP) {
      for (int k = 0; k < 3; ++k)
        put(ply, p[k], big);
      for (int k = 3; k < 6; ++k)
        put(ply, static_cast<float>(p[k]), big);
    }
    put(ply, std::uint8_t{3});
    for (int k = 0; k < 3; ++k)
      put(ply, std::int32_t{k}, big);
    const std::string name = dir / (big ? "be.ply" : "le.ply");
    write(name, ply);
    require_cloud(read_point_cloud(name));
  }

  write(dir / "a.xyzn", "# x y z nx ny nz\n" + text.str());
  require_cloud(read_point_cloud(dir / "a.xyzn"));
  write(dir / "a.xyz", text.str());
  require_cloud(read_point_cloud(dir / "a.xyz")); // unit vectors in columns 4-6: normals
  write(dir / "a.txt", "0.5 -1.25 2\r\n1.5,0.25,-3\n\n-2 4 0.125\n");
  require_cloud(read_point_cloud(dir / "a.txt"), false);

  std::ostringstream csv;
  csv.precision(17);
  csv << "\xEF\xBB\xBFNX,ny,nz,x,y,z,intensity\n";
  for (const auto& p : kP)
    csv << p[3] << "," << p[4] << "," << p[5] << "," << p[0] << "," << p[1] << "," << p[2]
        << ",7\n";
  write(dir / "a.csv", csv.str());
  require_cloud(read_point_cloud(dir / "a.csv"));
}

TEST_CASE("readers: decisions are reported as notes", "[clouds][read]") {
  test::TempDir dir("clouds");
  std::vector<std::string> notes;
  // colour columns in an .xyz file are not normals
  write(dir / "rgb.xyz", "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n");
  const PointCloud c = read_point_cloud(dir / "rgb.xyz", &notes);
  CHECK_FALSE(c.has_normals());
  CHECK_THAT(notes.back(), Contains("columns 4-6 ignored"));
  // an organised PCD marks missing measurements with NaN: skipped
  write(dir / "org.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
                         "WIDTH 2\nHEIGHT 2\nPOINTS 4\nDATA ascii\n1 2 3\nnan nan nan\n4 5 6\n"
                         "7 8 9\n");
  CHECK(read_point_cloud(dir / "org.pcd", &notes).points.rows() == 3);
  CHECK_THAT(notes.back(), Contains("1 invalid (NaN) points of the organised cloud skipped"));
  // a zero normal: normals dropped (they will be estimated)
  write(dir / "zero.xyzn", "0 0 0 0 0 1\n1 0 0 0 0 0\n0 1 0 0 0 1\n");
  CHECK_FALSE(read_point_cloud(dir / "zero.xyzn", &notes).has_normals());
  CHECK_THAT(notes.back(), Contains("point 2 has a zero or non-finite normal"));
}

TEST_CASE("readers: malformed files give one line naming file and line", "[clouds][read]") {
  test::TempDir dir("clouds");
  struct Case {
    std::string name, content, message;
  };
  const std::string pts = "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n";
  const std::vector<Case> cases{
      {"bad.pcd", "garbage\n", "bad.pcd:1: not a PCD file"},
      {"empty.pcd", "", "empty.pcd: empty file"},
      {"nodata.pcd", "VERSION 0.7\nFIELDS x y z\n", "nodata.pcd: PCD header has no DATA line"},
      {"noz.pcd",
       "VERSION 0.7\nFIELDS x y\nSIZE 4 4\nTYPE F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2\n",
       "noz.pcd:2: FIELDS lacks z"},
      {"size.pcd", "VERSION 0.7\nFIELDS x y z\nSIZE 4 4\n", "size.pcd:3: SIZE has 2 values for 3"},
      {"key.pcd", "VERSION 0.7\nFIELDS x y z\nFOO 1\n",
       "key.pcd:3: unknown PCD header keyword 'FOO'"},
      {"word.pcd", pcd_header("ascii") + "0 0 abc 0 0 1\n" + pts.substr(12),
       "word.pcd:12: column z: 'abc' is not a number"},
      {"short.pcd", pcd_header("ascii") + "0 0\n" + pts.substr(12),
       "short.pcd:12: expected 6 values (FIELDS, COUNT), found 2"},
      {"nan.pcd", pcd_header("ascii") + "0 nan 0 0 0 1\n" + pts.substr(12),
       "nan.pcd:12: column y: 'nan' is not a finite value"},
      {"few.pcd", pcd_header("ascii") + pts.substr(12),
       "few.pcd:10: POINTS 3 but the data holds 2"},
      {"many.pcd", pcd_header("ascii", 2) + pts, "many.pcd:14: more data lines than POINTS 2"},
      {"wh.pcd", "VERSION 0.7\nFIELDS x y z\nWIDTH 3\nHEIGHT 1\nPOINTS 4\nDATA ascii\n",
       "wh.pcd:5: POINTS 4 differs from WIDTH x HEIGHT = 3 x 1"},
      {"huge.pcd", pcd_header("binary", 900000000) + std::string(24, '\0'),
       "huge.pcd:10: POINTS 900000000 needs 21600000000 bytes of binary data, the file holds 24"},
      {"lzf.pcd", pcd_header("binary_compressed") + std::string(8, '\0'),
       "lzf.pcd:11: binary_compressed data decompresses to 0 bytes"},
      {"bad.ply", "plyx\n", "bad.ply:1: not a PLY file"},
      {"fmt.ply", "ply\nformat text 1.0\n", "fmt.ply:2: unknown PLY format 'text'"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\n",
       "type.ply:4: expected 'property TYPE NAME'"},
      {"nov.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n",
       "nov.ply:5: no vertex element"},
      {"noz.ply",
       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 "
       "0\n",
       "noz.ply: the vertex element lacks the property z"},
      {"word.ply", ply_header("ascii", 3, false) + "0 0 0 0 0 1\n1 x 0 0 0 1\n0 1 0 0 0 1\n",
       "word.ply:13: 'x' is not a finite number"},
      {"count.ply",
       ply_header("ascii", 3, false) +
           "0.0 0.0 0.0 0.0 0.0 1.0\n1 0 0 0 0\n0.0 1.0 0.0 0.0 0.0 1.0\n",
       "count.ply:13: a line ends before the properties its element declares"},
      {"few.ply", ply_header("ascii", 3, false) + "0 0 0 0 0 1\n",
       "few.ply: the header declares 3 vertex elements, more than the 12 bytes"},
      {"huge.ply", ply_header("binary_little_endian", 300000000, false) + std::string(36, '\0'),
       "huge.ply: the header declares 300000000 vertex elements, more than the 36 bytes"},
      {"nohead.ply", "ply\nformat ascii 1.0\nelement vertex 1\n",
       "nohead.ply: the header does not end (no 'end_header' line)"},
      {"two.xyz", "0 0\n", "two.xyz:1: expected at least 3 fields (x y z), found 2"},
      {"ragged.xyz", "0 0 0\n1 1 1 1\n", "ragged.xyz:2: expected 3 fields (as on line 1), found 4"},
      {"nan.xyz", "0 0 0\nnan 1 1\n", "nan.xyz:2: column x: 'nan' is not a finite value"},
      {"inf.txt", "0 0 0\n1 inf 1\n", "inf.txt:2: column y: 'inf' is not a finite value"},
      {"short.xyzn", "0 0 0\n", "short.xyzn:1: expected 6 fields (x y z nx ny nz)"},
      {"none.xyz", "# nothing\n\n", "none.xyz: no points"},
      {"nx.csv", "x,y,z,nx,ny\n0,0,0,0,0\n",
       "nx.csv:1: header names only some of the normal columns"},
      {"word.csv", "x,y,z\n0,0,0\n1,a,1\n", "word.csv:3: column y: 'a' is not a number"},
      {"a.obj", "v 0 0 0\n", "a.obj: unknown point-cloud extension '.obj'"},
  };
  for (const Case& c : cases) {
    write(dir / c.name, c.content);
    INFO(c.name);
    CHECK_THAT(error_of(dir / c.name), StartsWith(dir / c.message));
  }
  CHECK_THAT(error_of(dir / "missing.pcd"), StartsWith(dir / "missing.pcd: cannot open"));
  // binary payloads are bounds-checked while decoding
  std::string ply = ply_header("binary_little_endian", 1, true);
  for (int k = 0; k < 3; ++k)
    put(ply, 1.0);
  for (int k = 0; k < 3; ++k)
    put(ply, 0.0f);
  put(ply, std::uint8_t{200}); // a face with 200 indices, file ends after 1
  put(ply, std::int32_t{0});
  CHECK(parse_point_cloud(ply, "f.ply").points.rows() == 1); // faces after the vertices: unread
  std::string front = "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                      "property list uchar int vertex_indices\nelement vertex 1\n"
                      "property float x\nproperty float y\nproperty float z\nend_header\n";
  front += std::string(1, char(200)) + std::string(16, '\0');
  CHECK_THAT(parse_error(front, "g.ply"),
             StartsWith("g.ply: face 0: list length 200 beyond the data"));
  std::string nan = pcd_header("binary", 1);
  for (float v : {0.f, std::nanf(""), 0.f, 0.f, 0.f, 1.f})
    put(nan, v);
  CHECK_THAT(parse_error(nan, "n.pcd"),
             StartsWith("n.pcd: point 1 (binary data): y is not a finite value"));
}
