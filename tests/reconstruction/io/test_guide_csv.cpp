// Guide files: accepted forms and one FILE:LINE error for each defect.
#include "interlin/reconstruction/io/guide_csv.h"
#include "interlin/reconstruction/io/input_error.h"

#include <catch2/catch.hpp>
#include <sstream>

using namespace interlin;

namespace {

GuideSet parse(const std::string& text) {
  std::istringstream in(text);
  return parse_guides(in, "g.csv");
}

void expect_error(const std::string& text, const std::string& what) {
  INFO(text);
  CHECK_THROWS_AS(parse(text), InputError);
  CHECK_THROWS_WITH(parse(text), Catch::StartsWith("g.csv") && Catch::Contains(what));
}

} // namespace

TEST_CASE("Guide files: header, index order, comments, BOM and CRLF", "[guide_csv]") {
  const GuideSet g = parse("\xEF\xBB\xBF# edges\r\nx, Y ,z,guide,index,note\r\n"
                           "1,2,3,LE,1,a\r\n0,0,0,LE,0,b\r\n\r\n5,5,5,TE,0,\r\n6,6,+6.5,TE,1,\r\n");
  REQUIRE(g.guides.size() == 2);
  CHECK(g.guides[0].id == "LE");
  CHECK(g.guides[0].points(0, 0) == 0.0); // sorted by index
  CHECK(g.guides[0].lines == std::vector<long>{4, 3});
  CHECK(g.guides[1].points(1, 2) == 6.5);
  // Without an index column: file order, rows of a guide contiguous.
  const GuideSet h = parse("guide,x,y,z\nA,0,0,0\nA,1,0,0\nB,0,1,0\nB,1,1,0\n");
  CHECK(h.guides[1].points(1, 0) == 1.0);
}

TEST_CASE("Guide files: every defect is one error naming the line", "[guide_csv]") {
  expect_error("", "no data rows");
  expect_error("guide,x,y\nA,1,2\n", "lacks the required column(s) z");
  expect_error("guide,x,y,z,x\n", "g.csv:1: column x appears twice");
  expect_error("guide,x,y,z\nA,1,2\n", "g.csv:2: expected 4 comma-separated fields");
  expect_error("guide,x,y,z\nA,1,2abc,3\n", "g.csv:2: column y: '2abc' is not a number");
  expect_error("guide,x,y,z\nA,1,nan,3\n", "g.csv:2: column y: 'nan' is not a finite value");
  expect_error("guide,x,y,z\nA,1,1e999,3\n", "out of the range of a double");
  expect_error("guide,x,y,z\n,1,2,3\n", "g.csv:2: column guide: empty value");
  expect_error("guide,index,x,y,z\nA,1.5,1,2,3\n", "column index: '1.5' is not an integer");
  expect_error("guide,index,x,y,z\nA,0,1,2,3\nA,0,2,2,3\n", "g.csv:3: duplicate index 0");
  expect_error("guide,x,y,z\nA,1,2,3\nB,1,2,3\nB,2,2,3\n", "g.csv:2: guide A has 1 point");
  expect_error("guide,x,y,z\nA,1,2,3\nA,1,2,3\n", "g.csv:3: point repeats the previous point");
  expect_error("guide,x,y,z\nA,1,2,3\nB,1,2,3\nA,2,2,3\n", "g.csv:4: rows of guide A resume");
  expect_error("guide,x,y,z\n", "no data rows after the header");
  CHECK_THROWS_WITH(read_guides("/nonexistent/g.csv"), Catch::Contains("cannot open"));
}
