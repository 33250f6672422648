// IGES entity 128 writer and reader: bit-exact round trips, the fixed 80-column layout of every
// section, Hollerith strings, a foreign-style file (other delimiters, D exponents, CRLF, a
// transformation matrix) and line-accurate errors for malformed files.
// Knots and control points are compared bit for bit: the writer prints the shortest decimal that
// reads back to the same double and the reader parses correctly rounded, so nothing may change.

#include "interlin/reconstruction/io/iges.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/knot_insertion.h"

#include "support/test_support.h"
#include "support/test_surfaces.h"

#include <catch2/catch.hpp>

#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

using namespace interlin;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
namespace fs = std::filesystem;

namespace {

// Random surface whose coordinates span many magnitudes (and a few awkward values), so the
// round trip exercises exponents, signs and 17-digit mantissas.
BSplineSurface random_surface(int pu, int pv, Eigen::Index nu, Eigen::Index nv, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-12, 12);
  BSplineSurface s;
  s.degree_u = pu;
  s.degree_v = pv;
  s.num_u = nu;
  s.num_v = nv;
  s.knots_u = test::random_clamped_knots(rng, pu, nu, -0.37, 2.9, true);
  s.knots_v = test::random_clamped_knots(rng, pv, nv, 1.0 / 3.0, 1e5 + 0.1, true);
  s.ctrl.resize(nu * nv, 3);
  for (Eigen::Index r = 0; r < s.ctrl.rows(); ++r)
    for (int c = 0; c < 3; ++c)
      s.ctrl(r, c) = coord(rng) * std::pow(10.0, exponent(rng));
  s.ctrl(0, 0) = -0.0;
  s.ctrl(1, 1) = 4.9406564584124654e-324; // smallest subnormal
  s.ctrl(2, 2) = 1.7976931348623157e308;  // largest double
  s.ctrl(3, 0) = 0.1;
  s.ctrl(3, 1) = 1.0 / 3.0;
  s.ctrl(3, 2) = -123456789012345678.0;
  return s;
}

// Closed tube: a periodic cubic cross-section (8 points on a circle of radius 2, clamped with
// periodic_to_clamped, so the seam is C^2) swept linearly (degree 1) through 3 levels in z.
BSplineSurface closed_tube_degree_3_1() {
  const int p = 3;
  const BSplineCurve clamped = test::clamped_ring(0.0);
  BSplineSurface s;
  s.degree_u = p;
  s.degree_v = 1;
  s.num_u = clamped.ctrl.rows();
  s.num_v = 3;
  s.knots_u = clamped.knots;
  s.knots_v.resize(5);
  s.knots_v << 0.0, 0.0, 0.4, 1.0, 1.0;
  s.closed_u = true;
  s.ctrl.resize(s.num_u * s.num_v, 3);
  const double z[3] = {0.0, 1.5, 4.0};
  for (Eigen::Index j = 0; j < s.num_v; ++j)
    for (Eigen::Index i = 0; i < s.num_u; ++i)
      s.ctrl.row(i + s.num_u * j) << clamped.ctrl(i, 0) * (1.0 + 0.1 * static_cast<double>(j)),
          clamped.ctrl(i, 1), z[j];
  return s;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

void require_identical(const BSplineSurface& a, const BSplineSurface& b) {
  CHECK(a.degree_u == b.degree_u);
  CHECK(a.degree_v == b.degree_v);
  CHECK(a.num_u == b.num_u);
  CHECK(a.num_v == b.num_v);
  CHECK(a.closed_u == b.closed_u);
  CHECK(same_bits(a.knots_u, b.knots_u));
  CHECK(same_bits(a.knots_v, b.knots_v));
  CHECK(same_bits(a.ctrl, b.ctrl));
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  std::string l;
  while (std::getline(in, l))
    lines.push_back(l);
  return lines;
}

void write_lines(const std::string& path, const std::vector<std::string>& lines,
                 const char* eol = "\n") {
  std::ofstream out(path, std::ios::binary);
  for (const std::string& l : lines)
    out << l << eol;
}

// The InputError message of read_iges_surface, or a marker that fails the caller's matchers.
std::string read_error(const std::string& path) {
  try {
    read_iges_surface(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Free-format parameters of a record (test-side tokenizer, default delimiters): Hollerith
// strings are decoded, so a wrong count shows up as a garbled parameter list.
std::vector<std::string> record_parameters(const std::string& text) {
  std::vector<std::string> out;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && text[i] == ' ') // padding at the end of the previous line
      ++i;
    std::size_t j = i;
    while (j < text.size() && std::isdigit(static_cast<unsigned char>(text[j])))
      ++j;
    std::string item;
    if (j > i && j < text.size() && text[j] == 'H') {
      const std::size_t n = std::stoul(text.substr(i, j - i));
      item = "H:" + text.substr(j + 1, n);
      i = j + 1 + n;
    } else {
      j = text.find_first_of(",;", i);
      item = text.substr(i, j - i);
      i = j;
    }
    out.push_back(item);
    if (i >= text.size() || text[i] == ';')
      break;
    ++i;
  }
  return out;
}

// Section lines of a file (columns 1-72, or 1-64 for P).
std::string section_text(const std::vector<std::string>& lines, char letter, std::size_t width) {
  std::string text;
  for (const std::string& l : lines)
    if (l.size() >= 73 && l[72] == letter)
      text += l.substr(0, width);
  return text;
}

struct ParameterPlace {
  long line = 0;          // 0-based line index
  std::size_t column = 0; // 0-based start column
  std::size_t length = 0;
};

// Where parameter `index` of the (only) parameter record starts; lines[first_p] is P line 1.
// Our writer never splits a parameter, so each one lies on a single line.
ParameterPlace locate_parameter(const std::vector<std::string>& lines, long first_p,
                                std::size_t index) {
  std::size_t k = 0;
  for (long i = first_p; lines[static_cast<std::size_t>(i)][72] == 'P'; ++i) {
    const std::string data = lines[static_cast<std::size_t>(i)].substr(0, 64);
    std::size_t b = 0;
    while (b < data.size() && data[b] != ' ') {
      const std::size_t e = data.find_first_of(",;", b);
      if (k == index)
        return {i, b, e - b};
      ++k;
      b = e + 1;
    }
  }
  throw std::logic_error("parameter not found");
}

// Replaces parameter `index` by `text` (the line stays 80 columns); returns its line index.
long replace_parameter(std::vector<std::string>& lines, long first_p, std::size_t index,
                       const std::string& text) {
  const ParameterPlace at = locate_parameter(lines, first_p, index);
  std::string& l = lines[static_cast<std::size_t>(at.line)];
  std::string data = l.substr(0, 64);
  data.replace(at.column, at.length, text);
  data.erase(data.find_last_not_of(' ') + 1);
  REQUIRE(data.size() <= 64);
  data.resize(64, ' ');
  l = data + l.substr(64);
  return at.line;
}

} // namespace

TEST_CASE("IGES round trip is bit-exact for a random bicubic surface", "[iges]") {
  test::TempDir tmp("iges-bicubic");
  const BSplineSurface s = random_surface(3, 3, 9, 7, 20240601u);
  const std::string path = tmp.file("bicubic.igs");
  write_iges(path, s);
  require_identical(s, read_iges_surface(path));
}

TEST_CASE("IGES round trip is bit-exact for a degree (3,1) closed surface", "[iges]") {
  test::TempDir tmp("iges-deg31");
  const BSplineSurface tube = closed_tube_degree_3_1();
  const std::string path = tmp.file("tube.igs");
  write_iges(path, tube, {LengthUnit::inch, "someone", "closed tube"});
  const BSplineSurface back = read_iges_surface(path);
  require_identical(tube, back);
  CHECK(back.closed_u);

  // An open (3,1) surface with random data keeps closed_u = false.
  const BSplineSurface open = random_surface(3, 1, 6, 5, 7u);
  write_iges(path, open);
  require_identical(open, read_iges_surface(path));
}

TEST_CASE("IGES file layout: 80 columns, sections, sequence numbers, Terminate counts", "[iges]") {
  test::TempDir tmp("iges-layout");
  const BSplineSurface s = random_surface(3, 2, 6, 4, 99u);
  const std::string path = tmp.file("layout.igs");
  write_iges(path, s, {LengthUnit::mm, "Ada Lovelace", "first line\nsecond line"});
  const std::vector<std::string> lines = read_lines(path);
  REQUIRE(lines.size() > 6);

  std::string letters;
  long count[5] = {0, 0, 0, 0, 0};
  const std::string order = "SGDPT";
  for (const std::string& l : lines) {
    REQUIRE(l.size() == 80);
    const auto k = order.find(l[72]);
    REQUIRE(k != std::string::npos);
    if (letters.empty() || letters.back() != l[72])
      letters += l[72];
    ++count[k];
    // Columns 74-80: the sequence number within the section, right-justified.
    CHECK(l.substr(73) ==
          std::string(7 - std::to_string(count[k]).size(), ' ') + std::to_string(count[k]));
  }
  CHECK(letters == "SGDPT"); // each section once, in order
  CHECK(count[2] == 2);      // one entity: two Directory Entry lines
  CHECK(count[4] == 1);

  // Terminate line: counts of S, G, D, P.
  char expected_t[64];
  std::snprintf(expected_t, sizeof expected_t, "S%7ldG%7ldD%7ldP%7ld", count[0], count[1], count[2],
                count[3]);
  CHECK(lines.back().substr(0, 72) == std::string(expected_t) + std::string(40, ' '));

  // Start section: the description, one line per paragraph.
  const std::string start = section_text(lines, 'S', 72);
  CHECK_THAT(start, Contains("entity 128, polynomial, untrimmed)"));
  CHECK_THAT(start, Contains("first line"));
  CHECK_THAT(start, Contains("second line"));

  // Global section: Hollerith strings decode to the intended values.
  const std::vector<std::string> g = record_parameters(section_text(lines, 'G', 72));
  REQUIRE(g.size() == 25);
  CHECK(g[0] == "H:,");
  CHECK(g[1] == "H:;");
  CHECK(g[3] == "H:layout.igs");
  CHECK(g[13] == "2"); // unit flag: millimetres
  CHECK(g[14] == "H:MM");
  // Date "YYYYMMDD.HHNNSS".
  REQUIRE(g[17].size() == 17);
  CHECK(g[17].substr(0, 2) == "H:");
  CHECK(g[17][10] == '.');
  for (std::size_t k = 2; k < 17; ++k)
    CHECK((k == 10 || std::isdigit(static_cast<unsigned char>(g[17][k]))));
  CHECK(g[20] == "H:Ada Lovelace");
  CHECK(g[22] == "11"); // IGES 5.3

  // Directory Entry: 8-column fields.
  const std::string& d1 = lines[static_cast<std::size_t>(count[0] + count[1])];
  const std::string& d2 = lines[static_cast<std::size_t>(count[0] + count[1] + 1)];
  CHECK(d1.substr(0, 8) == "     128");
  CHECK(d1.substr(8, 8) == "       1");  // parameter data starts at P line 1
  CHECK(d1.substr(64, 8) == "00000000"); // status: visible, independent, geometry
  CHECK(d2.substr(0, 8) == "     128");
  CHECK(std::stol(d2.substr(24, 8)) == count[3]); // parameter line count
  CHECK(d2.substr(32, 8) == "       0");          // form 0

  // Parameter Data: column 65 blank, 66-72 the DE pointer 1; the record has every value.
  for (const std::string& l : lines)
    if (l[72] == 'P') {
      CHECK(l[64] == ' ');
      CHECK(l.substr(65, 7) == "      1");
    }
  const std::vector<std::string> p = record_parameters(section_text(lines, 'P', 64));
  const std::size_t n_ctrl = static_cast<std::size_t>(s.num_u * s.num_v);
  REQUIRE(p.size() ==
          10 + static_cast<std::size_t>(s.knots_u.size() + s.knots_v.size()) + 4 * n_ctrl + 4);
  CHECK(p[0] == "128");
  CHECK(p[1] == "5"); // K1 = num_u - 1
  CHECK(p[2] == "3");
  CHECK(p[3] == "3");
  CHECK(p[4] == "2");
  CHECK(p[7] == "1"); // PROP3: polynomial
  for (std::size_t k = 0; k < n_ctrl; ++k)
    CHECK(p[10 + static_cast<std::size_t>(s.knots_u.size() + s.knots_v.size()) + k] == "1.");
  // Real constants always carry a decimal point (IGES syntax), e.g. the first u knot -0.37.
  CHECK(p[10] == "-0.37");

  // Other units: flag and name.
  const std::pair<LengthUnit, std::pair<const char*, const char*>> units[] = {
      {LengthUnit::cm, {"10", "H:CM"}},
      {LengthUnit::m, {"6", "H:M"}},
      {LengthUnit::inch, {"1", "H:IN"}}};
  for (const auto& [unit, label] : units) {
    write_iges(path, s, {unit, "", ""});
    const std::vector<std::string> gu = record_parameters(section_text(read_lines(path), 'G', 72));
    REQUIRE(gu.size() == 25);
    CHECK(gu[13] == label.first);
    CHECK(gu[14] == label.second);
    CHECK(gu[20].empty()); // empty author: defaulted parameter
  }
}

TEST_CASE("IGES reader accepts a foreign-style file with a transformation matrix", "[iges]") {
  // Written independently of write_iges: delimiters '/' and '#', D exponents, zero-padded
  // sequence numbers, CRLF line ends, a bilinear patch transformed by entity 124
  // (rotation by 90 degrees about z, then translation by (10, 20, 30)).
  test::TempDir tmp("iges-foreign");
  const std::string path = tmp.file("foreign.iges");
  auto line = [](std::string data, char section, int seq) {
    data.resize(72, ' ');
    char tail[16];
    std::snprintf(tail, sizeof tail, "%c%07d", section, seq);
    return data + tail;
  };
  auto pline = [&](std::string data, int de, int seq) {
    data.resize(64, ' ');
    char ptr[16];
    std::snprintf(ptr, sizeof ptr, " %7d", de);
    return line(data + ptr, 'P', seq);
  };
  auto de = [&](int type, int param, int transform, int count, int seq) {
    char l1[80], l2[80];
    std::snprintf(l1, sizeof l1, "%8d%8d%8d%8d%8d%8d%8d%8d%8s", type, param, 0, 0, 0, 0, transform,
                  0, "00000000");
    std::snprintf(l2, sizeof l2, "%8d%8d%8d%8d%8d%8s%8s%8s%8d", type, 0, 0, count, 0, "", "", "",
                  0);
    return std::vector<std::string>{line(l1, 'D', seq), line(l2, 'D', seq + 1)};
  };
  const auto de124 = de(124, 1, 0, 1, 1), de128 = de(128, 2, 1, 3, 3);
  const std::vector<std::string> lines = {
      line("foreign writer", 'S', 1),
      line("1H//1H#/7Hforeign/11Hforeign.igs/3Hxyz/3H1.0/32/38/6/308/15/", 'G', 1),
      line("7Hforeign/1.0D0/2/2HMM/1/0.1D0/15H20240101.000000/1.0D-6/40.0D0/", 'G', 2),
      line("1HA/1HB/11/0#", 'G', 3),
      de124[0],
      de124[1],
      de128[0],
      de128[1],
      pline("124/0.0D0/-1.0D0/0.0/10.0/1.0/0./0./2.0D1/0/0/1.0/3.0D+01#", 1, 1),
      pline("128/1/1/1/1/0/0/0/0/0/0.0D0/0.0/1.0D0/1.0/-1/-1/2.5D0/2.5/1.0D0/", 3, 2),
      pline("1.0/1.0D0/1.0/0.0/0.0/0.0/+1.0D0/0/0/0/1/0.5D0/1.0D0/1/1/", 3, 3),
      pline("0.0D0/1.0/-1.0D0/2.5#", 3, 4),
      line("S0000001G0000003D0000004P0000004", 'T', 1),
  };
  write_lines(path, lines, "\r\n");
  const BSplineSurface s = read_iges_surface(path);
  CHECK(s.degree_u == 1);
  CHECK(s.degree_v == 1);
  CHECK(s.num_u == 2);
  CHECK(s.num_v == 2);
  CHECK_FALSE(s.closed_u);
  CHECK(s.knots_u == (Eigen::VectorXd(4) << 0, 0, 1, 1).finished());
  CHECK(s.knots_v == (Eigen::VectorXd(4) << -1, -1, 2.5, 2.5).finished());
  // Points before the transform: (0,0,0), (1,0,0), (0,1,0.5), (1,1,1); x' = (-y, x, z) + T.
  Eigen::MatrixXd expected(4, 3);
  expected << 10, 20, 30, 10, 21, 30, 9, 20, 30.5, 9, 21, 31;
  CHECK(s.ctrl == expected); // exact: every operation is on small integers and halves
}

TEST_CASE("IGES reader reports malformed files with file and line", "[iges]") {
  test::TempDir tmp("iges-bad");
  const BSplineSurface s = random_surface(3, 3, 5, 5, 5u);
  const std::string good = tmp.file("good.igs");
  write_iges(good, s);
  const std::vector<std::string> lines = read_lines(good);
  long first_p = 0; // 0-based index of the first P line
  while (lines[static_cast<std::size_t>(first_p)][72] != 'P')
    ++first_p;
  const std::string bad = tmp.file("bad.igs");
  auto error_for = [&](const std::vector<std::string>& l) {
    write_lines(bad, l);
    return read_error(bad);
  };
  auto at_line = [&](long line) { return bad + ":" + std::to_string(line) + ": "; };

  SECTION("missing file") {
    CHECK_THAT(read_error(tmp.file("none.igs")), StartsWith(tmp.file("none.igs") + ": "));
  }
  SECTION("truncated: no Terminate section") {
    std::vector<std::string> l(lines.begin(), lines.end() - 2);
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(static_cast<long>(l.size()))));
    CHECK_THAT(e, Contains("Terminate"));
  }
  SECTION("truncated in the middle of a line") {
    std::vector<std::string> l(lines.begin(), lines.begin() + first_p + 2);
    l.back().resize(40);
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(first_p + 2)));
    CHECK_THAT(e, Contains("columns"));
  }
  SECTION("Terminate counts do not match (P lines lost)") {
    std::vector<std::string> l(lines.begin(), lines.end() - 2);
    l.push_back(lines.back());
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(static_cast<long>(l.size()))));
  }
  SECTION("parameter data of another entity") {
    std::vector<std::string> l = lines;
    l[static_cast<std::size_t>(first_p)].replace(0, 3, "126");
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(first_p + 1)));
    CHECK_THAT(e, Contains("entity 126, expected 128"));
  }
  SECTION("no entity 128 at all") {
    std::vector<std::string> l = lines;
    l[static_cast<std::size_t>(first_p - 2)].replace(5, 3, "126");
    l[static_cast<std::size_t>(first_p - 1)].replace(5, 3, "126");
    CHECK_THAT(error_for(l), StartsWith(bad + ": ") && Contains("entity 128"));
  }
  SECTION("bad number") {
    // Corrupt the first parameter of P line 3 (a knot or a coordinate): "x" is no number.
    std::vector<std::string> l = lines;
    l[static_cast<std::size_t>(first_p + 2)][0] = 'x';
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(first_p + 3)));
    CHECK_THAT(e, Contains("bad number"));
  }
  SECTION("wrong sequence number") {
    std::vector<std::string> l = lines;
    l[static_cast<std::size_t>(first_p + 1)][79] = '9';
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(first_p + 2)));
    CHECK_THAT(e, Contains("sequence number"));
  }
  SECTION("decreasing knots") {
    // 5 control points of degree 3: u knots are parameters 10..18, knot 4 (parameter 14) is the
    // only interior one; 1E9 is beyond the end knots, so knot 5 decreases.
    std::vector<std::string> l = lines;
    const long line = replace_parameter(l, first_p, 14, "1E9");
    const long next = locate_parameter(l, first_p, 15).line;
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(next + 1)));
    CHECK_THAT(e, Contains("u knots decrease at knot 5"));
    CHECK(line <= next);
  }
  SECTION("rational weights") {
    // Weights are parameters 28..52; the third one differs from the first.
    std::vector<std::string> l = lines;
    REQUIRE(record_parameters(section_text(l, 'P', 64))[30] == "1.");
    const long line = replace_parameter(l, first_p, 30, "2.");
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(line + 1)));
    CHECK_THAT(e, Contains("rational"));
  }
  SECTION("unclamped knots") {
    std::vector<std::string> l = lines;
    const long line = replace_parameter(l, first_p, 10, "-1");
    const std::string e = error_for(l);
    CHECK_THAT(e, StartsWith(at_line(line + 1)));
    CHECK_THAT(e, Contains("not clamped"));
  }
}

TEST_CASE("write_iges failures leave no file behind", "[iges]") {
  test::TempDir tmp("iges-fail");
  const BSplineSurface s = random_surface(3, 3, 5, 5, 1u);
  // Missing directory.
  CHECK_THROWS_AS(write_iges(tmp.file("missing/x.igs"), s), std::runtime_error);
  CHECK_FALSE(fs::exists(tmp.path() / "missing"));
  // The target is a directory: the final rename fails, the temporary file is removed.
  fs::create_directories(tmp.path() / "taken.igs");
  CHECK_THROWS_AS(write_iges(tmp.file("taken.igs"), s), std::runtime_error);
  // An invalid surface is a programming error, detected before anything is written.
  BSplineSurface broken = s;
  broken.ctrl(0, 0) = std::nan("");
  CHECK_THROWS_AS(write_iges(tmp.file("broken.igs"), broken), std::invalid_argument);
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(tmp.path()))
    left.push_back(entry.path().filename().string());
  CHECK(left == std::vector<std::string>{"taken.igs"});
  CHECK(fs::is_directory(tmp.path() / "taken.igs"));
}
