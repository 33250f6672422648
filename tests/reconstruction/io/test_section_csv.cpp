// Section-file reader and writer: formats, ordering, warnings and every error message.
// Coordinates in these tests are compared exactly: the reader must give the correctly rounded
// double of each decimal token (the same value the compiler gives the literal, or strtod gives).

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/section_csv.h"

#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

using namespace interlin;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;

namespace {

SectionSet parse(const std::string& text, const std::string& name = "in.csv") {
  std::istringstream in(text);
  return parse_sections(in, name);
}

// The InputError message, or a marker that makes the caller's matchers fail.
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Rows "id,k,x,y,z" of a test section: point k is (k + 0.5, 2k, z), all distinct.
std::string rows(const std::string& id, double z, int n = 4) {
  std::string s;
  for (int k = 0; k < n; ++k)
    s += id + "," + std::to_string(k) + "," + std::to_string(k + 0.5) + "," +
         std::to_string(2 * k) + "," + std::to_string(z) + "\n";
  return s;
}

Eigen::MatrixXd expected_points(double z, int n = 4) {
  Eigen::MatrixXd p(n, 3);
  for (int k = 0; k < n; ++k)
    p.row(k) << k + 0.5, 2 * k, z;
  return p;
}

std::vector<std::string> ids(const SectionSet& s) {
  std::vector<std::string> r;
  for (const Section& x : s.sections)
    r.push_back(x.id);
  return r;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

} // namespace

TEST_CASE("rotor37 sections.csv: 13 sections of 198 points, values as in the file text", "[csv]") {
  const std::string path = INTERLIN_DATA_DIR "/rotor37/sections.csv";
  const SectionSet s = read_sections(path);
  CHECK(s.path == path);
  CHECK(s.warnings.empty());
  REQUIRE(s.sections.size() == 13);
  for (size_t i = 0; i < 13; ++i) {
    CHECK(s.sections[i].id == std::to_string(i));
    REQUIRE(s.sections[i].points.rows() == 198);
    REQUIRE(s.sections[i].lines.size() == 198);
  }
  // First and last rows of sections 0 and 12 (file lines 2, 199, 2378, 2575).
  const Section& s0 = s.sections[0];
  const Section& s12 = s.sections[12];
  CHECK(s0.points.row(0) == Eigen::RowVector3d(17.6697245, -2.0683810, 0.0281091));
  CHECK(s0.points.row(197) == Eigen::RowVector3d(17.6691286, -2.0747417, 0.0289117));
  CHECK(s12.points.row(0) == Eigen::RowVector3d(25.1089121, -2.4918028, 0.6383425));
  CHECK(s12.points.row(197) == Eigen::RowVector3d(25.1084226, -2.4953421, 0.6388631));
  CHECK(s0.lines.front() == 2);
  CHECK(s0.lines.back() == 199);
  CHECK(s12.lines.front() == 2378);
  CHECK(s12.lines.back() == 2575);

  // Every row against an independent parse of the text (sscanf/strtod).
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  CHECK(line == "section,index,x,y,z");
  long n = 1, count = 0;
  while (std::getline(in, line)) {
    ++n;
    int sec = -1;
    long idx = -1;
    double x, y, z;
    REQUIRE(std::sscanf(line.c_str(), "%d,%ld,%lf,%lf,%lf", &sec, &idx, &x, &y, &z) == 5);
    const Section& t = s.sections[static_cast<size_t>(sec)];
    CHECK(t.lines[static_cast<size_t>(idx)] == n);
    CHECK(t.points.row(idx) == Eigen::RowVector3d(x, y, z));
    ++count;
  }
  CHECK(count == 13 * 198);
}

TEST_CASE("csv: columns in any order, names trimmed and case-insensitive, extra columns ignored",
          "[csv]") {
  const std::string text = " Z ,note, X,INDEX,y ,Section\n"
                           "5,a,0.5,0,0,s1\n"
                           "5,b,1.5,1,2,s1\n"
                           "5,,2.5,2,4,s1\n"
                           "5,d e,3.5,3,6,s1\n"
                           "7,a,0.5,0,0,s2\n"
                           "7,b,1.5,1,2,s2\n"
                           "7,c,2.5,2,4,s2\n"
                           "7,d,3.5,3,6,s2\n";
  const SectionSet s = parse(text);
  REQUIRE(ids(s) == std::vector<std::string>{"s1", "s2"});
  CHECK(s.sections[0].points == expected_points(5));
  CHECK(s.sections[1].points == expected_points(7));
  CHECK(s.sections[0].lines == std::vector<long>{2, 3, 4, 5});
  CHECK(s.sections[1].lines == std::vector<long>{6, 7, 8, 9});
  CHECK(s.warnings.empty());
}

TEST_CASE("csv: without an index column points keep the file order", "[csv]") {
  // Section 0 written in reverse order: the reader must not reorder it.
  const std::string text = "section,x,y,z\n"
                           "0,3.5,6,1\n0,2.5,4,1\n0,1.5,2,1\n0,0.5,0,1\n"
                           "1,0.5,0,2\n1,1.5,2,2\n1,2.5,4,2\n1,3.5,6,2\n";
  const SectionSet s = parse(text);
  REQUIRE(s.sections.size() == 2);
  CHECK(s.sections[0].points == expected_points(1).colwise().reverse());
  CHECK(s.sections[1].points == expected_points(2));
  CHECK(s.sections[0].lines == std::vector<long>{2, 3, 4, 5});
}

TEST_CASE("csv: the index column defines the order of shuffled rows", "[csv]") {
  const std::string text = "section,index,x,y,z\n"
                           "0,2,2.5,4,1\n0,0,0.5,0,1\n0,3,3.5,6,1\n0,1,1.5,2,1\n"
                           "1,3,3.5,6,2\n1,1,1.5,2,2\n1,0,0.5,0,2\n1,2,2.5,4,2\n";
  const SectionSet s = parse(text);
  REQUIRE(s.sections.size() == 2);
  CHECK(s.sections[0].points == expected_points(1));
  CHECK(s.sections[1].points == expected_points(2));
  CHECK(s.sections[0].lines == std::vector<long>{3, 5, 2, 4});
  CHECK(s.sections[1].lines == std::vector<long>{8, 7, 9, 6});
}

TEST_CASE("csv: non-contiguous runs are grouped with an index, rejected without", "[csv]") {
  SECTION("with index: grouped, order from index") {
    const std::string text = "section,index,x,y,z\n"
                             "0,0,0.5,0,1\n0,1,1.5,2,1\n"
                             "1,0,0.5,0,2\n1,1,1.5,2,2\n1,2,2.5,4,2\n1,3,3.5,6,2\n"
                             "0,2,2.5,4,1\n0,3,3.5,6,1\n";
    const SectionSet s = parse(text);
    REQUIRE(s.sections.size() == 2);
    CHECK(s.sections[0].points == expected_points(1));
    CHECK(s.sections[0].lines == std::vector<long>{2, 3, 8, 9});
    CHECK(s.sections[1].points == expected_points(2));
  }
  SECTION("without index: error at the resuming row naming the previous run's end") {
    const std::string text = "section,x,y,z\n"
                             "0,0.5,0,1\n0,1.5,2,1\n"
                             "1,0.5,0,2\n1,1.5,2,2\n1,2.5,4,2\n1,3.5,6,2\n"
                             "# comment between runs\n"
                             "0,2.5,4,1\n0,3.5,6,1\n";
    CHECK(error_of(text) == "in.csv:9: rows of section 0 resume here after other sections (its "
                            "previous run ended at line 3); make them contiguous or add an index "
                            "column");
  }
}

TEST_CASE("plain x y z files: without header, with header, separators, CRLF and BOM", "[csv]") {
  const Eigen::MatrixXd a = expected_points(1), b = expected_points(2), c = expected_points(3);
  SECTION("no header, whitespace, several blank lines, blank lines at both ends") {
    const std::string text = "\n  \n0.5 0 1\n1.5\t2 1\n2.5 4  1\n3.5 6 1\n\n\n"
                             "0.5 0 2\n1.5 2 2\n2.5 4 2\n3.5 6 2\n \t\n"
                             "0.5 0 3\n1.5 2 3\n2.5 4 3\n3.5 6 3\n\n";
    const SectionSet s = parse(text, "p.xyz");
    REQUIRE(ids(s) == std::vector<std::string>{"1", "2", "3"});
    CHECK(s.sections[0].points == a);
    CHECK(s.sections[1].points == b);
    CHECK(s.sections[2].points == c);
    CHECK(s.sections[0].lines == std::vector<long>{3, 4, 5, 6});
    CHECK(s.sections[1].lines == std::vector<long>{9, 10, 11, 12});
    CHECK(s.sections[2].lines == std::vector<long>{14, 15, 16, 17});
  }
  SECTION("header naming x, y, z in another order; commas and/or spaces") {
    const std::string text = "Z, y x\n"
                             "1,0,0.5\n1, 2 ,1.5\n1 4 2.5\n1 ,6, 3.5\n\n"
                             "2,0,0.5\n2,2,1.5\n2,4,2.5\n2,6,3.5\n";
    const SectionSet s = parse(text, "p.xyz");
    REQUIRE(s.sections.size() == 2);
    CHECK(s.sections[0].points == a);
    CHECK(s.sections[1].points == b);
    CHECK(s.sections[0].lines == std::vector<long>{2, 3, 4, 5});
  }
  SECTION("CRLF line ends, UTF-8 BOM, header x,y,z, no final line end") {
    const std::string text = "\xEF\xBB\xBFx,y,z\r\n"
                             "0.5,0,1\r\n1.5,2,1\r\n2.5,4,1\r\n3.5,6,1\r\n\r\n"
                             "0.5,0,2\r\n1.5,2,2\r\n2.5,4,2\r\n3.5,6,2";
    const SectionSet s = parse(text, "p.xyz");
    REQUIRE(s.sections.size() == 2);
    CHECK(s.sections[0].points == a);
    CHECK(s.sections[1].points == b);
    CHECK(s.sections[1].lines.back() == 10);
  }
  SECTION("CRLF and BOM in a section CSV") {
    const std::string text = "\xEF\xBB\xBFsection,index,x,y,z\r\n" + rows("0", 1) + rows("1", 2);
    std::string crlf;
    for (char ch : text)
      crlf += ch == '\n' ? std::string("\r\n") : std::string(1, ch);
    const SectionSet s = parse(crlf);
    REQUIRE(s.sections.size() == 2);
    CHECK(s.sections[0].points == a);
    CHECK(s.sections[1].points == b);
  }
}

TEST_CASE("comment lines are skipped and do not separate plain sections", "[csv]") {
  SECTION("csv") {
    const std::string text = "# generated by hand\n  # indented comment\nsection,index,x,y,z\n" +
                             rows("0", 1, 2) + "# middle of section 0\n" +
                             "0,2,2.5,4,1\n0,3,3.5,6,1\n" + rows("1", 2);
    const SectionSet s = parse(text);
    REQUIRE(s.sections.size() == 2);
    CHECK(s.sections[0].points == expected_points(1));
    CHECK(s.sections[0].lines == std::vector<long>{4, 5, 7, 8});
  }
  SECTION("plain") {
    const std::string text = "# x y z\n0.5 0 1\n1.5 2 1\n# still section 1\n2.5 4 1\n3.5 6 1\n\n"
                             "# section 2\n0.5 0 2\n1.5 2 2\n2.5 4 2\n3.5 6 2\n";
    const SectionSet s = parse(text);
    REQUIRE(s.sections.size() == 2);
    CHECK(s.sections[0].points == expected_points(1));
    CHECK(s.sections[0].lines == std::vector<long>{2, 3, 5, 6});
    CHECK(s.sections[1].lines.front() == 9);
  }
}

TEST_CASE("errors: file access and empty content", "[csv]") {
  test::TempDir dir("csv");
  CHECK_THROWS_WITH(read_sections(dir.file("missing.csv")),
                    dir.file("missing.csv") + ": cannot open: No such file or directory");
  CHECK_THROWS_WITH(read_sections(dir.path().string()),
                    dir.path().string() + ": cannot open: Is a directory");
  CHECK_THROWS_AS(read_sections(dir.file("missing.csv")), InputError);
  write_text(dir.file("empty.csv"), "");
  CHECK_THROWS_WITH(read_sections(dir.file("empty.csv")),
                    StartsWith(dir.file("empty.csv") + ": no data rows"));
  CHECK_THAT(error_of("# only a comment\n\n  \n"),
             StartsWith("in.csv: no data rows") && Contains("comments"));
  CHECK(error_of("\n# c\nsection,x,y,z\n\n") == "in.csv: no data rows after the header on line 3");
  CHECK(error_of("x y z\n") == "in.csv: no data rows after the header on line 1");
}

TEST_CASE("errors: header problems", "[csv]") {
  // First content line numeric with a field count other than 3: no header.
  CHECK_THAT(error_of("# c\n0,0,17.6,-2.0,0.02\n0,1,17.7,-2.0,0.03\n"),
             StartsWith("in.csv:2: no header: this first line has 5 fields") &&
                 Contains("section, x, y, z") && Contains("3 numbers x y z"));
  CHECK_THAT(error_of("section,index,x,y\n0,0,1,2\n"),
             StartsWith("in.csv:1: header lacks the required column(s) z:") &&
                 Contains("section, x, y, z"));
  CHECK_THAT(error_of("section,a,b\n0,1,2\n"),
             StartsWith("in.csv:1: header lacks the required column(s) x, y, z:"));
  CHECK_THAT(error_of("\nid,x,y,z\n0,1,2,3\n"),
             StartsWith("in.csv:2: header lacks the section column") &&
                 Contains("exactly x, y, z"));
  CHECK_THAT(error_of("x y z w\n1 2 3 4\n"),
             StartsWith("in.csv:1: header lacks the section column"));
  CHECK_THAT(error_of("section x y z\n0 1 2 3\n"),
             StartsWith("in.csv:1: the header names a section column but has no commas"));
  CHECK(error_of("section,x,y,z,X\n0,1,2,3,4\n") ==
        "in.csv:1: column x appears twice in the header (fields 2 and 5)");
}

TEST_CASE("errors: rows", "[csv]") {
  const std::string header = "section,index,x,y,z\n";
  CHECK(error_of(header + rows("0", 1) + "1,0,1,2\n") ==
        "in.csv:6: expected 5 comma-separated fields (as in the header on line 1), found 4");
  CHECK(error_of(header + rows("0", 1) + "1,0,1,2,3,\n") ==
        "in.csv:6: expected 5 comma-separated fields (as in the header on line 1), found 6");
  CHECK(error_of(header + "0,0,1.5abc,2,3\n") == "in.csv:2: column x: '1.5abc' is not a number");
  CHECK(error_of(header + rows("0", 1) + "0,4,1,,3\n") == "in.csv:6: column y: '' is not a number");
  CHECK(error_of(header + "0,0,1,2,1,5\n").find("expected 5") != std::string::npos);
  CHECK(error_of(header + "0,0,1,2,0x10\n") == "in.csv:2: column z: '0x10' is not a number");
  CHECK(error_of(header + "0,0,1,nan,3\n") ==
        "in.csv:2: column y: 'nan' is not a finite value (NaN and infinity are not allowed)");
  CHECK_THAT(error_of(header + "0,0,-inf,2,3\n"),
             StartsWith("in.csv:2: column x: '-inf' is not a finite value"));
  CHECK(error_of(header + "0,0,1,2,1e999\n") ==
        "in.csv:2: column z: '1e999' is out of the range of a double");
  CHECK(error_of(header + "0,1.0,1,2,3\n") == "in.csv:2: column index: '1.0' is not an integer");
  CHECK(error_of(header + "0,,1,2,3\n") == "in.csv:2: column index: '' is not an integer");
  CHECK(error_of(header + " ,0,1,2,3\n") == "in.csv:2: column section: empty value");
  // Plain files.
  CHECK(error_of("1 2 3\n4 5\n") == "in.csv:2: expected 3 fields (x, y, z), found 2");
  CHECK(error_of("1 2 3\n4 5 6,\n") == "in.csv:2: expected 3 fields (x, y, z), found 4");
  CHECK(error_of("x,y,z\n1 2 3\n4 five 6\n") == "in.csv:3: column y: 'five' is not a number");
  CHECK(error_of("1 2 3\n4,,6\n") == "in.csv:2: column y: '' is not a number");
  CHECK(error_of("1 2 inf\n") ==
        "in.csv:1: column z: 'inf' is not a finite value (NaN and infinity are not allowed)");
  // A leading '+' is accepted (one only).
  CHECK(error_of("1 2 ++3\n") == "in.csv:1: column z: '++3' is not a number");
  const SectionSet plus = parse("+0.5 0 1\n1.5 +2 1\n2.5 4 1\n3.5 6 +1\n\n"
                                "0.5 0 2\n1.5 2 2\n2.5 4 2\n3.5 6 2\n");
  CHECK(plus.sections[0].points == expected_points(1));
}

TEST_CASE("errors: sections", "[csv]") {
  const std::string header = "section,index,x,y,z\n";
  SECTION("duplicate index names both lines") {
    CHECK(error_of(header + rows("0", 1) + rows("1", 2, 3) + "1,1,9,9,9\n") ==
          "in.csv:9: duplicate index 1 in section 1 (also on line 7)");
  }
  SECTION("fewer than 4 points, counted after dropping repeated points") {
    CHECK(error_of(header + rows("0", 1) + rows("1", 2, 3)) ==
          "in.csv:6: section 1 has 3 distinct point(s) after dropping repeated points; need at "
          "least 4");
    CHECK(error_of(header + rows("0", 1) + rows("1", 2, 3) + "1,3,0.5,0,2\n") ==
          "in.csv:6: section 1 has 3 distinct point(s) after dropping repeated points; need at "
          "least 4");
    CHECK(error_of("1 2 3\n4 5 6\n7 8 9\n10 11 12\n\n1 1 1\n1 1 1\n") ==
          "in.csv:6: section 2 has 1 distinct point(s) after dropping repeated points; need at "
          "least 4");
  }
  SECTION("only one section") {
    CHECK(error_of(header + rows("7", 1, 10)) == "in.csv: need at least 2 sections, found 1");
    CHECK(error_of("1 2 3\n4 5 6\n7 8 9\n10 11 12\n") ==
          "in.csv: need at least 2 sections, found 1");
  }
  SECTION("identical sections") {
    CHECK(error_of(header + rows("0", 1) + rows("1", 2) + rows("2", 1)) ==
          "in.csv: sections 0 (line 2) and 2 (line 10) are identical");
    // Identical after dropping the repeated closing point of one of them.
    CHECK(error_of(header + rows("a", 1) + rows("b", 1) + "b,4,0.5,0,1\n") ==
          "in.csv: sections a (line 2) and b (line 6) are identical");
  }
  SECTION("two ids with the same numeric value") {
    CHECK(error_of(header + rows("1", 1) + rows("1.0", 2)) ==
          "in.csv: section ids '1' (line 2) and '1.0' (line 6) have the same numeric value");
  }
}

TEST_CASE("warnings: repeated points and the repeated closing point are dropped", "[csv]") {
  const std::string text = "section,x,y,z\n"
                           "0,0.5,0,1\n0,0.5,0,1\n0,1.5,2,1\n0,2.5,4,1\n0,2.5,4,1\n0,2.5,4,1\n"
                           "0,3.5,6,1\n0,0.5,0,1\n" +
                           std::string("1,0.5,0,2\n1,1.5,2,2\n1,2.5,4,2\n1,3.5,6,2\n");
  const SectionSet s = parse(text, "w.csv");
  REQUIRE(s.sections.size() == 2);
  CHECK(s.sections[0].points == expected_points(1));
  CHECK(s.sections[0].lines == std::vector<long>{2, 4, 5, 8});
  CHECK(s.sections[1].points == expected_points(2));
  REQUIRE(s.warnings.size() == 4);
  CHECK(s.warnings[0] ==
        "w.csv:3: point identical to the previous point of section 0 (line 2); dropped");
  CHECK(s.warnings[1] ==
        "w.csv:6: point identical to the previous point of section 0 (line 5); dropped");
  CHECK(s.warnings[2] ==
        "w.csv:7: point identical to the previous point of section 0 (line 5); dropped");
  CHECK(s.warnings[3] == "w.csv:9: last point of section 0 repeats its first point (line 2); "
                         "dropped (sections are closed implicitly)");
  // Repetition is judged in index order, not file order.
  const std::string indexed = "section,index,x,y,z\n"
                              "0,1,1.5,2,1\n0,0,0.5,0,1\n0,4,0.5,0,1\n0,2,2.5,4,1\n0,3,3.5,6,1\n" +
                              rows("1", 2);
  const SectionSet t = parse(indexed, "w.csv");
  CHECK(t.sections[0].points == expected_points(1));
  REQUIRE(t.warnings.size() == 1);
  CHECK(t.warnings[0] == "w.csv:4: last point of section 0 repeats its first point (line 3); "
                         "dropped (sections are closed implicitly)");
}

TEST_CASE("sections are ordered numerically when every id is a number, else lexicographically",
          "[csv]") {
  const std::string header = "section,index,x,y,z\n";
  const SectionSet n2 = parse(header + rows("10", 10) + rows("9", 9) + rows("-1", -1) +
                              rows("2.5", 2.5) + rows("+3", 3) + rows("1e2", 100));
  CHECK(ids(n2) == std::vector<std::string>{"-1", "2.5", "+3", "9", "10", "1e2"});
  CHECK(n2.sections[0].points == expected_points(-1));
  CHECK(n2.sections[5].points == expected_points(100));
  const SectionSet lex =
      parse(header + rows("b9", 1) + rows("10", 2) + rows("b10", 3) + rows("9", 4) + rows("a", 5));
  CHECK(ids(lex) == std::vector<std::string>{"10", "9", "a", "b10", "b9"});
  CHECK(lex.sections[0].points == expected_points(2));
  CHECK(lex.sections[4].points == expected_points(1));
}

TEST_CASE("write_sections_csv then read_sections is bit-exact", "[csv]") {
  test::TempDir dir("csv");
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-300, 300);
  std::vector<Section> sections(3);
  for (size_t k = 0; k < sections.size(); ++k) {
    Section& s = sections[k];
    s.id = std::to_string(k);
    s.points.resize(50, 3);
    for (Eigen::Index i = 0; i < s.points.rows(); ++i)
      for (int c = 0; c < 3; ++c)
        s.points(i, c) = std::ldexp(unit(rng), expo(rng) / 10); // wide range of magnitudes
  }
  // Values whose shortest decimal forms need all 17 digits, and extremes.
  sections[0].points.row(0) << 0.1 + 0.2, 1.0 / 3.0, -2.0 / 3.0;
  sections[0].points.row(1) << 1.7976931348623157e308, -2.2250738585072014e-308, 5e-300;
  sections[0].points.row(2) << 0.0, -0.0, 123456789.123456789;
  const std::string path = dir.file("out.csv");
  write_sections_csv(path, sections);
  const SectionSet back = read_sections(path);
  REQUIRE(back.sections.size() == sections.size());
  CHECK(back.warnings.empty());
  for (size_t k = 0; k < sections.size(); ++k) {
    CHECK(back.sections[k].id == sections[k].id);
    REQUIRE(back.sections[k].points.rows() == sections[k].points.rows());
    // Bit-exact: compare the representations, so that -0.0 vs 0.0 would also be caught.
    CHECK(std::memcmp(back.sections[k].points.data(), sections[k].points.data(),
                      sizeof(double) * static_cast<size_t>(sections[k].points.size())) == 0);
  }
  std::ifstream in(path);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  CHECK(first == "section,index,x,y,z");
  CHECK(second == "0,0,0.30000000000000004,0.33333333333333331,-0.66666666666666663");

  SECTION("invalid input throws and leaves no file") {
    std::vector<Section> bad = sections;
    bad[1].id = "a,b";
    const std::string p2 = dir.file("bad.csv");
    CHECK_THROWS_AS(write_sections_csv(p2, bad), std::invalid_argument);
    bad[1].id = "#1";
    CHECK_THROWS_AS(write_sections_csv(p2, bad), std::invalid_argument);
    bad[1].id = "1";
    bad[1].points(0, 0) = std::nan("");
    CHECK_THROWS_AS(write_sections_csv(p2, bad), std::invalid_argument);
    CHECK_THROWS_AS(write_sections_csv(dir.file("no-such-dir/x.csv"), sections),
                    std::runtime_error);
    CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                        std::filesystem::directory_iterator()) == 1); // only out.csv
  }
}
