// PLY and OBJ in double precision: what write_mesh writes reads back bit for bit, foreign PLY
// variants (ASCII, big-endian, other types, extra properties, polygons) read as written, and
// malformed files give one error line before anything large is allocated.
#include "support/test_support.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/mesh_io.h"

#include <catch2/catch.hpp>

#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

using namespace interlin;
using Catch::Contains;

namespace {

// A random soup: coordinates with all 53 bits used, over several magnitudes.
void random_mesh(Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  V.resize(50, 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      V(i, k) = u(rng) * std::pow(10.0, double(i % 9) - 4);
  F.resize(40, 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      F(f, k) = int((f * 7 + k * 13) % V.rows());
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <class T>
std::string bytes(T v, bool big_endian = false) {
  std::string b(sizeof(T), '\0');
  std::memcpy(b.data(), &v, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big))
    std::reverse(b.begin(), b.end());
  return b;
}

void parse(const std::string& text, const std::string& name, Eigen::MatrixXd& V,
           Eigen::MatrixXi& F) {
  parse_mesh(text, name, V, F);
}

std::string error_of(const std::string& text, const std::string& name) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  try {
    parse(text, name, V, F);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

} // namespace

TEST_CASE("PLY and OBJ round trip doubles bit for bit, float precision rounds to float",
          "[mesh][precision]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  random_mesh(V, F);
  const test::TempDir dir("mesh-formats");
  for (const std::string ext : {".ply", ".obj", ".PLY"}) {
    INFO(ext);
    const std::string path = dir / ("m" + ext);
    write_mesh(path, V, F);
    Eigen::MatrixXd Vr;
    Eigen::MatrixXi Fr;
    read_mesh(path, Vr, Fr);
    CHECK(Vr == V); // exact: 17 significant digits / 8-byte doubles
    CHECK(Fr == F);
    write_mesh(path, V, F, MeshPrecision::float32);
    read_mesh(path, Vr, Fr);
    // Each coordinate is the nearest float (OBJ: its shortest decimal, which reads back to it).
    CHECK(Vr.cast<float>() == V.cast<float>());
    CHECK(Fr == F);
  }
  // The double PLY header and size: 24 bytes per vertex, 13 per triangle.
  const std::string path = dir / "m.ply";
  write_mesh(path, V, F);
  const std::string ply = slurp(path);
  CHECK(ply.find("format binary_little_endian 1.0\n") != std::string::npos);
  CHECK(ply.find("property double x\nproperty double y\nproperty double z\n") != std::string::npos);
  const std::size_t header = ply.find("end_header\n") + 11;
  CHECK(ply.size() - header == std::size_t(24 * V.rows() + 13 * F.rows()));
}

TEST_CASE("PLY reader: ASCII, big-endian, other types, extra properties, polygons",
          "[mesh][precision]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  // ASCII with CRLF, a comment, colours, a quad (split into a fan) and an extra element.
  const std::string ascii =
      "ply\r\nformat ascii 1.0\r\ncomment made by hand\r\nelement vertex 4\r\n"
      "property float x\r\nproperty float y\r\nproperty float z\r\nproperty uchar red\r\n"
      "element face 1\r\nproperty list uchar int vertex_indices\r\nelement edge 1\r\n"
      "property int a\r\nproperty int b\r\nend_header\r\n"
      "0 0 0 255\r\n1 0 0 0\r\n1 1 0.5 7\r\n0 1 0.25 9\r\n4 0 1 2 3\r\n0 1\r\n";
  parse(ascii, "a.ply", V, F);
  Eigen::MatrixXd Ve(4, 3);
  Ve << 0, 0, 0, 1, 0, 0, 1, 1, 0.5, 0, 1, 0.25;
  CHECK(V == Ve);
  Eigen::MatrixXi Fe(2, 3);
  Fe << 0, 1, 2, 0, 2, 3;
  CHECK(F == Fe);
  // Big-endian doubles, a ushort-counted uint index list named vertex_index, a property after
  // the list.
  std::string big = "ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\n"
                    "property double y\nproperty double z\nelement face 1\n"
                    "property list ushort uint vertex_index\nproperty float quality\nend_header\n";
  for (const double x : {0.1, 0.2, 0.3, 1.0 / 3, 2.0, 3.0, -1e-300, 5e300, 7.0})
    big += bytes(x, true);
  big += bytes<std::uint16_t>(3, true) + bytes<std::uint32_t>(2, true) +
         bytes<std::uint32_t>(0, true) + bytes<std::uint32_t>(1, true) + bytes(0.5f, true);
  parse(big, "b.ply", V, F);
  CHECK(V(0, 0) == 0.1);
  CHECK(V(1, 0) == 1.0 / 3);
  CHECK(V(2, 1) == 5e300);
  CHECK(F(0, 0) == 2);
  CHECK(F(0, 2) == 1);
}

TEST_CASE("PLY and OBJ readers: one error line, counts checked before allocation",
          "[mesh][precision]") {
  const std::string head = "ply\nformat binary_little_endian 1.0\n";
  // A header that declares far more than the file holds is rejected before any allocation.
  CHECK_THAT(error_of(head +
                          "element vertex 400000000\nproperty double x\nproperty double y\n"
                          "property double z\nend_header\n" +
                          std::string(48, '\0'),
                      "h.ply"),
             Contains("h.ply: the header declares 400000000 vertex elements, more than the 48 "
                      "bytes"));
  CHECK_THAT(error_of(head +
                          "element vertex 1\nproperty double x\nproperty double y\n"
                          "property double z\nelement face 18446744073709551615\n"
                          "property list uchar int vertex_indices\nend_header\n" +
                          std::string(40, '\0'),
                      "h.ply"),
             Contains("face elements, more than"));
  CHECK_THAT(error_of("solid x\n", "j.ply"), Contains("j.ply:1: not a PLY file"));
  CHECK_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n"
                      "0\n",
                      "m.ply"),
             Contains("m.ply:6: the vertex element lacks the property x, y or z"));
  CHECK_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                      "3 0 1 3\n",
                      "i.ply"),
             Contains("i.ply:13: face 0: vertex index 3 outside [0, 3)"));
  CHECK_THAT(error_of("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                      "property float y\nproperty float z\nend_header\n0 nan 0\n",
                      "n.ply"),
             Contains("n.ply:8: 'nan' is not a finite number"));
  CHECK_THAT(error_of("ply\nformat binary_little_endian 1.0\nproperty float x\n", "p.ply"),
             Contains("p.ply:3: a property before any element"));
  // OBJ: line numbers, negative indices, a/t/n references, polygons.
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  parse("# c\nv 0 0 0\nv 1 0 0\nvt 0 0\nv 1 1 0\nv 0 1 0 1\nf 1/1 2/1/1 -2//1 -1\n", "q.obj", V, F);
  CHECK(V.rows() == 4);
  Eigen::MatrixXi Fe(2, 3);
  Fe << 0, 1, 2, 0, 2, 3;
  CHECK(F == Fe);
  CHECK_THAT(error_of("v 0 0 0\nv 1 0 0\nf 1 2 3\n", "r.obj"),
             Contains("r.obj:3: vertex reference '3' is not in 1..2"));
  CHECK_THAT(error_of("v 0 0 abc\n", "s.obj"),
             Contains("s.obj:1: column z: 'abc' is not a number"));
  CHECK_THAT(error_of("", "e.obj"), Contains("e.obj: no vertex"));
}
