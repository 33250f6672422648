// Surface JSON: bit-exact round trip, meta key/values, and an InputError naming the problem for
// every kind of bad input. Values are compared bit for bit: the writer prints the shortest
// decimal that reads back to the same double, the reader parses correctly rounded.

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/surface_json.h"

#include "support/test_support.h"
#include "support/test_surfaces.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

using namespace interlin;
using Catch::Matchers::Contains;
using Catch::Matchers::StartsWith;
namespace fs = std::filesystem;

namespace {

// Random clamped surface; coordinates over many magnitudes plus awkward values.
BSplineSurface random_json_surface(int pu, int pv, Eigen::Index nu, Eigen::Index nv,
                                   unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> exponent(-15, 15);
  BSplineSurface s;
  s.degree_u = pu;
  s.degree_v = pv;
  s.num_u = nu;
  s.num_v = nv;
  s.knots_u = test::random_clamped_knots(rng, pu, nu, 0.1, 0.7);
  s.knots_v = test::random_clamped_knots(rng, pv, nv, -3.0, 1e10);
  s.ctrl.resize(nu * nv, 3);
  for (Eigen::Index r = 0; r < s.ctrl.rows(); ++r)
    for (int c = 0; c < 3; ++c)
      s.ctrl(r, c) = (2.0 * unit(rng) - 1.0) * std::pow(10.0, exponent(rng));
  s.ctrl(0, 0) = -0.0;
  s.ctrl(1, 1) = 4.9406564584124654e-324;
  s.ctrl(2, 2) = -1.7976931348623157e308;
  return s;
}

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

// A valid degree (1,1) surface with 2 x 2 control points; tests replace one field.
std::string minimal(const std::map<std::string, std::string>& replace = {}) {
  std::map<std::string, std::string> f = {
      {"format", "\"interlin-bspline-surface\""},
      {"version", "1"},
      {"degree", "[1, 1]"},
      {"closed_u", "false"},
      {"size", "[2, 2]"},
      {"knots_u", "[0, 0, 1, 1]"},
      {"knots_v", "[0, 0, 2, 2]"},
      {"control_points", "[[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 1]]"},
  };
  for (const auto& [k, v] : replace)
    f[k] = v;
  std::string text = "{\n";
  bool first = true;
  for (const auto& [k, v] : f) {
    if (v == "(absent)")
      continue;
    text += std::string(first ? "" : ",\n") + "  \"" + k + "\": " + v;
    first = false;
  }
  return text + "\n}\n";
}

std::string json_error(const std::string& path, const std::string& text) {
  {
    std::ofstream out(path, std::ios::binary);
    out << text;
  }
  try {
    read_surface_json(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

} // namespace

TEST_CASE("Surface JSON round trip is bit-exact and keeps meta", "[json]") {
  test::TempDir tmp("json-roundtrip");
  const std::string path = tmp.file("surface.json");
  const BSplineSurface s = random_json_surface(3, 2, 8, 5, 4242u);
  const std::map<std::string, std::string> meta = {
      {"source", "blade \"A\"\\sections.csv"},
      {"units", "mm"},
      {"deviation", "1.25e-07"},
      {"note", "line one\nline two\ttab, unicode \xc2\xb5m"},
  };
  write_surface_json(path, s, meta);
  std::map<std::string, std::string> meta_back;
  const BSplineSurface r = read_surface_json(path, &meta_back);
  CHECK(r.degree_u == 3);
  CHECK(r.degree_v == 2);
  CHECK(r.num_u == 8);
  CHECK(r.num_v == 5);
  CHECK(r.closed_u == s.closed_u);
  CHECK(same_bits(r.knots_u, s.knots_u));
  CHECK(same_bits(r.knots_v, s.knots_v));
  CHECK(same_bits(r.ctrl, s.ctrl));
  CHECK(meta_back == meta);

  // closed_u survives; no "meta" key when meta is empty; reading without meta works.
  BSplineSurface closed = s;
  closed.closed_u = true;
  write_surface_json(path, closed);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK_THAT(text, !Contains("\"meta\""));
  CHECK_THAT(text, Contains("\"format\": \"interlin-bspline-surface\""));
  CHECK_THAT(text, Contains("\"closed_u\": true"));
  CHECK(read_surface_json(path).closed_u);
  CHECK(read_surface_json(path, &meta_back).closed_u);
  CHECK(meta_back.empty());
}

TEST_CASE("Surface JSON reads the documented layout and keeps non-string meta as JSON text",
          "[json]") {
  test::TempDir tmp("json-layout");
  const std::string path = tmp.file("m.json");
  const std::string text =
      minimal({{"meta", "{\"a\": \"x\", \"tol\": 0.5, \"ok\": true}"}, {"unknown_key", "[1, 2]"}});
  {
    std::ofstream out(path);
    out << text;
  }
  std::map<std::string, std::string> meta;
  const BSplineSurface s = read_surface_json(path, &meta);
  CHECK(s.knots_v == (Eigen::VectorXd(4) << 0, 0, 2, 2).finished());
  Eigen::MatrixXd ctrl(4, 3);
  ctrl << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1; // row i + num_u * j as listed
  CHECK(s.ctrl == ctrl);
  CHECK(meta == std::map<std::string, std::string>{{"a", "x"}, {"tol", "0.5"}, {"ok", "true"}});
}

TEST_CASE("Surface JSON errors name the problem", "[json]") {
  test::TempDir tmp("json-errors");
  const std::string path = tmp.file("bad.json");
  auto err = [&](const std::map<std::string, std::string>& replace) {
    return json_error(path, minimal(replace));
  };
  const std::string prefix = path + ": ";

  CHECK(json_error(path, minimal()) == "(no error)"); // the base case is valid

  CHECK_THAT(err({{"knots_v", "(absent)"}}),
             StartsWith(prefix) && Contains("missing field") && Contains("knots_v"));
  CHECK_THAT(err({{"control_points", "(absent)"}}), Contains("\"control_points\""));
  CHECK_THAT(err({{"format", "\"other\""}}), StartsWith(prefix) && Contains("\"format\""));
  CHECK_THAT(err({{"version", "2"}}), Contains("\"version\""));
  CHECK_THAT(err({{"version", "\"1\""}}), Contains("\"version\" must be an integer"));
  CHECK_THAT(err({{"degree", "[0, 1]"}}), Contains("\"degree\"[0]"));
  CHECK_THAT(err({{"degree", "[1]"}}), Contains("\"degree\" must have 2 entries"));
  CHECK_THAT(err({{"degree", "[1.5, 1]"}}), Contains("\"degree\"[0] must be an integer"));
  CHECK_THAT(err({{"closed_u", "1"}}), Contains("\"closed_u\""));
  CHECK_THAT(err({{"size", "[1, 2]"}}), Contains("\"size\"[0]"));
  // Wrong sizes.
  CHECK_THAT(err({{"knots_u", "[0, 0, 1, 1, 1]"}}),
             StartsWith(prefix) && Contains("\"knots_u\" must have 4 entries, has 5"));
  CHECK_THAT(err({{"control_points", "[[0, 0, 0], [1, 0, 0], [0, 1, 0]]"}}),
             Contains("\"control_points\" must have 4 entries, has 3"));
  CHECK_THAT(err({{"control_points", "[[0, 0, 0], [1, 0], [0, 1, 0], [1, 1, 1]]"}}),
             Contains("\"control_points\"[1] must have 3 entries, has 2"));
  CHECK_THAT(err({{"control_points", "[[0, 0, 0], [1, 0, 0], [0, \"1\", 0], [1, 1, 1]]"}}),
             Contains("\"control_points\"[2][1] must be a number"));
  // Non-finite: JSON has no NaN/Infinity literals; 1e999 overflows the double range.
  // minimal() writes the keys in alphabetical order: "{" is line 1, then closed_u, control_points
  // (line 3), degree, format, knots_u, knots_v (line 7).
  CHECK_THAT(err({{"control_points", "[[0, 0, 0], [1, 0, 0], [0, 1, 1e999], [1, 1, 1]]"}}),
             StartsWith(path + ":3: ") && Contains("1e999") && Contains("not a finite"));
  CHECK_THAT(err({{"knots_v", "[0, 0, -1e999, 2]"}}),
             StartsWith(path + ":7: ") && Contains("-1e999"));
  CHECK_THAT(err({{"knots_v", "[0, 0, NaN, 2]"}}), StartsWith(path + ":7: JSON syntax error"));
  // Non-monotone knots and an empty domain.
  CHECK_THAT(err({{"knots_u", "[0, 1, 0.5, 1]"}}),
             Contains("\"knots_u\" is not non-decreasing: entry 2 (0.5) < entry 1 (1)"));
  CHECK_THAT(err({{"knots_u", "[0, 1, 1, 1]"}}), Contains("\"knots_u\" has an empty parameter"));
  CHECK_THAT(err({{"meta", "[1]"}}), Contains("\"meta\" must be an object"));
  CHECK_THAT(json_error(path, "[1, 2]"), Contains("not a JSON object"));

  // Syntax errors carry the line: the stray token is on line 3.
  CHECK_THAT(json_error(path, "{\n  \"format\": 1,\n  oops\n}\n"),
             StartsWith(path + ":3: JSON syntax error"));
  CHECK_THAT(json_error(path, ""), StartsWith(path + ":1: JSON syntax error"));
  try {
    read_surface_json(tmp.file("none.json"));
    FAIL("no error for a missing file");
  } catch (const InputError& e) {
    CHECK_THAT(std::string(e.what()), StartsWith(tmp.file("none.json") + ": cannot open"));
  }
}

TEST_CASE("write_surface_json failures leave no file behind", "[json]") {
  test::TempDir tmp("json-fail");
  const BSplineSurface s = random_json_surface(2, 2, 4, 4, 3u);
  CHECK_THROWS_AS(write_surface_json(tmp.file("missing/s.json"), s), std::runtime_error);
  fs::create_directories(tmp.path() / "taken.json");
  CHECK_THROWS_AS(write_surface_json(tmp.file("taken.json"), s), std::runtime_error);
  BSplineSurface broken = s;
  broken.knots_u(0) = 5.0; // decreasing knots: a programming error
  CHECK_THROWS_AS(write_surface_json(tmp.file("broken.json"), broken), std::invalid_argument);
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator(tmp.path()))
    left.push_back(entry.path().filename().string());
  CHECK(left == std::vector<std::string>{"taken.json"});
}
