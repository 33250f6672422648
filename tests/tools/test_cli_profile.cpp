// interlin profile: cascade parameters (seed 004 §4.1–4.2) -> section CSV, the span stack lofted
// end to end, and one clear error line with no output file for bad input.
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/splines/cascade_stack.h"

#include "support/cli_runner.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>

namespace fs = std::filesystem;
using namespace interlin;
using namespace interlin::test;

namespace {

const std::string kNozzle = INTERLIN_DATA_DIR "/profiles/turbine_nozzle.json";
const std::string kSpan = INTERLIN_DATA_DIR "/profiles/turbine_blade_span.json";
const std::string kSpanToml = INTERLIN_DATA_DIR "/profiles/turbine_blade_span.toml";

// The shipped nozzle file's parameters (data/profiles/turbine_nozzle.json).
CascadeParameters nozzle() {
  return {0.75, 1.0, 40, 90, 13, 30, 6, 0.06, 0.01, 13, 0.35, 0.15, 0.17};
}

std::string parameters_json(const std::string& replace_key = "", const std::string& value = "") {
  const std::pair<const char*, const char*> kv[] = {{"relative_pitch", "0.75"},
                                                    {"axial_width", "1.0"},
                                                    {"stagger_deg", "40"},
                                                    {"inlet_angle_deg", "90"},
                                                    {"outlet_angle_deg", "13"},
                                                    {"le_wedge_deg", "30"},
                                                    {"te_wedge_deg", "6"},
                                                    {"le_radius", "0.06"},
                                                    {"te_radius", "0.01"},
                                                    {"te_bend_deg", "13"},
                                                    {"max_thickness_position", "0.35"},
                                                    {"max_thickness", "0.15"},
                                                    {"throat", "0.17"}};
  std::string s = "{\n  \"parameters\": {\n";
  bool first = true;
  for (const auto& [k, v] : kv) {
    if (replace_key == k && value.empty())
      continue; // drop the key
    s += std::string(first ? "" : ",\n") + "    \"" + k + "\": " + (replace_key == k ? value : v);
    first = false;
  }
  return s + "\n  }";
}

} // namespace

TEST_CASE("interlin profile: one profile, bit-exact to the library, with curvature data",
          "[cli][profile]") {
  const TempDir d("profile");
  const Run h = run("profile --help");
  CHECK(h.status == 0);
  CHECK_THAT(h.out, Catch::Contains("Usage: interlin profile"));
  const Run r =
      run("profile " + kNozzle + " -o " + (d / "n.csv") + " --curvature " + (d / "k.csv"));
  INFO(r.err);
  REQUIRE(r.status == 0);
  CHECK_THAT(r.out, Catch::Contains("1 x 152 points") && Catch::Contains("G3"));
  // One section (read_sections wants >= 2, a loft input): parse the rows section,index,x,y,z.
  // Its points are the library's, bit for bit (%.17g round trip).
  const CascadeProfile P = cascade_profile(nozzle());
  std::istringstream csv(slurp(d / "n.csv"));
  std::string line;
  std::getline(csv, line);
  CHECK(line == "section,index,x,y,z");
  Eigen::Index rows = 0;
  while (std::getline(csv, line)) {
    double v[5];
    std::istringstream f(line);
    std::string field;
    for (double& x : v) {
      std::getline(f, field, ',');
      x = std::strtod(field.c_str(), nullptr);
    }
    REQUIRE(rows < P.points.rows());
    CHECK(v[0] == 0);
    CHECK(v[1] == rows);
    CHECK(v[2] == P.points(rows, 0));
    CHECK(v[3] == P.points(rows, 1));
    CHECK(v[4] == 0);
    ++rows;
  }
  CHECK(rows == P.points.rows());
  // Curvature plot: header + 2 sides x 201 samples.
  const std::string k = slurp(d / "k.csv");
  CHECK(k.rfind("section,side,sbar,s,x,y,phi,k,dk\n", 0) == 0);
  CHECK(std::count(k.begin(), k.end(), '\n') == 1 + 2 * 201);
  // G2 on request.
  const Run g2 = run("profile " + kNozzle + " -o " + (d / "g2.csv") + " --joint g2 -q");
  CHECK(g2.status == 0);
  CHECK_THAT(g2.out, Catch::Contains("G2"));
  CHECK(g2.err.empty());
}

TEST_CASE("interlin profile: a span law stacks profiles that loft exactly", "[cli][profile]") {
  const TempDir d("profile-span");
  const Run r = run("profile " + kSpan + " -o " + (d / "blade.csv") + " -q");
  INFO(r.err);
  REQUIRE(r.status == 0);
  const SectionSet set = read_sections(d / "blade.csv");
  REQUIRE(set.sections.size() == 5);
  const double radius[] = {200, 225, 250, 275, 300};
  for (size_t k = 0; k < 5; ++k) {
    CHECK(set.sections[k].points.rows() == 152);
    CHECK((set.sections[k].points.col(2).array() == radius[k]).all());
  }
  // The library's stack from the same span law, point for point.
  std::vector<SpanStation> st;
  const double B[] = {36, 38, 40, 42, 44}, stagger[] = {38, 39, 40, 41, 42},
               cm[] = {0.17, 0.16, 0.15, 0.13, 0.11},
               tb[] = {0.6981, 0.7441, 0.7854, 0.8228, 0.8568};
  for (int k = 0; k < 5; ++k) {
    CascadeParameters p{tb[k], B[k], stagger[k], 90, 13, 30, 6, 2.4, 0.4, 13, 0.35, cm[k], 0};
    st.push_back({radius[k], p});
  }
  const std::vector<Eigen::MatrixXd> S = stack_cascade_profiles(st, StackAlign::centroid);
  for (size_t k = 0; k < 5; ++k)
    CHECK(set.sections[k].points == S[k]);
  // End to end: the loft reproduces every profile point (its own exactness measure).
  const LoftResult loft = loft_sections(set.sections, LoftOptions{});
  CHECK(loft.max_deviation <= 1e-12 * loft.bbox_diagonal);
  // ... and the CLI lofts the file.
  const Run l = run("loft " + (d / "blade.csv") + " -o " + (d / "blade.json") + " -q");
  INFO(l.err);
  CHECK(l.status == 0);
  CHECK(fs::exists(d / "blade.json"));
}

TEST_CASE("interlin profile: bad input gives one error line, exit 1/2 and no output file",
          "[cli][profile]") {
  const TempDir d("profile-bad");
  const auto write = [&](const std::string& name, const std::string& text) {
    write_file(d / name, text);
    return d / name;
  };
  struct Case {
    std::string json, expect;
  };
  const Case cases[] = {
      {parameters_json() + "\n}", ""}, // valid: checked separately below
      {parameters_json() + ",\n  \"joint\": \"g3\",\n}",
       "t.json:18: JSON syntax error: syntax error while parsing object key"},
      {parameters_json("le_radius", "-0.06") + "\n}", "leading-edge radius must be > 0"},
      {parameters_json("throat") + "\n}", "missing parameter \"throat\""},
      {parameters_json("axial_width", "\"wide\"") + "\n}", "\"axial_width\" must be a number"},
      {parameters_json() + ",\n  \"stager\": 3\n}", "unknown key \"stager\""},
      {parameters_json("outlet_angle_deg", "95") + "\n}", "outlet angle must lie in (0, 90)"},
      {parameters_json("inlet_angle_deg", "175") + "\n}", "inconsistent angles"},
      {parameters_json() + ",\n  \"span\": {\"radius\": [1, 2], \"stagger_deg\": [40]}\n}",
       "must be an array of 2 numbers"},
      {parameters_json() + ",\n  \"span\": {\"radius\": [2, 1]}\n}", "radii must increase"},
      {parameters_json() + ",\n  \"edge_intervals\": 7\n}", "edge_intervals must be even"}};
  for (const Case& c : cases) {
    const std::string in = write("t.json", c.json);
    const Run r = run("profile " + in + " -o " + (d / "out.csv") + " -q");
    INFO(c.json << "\nstderr: " << r.err);
    if (c.expect.empty()) {
      CHECK(r.status == 0);
      fs::remove(d / "out.csv");
      continue;
    }
    CHECK(r.status == 1);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_THAT(r.err, Catch::StartsWith("interlin: ") && Catch::Contains(c.expect));
    CHECK(files_in(d) == 1); // only the input: no output, no temporary file
  }
  // Usage errors: exit 2, nothing written.
  const std::string in = write("t.json", parameters_json() + "\n}");
  for (const std::string& args :
       {"profile " + in + " -o " + (d / "out.stl"), "profile " + in, std::string("profile"),
        "profile " + in + " -o " + (d / "o.csv") + " --joint g4",
        "profile " + in + " -o " + (d / "o.csv") + " --points 10,5",
        "profile " + in + " -o " + (d / "o.csv") + " --frobnicate"}) {
    const Run r = run(args);
    INFO(args << "\nstderr: " << r.err);
    CHECK(r.status == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(files_in(d) == 1);
  }
  // Missing file and missing output directory: exit 1.
  Run m = run("profile " + (d / "none.json") + " -o " + (d / "o.csv"));
  CHECK(m.status == 1);
  CHECK_THAT(m.err, Catch::Contains("none.json: cannot open"));
  m = run("profile " + in + " -o " + (d / "no/dir/o.csv"));
  CHECK(m.status == 1);
  CHECK_THAT(m.err, Catch::Contains("does not exist"));
  CHECK(files_in(d) == 1);
}

TEST_CASE("interlin profile: a TOML parameter file is the same job as its JSON twin",
          "[cli][profile][toml]") {
  const TempDir d("profile-toml");
  const Run j = run("profile " + kSpan + " -o " + (d / "j.csv") + " -q");
  const Run t = run("profile " + kSpanToml + " -o " + (d / "t.csv") + " -q");
  INFO(j.err << t.err);
  REQUIRE(j.status == 0);
  REQUIRE(t.status == 0);
  // The shipped .toml and .json say the same thing, so the CSVs agree byte for byte.
  CHECK(slurp(d / "t.csv") == slurp(d / "j.csv"));
  // Integer-valued TOML floats and integers are both numbers; a one-profile file without span.
  write_file(d / "one.toml", "[parameters]\nrelative_pitch = 0.75\naxial_width = 1\n"
                             "stagger_deg = 40.0\ninlet_angle_deg = 90\noutlet_angle_deg = 13\n"
                             "le_wedge_deg = 30\nte_wedge_deg = 6\nle_radius = 0.06\n"
                             "te_radius = 0.01\nte_bend_deg = 13\n"
                             "max_thickness_position = 0.35\nmax_thickness = 0.15\n"
                             "throat = 0.17\n");
  const Run one = run("profile " + (d / "one.toml") + " -o " + (d / "one.csv") + " -q");
  const Run ref = run("profile " + kNozzle + " -o " + (d / "ref.csv") + " -q");
  REQUIRE(one.status == 0);
  REQUIRE(ref.status == 0);
  CHECK(slurp(d / "one.csv") == slurp(d / "ref.csv")); // the nozzle file's 13 parameters
}

TEST_CASE("interlin profile: bad TOML gives one error line with the line of the value",
          "[cli][profile][toml]") {
  const TempDir d("profile-toml-bad");
  const std::string good = slurp(kSpanToml);
  REQUIRE(good.find("le_radius = 2.4\n") != std::string::npos);
  const auto line_of = [&](const std::string& what) {
    return std::to_string(1 + std::count(good.begin(), good.begin() + good.find(what), '\n'));
  };
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    return s.replace(s.find(from), from.size(), to);
  };
  struct Case {
    std::string toml, expect;
  };
  const Case cases[] = {
      {replaced("le_radius = 2.4", "le_radius = \"big\""),
       "t.toml:" + line_of("le_radius = 2.4") + ": parameter \"le_radius\" must be a number"},
      {replaced("le_radius = 2.4", "le_radius = nan"),
       "t.toml:" + line_of("le_radius = 2.4") + ": parameter \"le_radius\" must be finite"},
      {replaced("le_radius = 2.4", "le_radius = 1979-05-27"),
       "t.toml:" + line_of("le_radius = 2.4") + ": parameter \"le_radius\" must be a number"},
      {replaced("te_radius = 0.4", "te_radius = 0.4\nstager = 3"),
       "t.toml:" + line_of("te_bend_deg") + ": unknown parameter \"stager\""},
      {replaced("throat = 0", "throat = 0\nthroat = 1"), // the line of the repeated key
       "t.toml:" + std::to_string(std::stoi(line_of("throat = 0")) + 1) + ": TOML syntax error:"},
      {replaced("axial_width    = [36, 38, 40, 42, 44]", "axial_width = [36, 38]"),
       "t.toml:" + line_of("axial_width    =") +
           ": \"span\".\"axial_width\" must be an array of 5"},
      {replaced("joint = \"g3\"", "joint = \"g5\""),
       "t.toml:" + line_of("joint =") + ": \"joint\" must be \"g2\" or \"g3\""},
      {replaced("le_radius = 2.4", "le_radius = -2.4"), "leading-edge radius must be > 0"}};
  for (size_t i = 0; i < std::size(cases); ++i) {
    const Case& c = cases[i];
    write_file(d / "t.toml", c.toml);
    const Run r = run("profile " + (d / "t.toml") + " -o " + (d / "out.csv") + " -q");
    INFO("case " << i << "\nstderr: " << r.err);
    CHECK(r.status == 1);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK_THAT(r.err, Catch::StartsWith("interlin: ") && Catch::Contains(c.expect));
    CHECK(files_in(d) == 1); // only the input: no output, no temporary file
  }
  // A parameter file that is neither .json nor .toml is a usage error (exit 2).
  write_file(d / "t.txt", good);
  const Run u = run("profile " + (d / "t.txt") + " -o " + (d / "out.csv"));
  CHECK(u.status == 2);
  CHECK_THAT(u.err, Catch::Contains("expected a .json or .toml file"));
}
