// interlin profile: the 13 cascade parameters (seed 004 §4.1–4.2) -> blade profile(s) as a
// section CSV, one profile or a span stack that `interlin loft` accepts.
#include "cli_common.h"
#include "commands.h"
#include "toml_as_json.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/splines/cascade_stack.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>

namespace interlin::cli {

const char* const kProfileHelp =
    R"(interlin profile - axial-turbine cascade profile(s) from 13 parameters -> section CSV

Usage: interlin profile PARAMS.{json,toml} -o SECTIONS.csv [options]

Input: a JSON or TOML file with the book's 13 parameters (seed 004 §4.1; docs/formats.md, "Cascade
profile parameters"), optionally a "span" law: per-radius values of any parameter (axial
width ~ chord, stagger, thickness, ...), which stacks one profile per radius.

Output: a section CSV (section,index,x,y,z): one closed profile per section, in the plane
z = radius (z = 0 without a span law), numbered from the middle of the trailing edge towards
the suction side, all sections with the same point count, so `interlin loft` lofts the stack.

Options:
  -o, --output FILE          the section CSV (.csv), written whole or not at all
  --joint g2|g3              joint after the throat / max-thickness point: quadratic curvature
                             (G2, §4.1) or cubic (G3, §4.2, default); overrides the file
  --points SIDE,EDGE         intervals along each side and each edge arc (EDGE even);
                             default 60,16; overrides the file
  --stack centroid|le|te|none
                             stacking line of a span law: area centroid (default), leading-
                             or trailing-edge centre, or the cascade frame; overrides the file
  --curvature FILE           curvature-plot data (.csv): section,side,sbar,s,x,y,phi,k,dk
  -q, --quiet                no progress lines on stderr
  -h, --help                 this help

Examples:
  interlin profile data/profiles/turbine_nozzle.json -o profile.csv --curvature k.csv
  interlin profile data/profiles/turbine_blade_span.toml -o blade.csv
  interlin loft blade.csv -o blade.stl --cap
)";

namespace {

using json = nlohmann::json;

// JSON key -> field of CascadeParameters, in the book's order.
const std::vector<std::pair<const char*, double CascadeParameters::*>>& parameter_fields() {
  static const std::vector<std::pair<const char*, double CascadeParameters::*>> f = {
      {"relative_pitch", &CascadeParameters::relative_pitch},
      {"axial_width", &CascadeParameters::axial_width},
      {"stagger_deg", &CascadeParameters::stagger_deg},
      {"inlet_angle_deg", &CascadeParameters::inlet_angle_deg},
      {"outlet_angle_deg", &CascadeParameters::outlet_angle_deg},
      {"le_wedge_deg", &CascadeParameters::le_wedge_deg},
      {"te_wedge_deg", &CascadeParameters::te_wedge_deg},
      {"le_radius", &CascadeParameters::le_radius},
      {"te_radius", &CascadeParameters::te_radius},
      {"te_bend_deg", &CascadeParameters::te_bend_deg},
      {"max_thickness_position", &CascadeParameters::max_thickness_position},
      {"max_thickness", &CascadeParameters::max_thickness},
      {"throat", &CascadeParameters::throat}};
  return f;
}

double CascadeParameters::*field(const std::string& key) {
  for (const auto& [name, member] : parameter_fields())
    if (key == name)
      return member;
  return nullptr;
}

struct ProfileJob {
  std::vector<SpanStation> stations;
  CascadeOptions options;
  StackAlign align = StackAlign::centroid;
  bool has_span = false;
};

const std::map<std::string, StackAlign> kAligns = {{"centroid", StackAlign::centroid},
                                                   {"le", StackAlign::leading_edge},
                                                   {"te", StackAlign::trailing_edge},
                                                   {"none", StackAlign::none}};

long line_at(const std::string& text, size_t byte) {
  return 1 +
         static_cast<long>(std::count(
             text.begin(), text.begin() + static_cast<long>(std::min(byte, text.size())), '\n'));
}

// The parameter file as a JSON value and the line of each value, known for TOML only (a JSON
// error names the key path, at line 0).
struct ParamDoc {
  std::string path;
  json root;
  std::map<std::string, long> lines; // JSON pointer -> line

  [[noreturn]] void fail(const std::string& pointer, const std::string& what) const {
    const auto it = lines.find(pointer);
    throw_input_error(path, it == lines.end() ? 0 : it->second, what);
  }
  double number(const json& v, const std::string& pointer, const std::string& where) const {
    if (!v.is_number())
      fail(pointer, where + " must be a number");
    const double d = v.get<double>();
    if (!std::isfinite(d))
      fail(pointer, where + " must be finite");
    return d;
  }
  int integer(const json& v, const std::string& pointer, const std::string& where, int lo,
              int hi) const {
    if (!v.is_number_integer() || v.get<long long>() < lo || v.get<long long>() > hi)
      fail(pointer, where + " must be an integer in [" + std::to_string(lo) + ", " +
                        std::to_string(hi) + "]");
    return static_cast<int>(v.get<long long>());
  }
  std::string text(const json& v, const std::string& pointer, const std::string& where) const {
    if (!v.is_string())
      fail(pointer, where + " must be a string");
    return v.get<std::string>();
  }
};

ParamDoc read_json_document(const std::string& path) {
  const std::string content = read_input_file(path);
  ParamDoc doc{path, {}, {}};
  try {
    doc.root = json::parse(content);
  } catch (const json::parse_error& e) {
    // nlohmann's text: "[json.exception.parse_error.101] parse error at line L, column C: what".
    const std::string msg = e.what();
    const auto col = msg.find("column"), p = msg.find(": ", col == std::string::npos ? 0 : col);
    throw_input_error(path, line_at(content, e.byte > 0 ? e.byte - 1 : 0),
                      "JSON syntax error: " + (p == std::string::npos ? msg : msg.substr(p + 2)));
  }
  return doc;
}

// Reads and validates the parameter file, JSON or TOML by extension (docs/formats.md,
// "Cascade profile parameters").
ProfileJob read_profile_parameters(const std::string& path) {
  ParamDoc doc;
  if (lower_extension(path) == ".toml") {
    TomlAsJson t = read_toml_as_json(path);
    doc = {path, std::move(t.value), std::move(t.lines)};
  } else {
    doc = read_json_document(path);
  }
  if (!doc.root.is_object())
    doc.fail("", "the file must hold one JSON object");
  ProfileJob job;
  CascadeParameters base;
  for (const auto& [key, value] : doc.root.items()) {
    const std::string at = "/" + key;
    if (key == "format") {
      if (doc.text(value, at, "\"format\"") != "interlin-cascade-profile")
        doc.fail(at, "\"format\" must be \"interlin-cascade-profile\"");
    } else if (key == "version") {
      if (doc.integer(value, at, "\"version\"", 1, 1000) != 1)
        doc.fail(at, "\"version\" must be 1");
    } else if (key == "parameters") {
      if (!value.is_object())
        doc.fail(at, "\"parameters\" must be an object");
      for (const auto& [name, v] : value.items()) {
        double CascadeParameters::*f = field(name);
        if (!f)
          doc.fail(at + "/" + name, "unknown parameter \"" + name + "\" in \"parameters\"");
        base.*f = doc.number(v, at + "/" + name, "parameter \"" + name + "\"");
      }
      for (const auto& [name, member] : parameter_fields())
        if (!value.contains(name))
          doc.fail(at, "missing parameter \"" + std::string(name) +
                           "\" in \"parameters\" (all 13 are required)");
    } else if (key == "joint") {
      const std::string j = doc.text(value, at, "\"joint\"");
      if (j != "g2" && j != "g3")
        doc.fail(at, "\"joint\" must be \"g2\" or \"g3\"");
      job.options.joint = j == "g2" ? CascadeJoint::g2_quadratic : CascadeJoint::g3_cubic;
    } else if (key == "side_intervals") {
      job.options.side_intervals = doc.integer(value, at, "\"side_intervals\"", 4, 100000);
    } else if (key == "edge_intervals") {
      job.options.edge_intervals = doc.integer(value, at, "\"edge_intervals\"", 2, 100000);
    } else if (key == "stack") {
      const std::string s = doc.text(value, at, "\"stack\"");
      if (!kAligns.count(s))
        doc.fail(at, "\"stack\" must be \"centroid\", \"le\", \"te\" or \"none\"");
      job.align = kAligns.at(s);
    } else if (key != "span") {
      doc.fail(at, "unknown key \"" + key + "\"");
    }
  }
  if (!doc.root.contains("parameters"))
    doc.fail("", "missing \"parameters\" (the 13 profile parameters)");
  if (!doc.root.contains("span")) {
    job.stations.push_back({0.0, base});
    return job;
  }
  const json& span = doc.root["span"];
  if (!span.is_object() || !span.contains("radius") || !span["radius"].is_array() ||
      span["radius"].empty())
    doc.fail("/span", "\"span\" must be an object with a non-empty \"radius\" array");
  job.has_span = true;
  const size_t n = span["radius"].size();
  for (size_t k = 0; k < n; ++k)
    job.stations.push_back({doc.number(span["radius"][k], "/span/radius/" + std::to_string(k),
                                       "\"span\".\"radius\"[" + std::to_string(k) + "]"),
                            base});
  for (const auto& [name, v] : span.items()) {
    if (name == "radius")
      continue;
    const std::string at = "/span/" + name;
    double CascadeParameters::*f = field(name);
    if (!f)
      doc.fail(at, "unknown parameter \"" + name + "\" in \"span\"");
    if (!v.is_array() || v.size() != n)
      doc.fail(at, "\"span\".\"" + name + "\" must be an array of " + std::to_string(n) +
                       " numbers (one per radius)");
    for (size_t k = 0; k < n; ++k)
      job.stations[k].parameters.*f =
          doc.number(v[k], at + "/" + std::to_string(k),
                     "\"span\".\"" + name + "\"[" + std::to_string(k) + "]");
  }
  return job;
}

void require_csv(const std::string& option, const std::string& path) {
  if (lower_extension(path) != ".csv")
    throw UsageError(option + " '" + path + "': expected a .csv file");
}

// The body of `interlin profile` (run_command handles help, exit statuses and removal on
// failure).
void profile_main(const ParsedArgs& a, std::vector<std::string>& written) {
  const std::string input = single_input(a, "parameter file");
  if (const std::string ext = lower_extension(input); ext != ".json" && ext != ".toml")
    throw UsageError("parameter file '" + input + "': expected a .json or .toml file");
  if (!a.has("output"))
    throw UsageError("nothing to do: give -o SECTIONS.csv");
  const std::string output = a.get("output");
  require_csv("output", output);
  const std::string curv = a.get("curvature");
  if (a.has("curvature"))
    require_csv("--curvature", curv);
  std::string joint, stack;
  if (a.has("joint"))
    joint = parse_choice("joint", a.get("joint"), {"g2", "g3"});
  if (a.has("stack"))
    stack = parse_choice("stack", a.get("stack"), {"centroid", "le", "te", "none"});
  std::pair<int, int> points{0, 0};
  if (a.has("points")) {
    points = parse_int_pair("points", a.get("points"), 2, 100000);
    if (points.first < 4 || points.second % 2 != 0)
      throw UsageError("--points SIDE,EDGE: SIDE must be >= 4 and EDGE even");
  }
  const bool quiet = a.has("quiet");
  check_output_dir(output);
  if (a.has("curvature"))
    check_output_dir(curv);

  if (!quiet)
    std::cerr << "reading " << input << "\n";
  ProfileJob job = read_profile_parameters(input);
  if (!joint.empty())
    job.options.joint = joint == "g2" ? CascadeJoint::g2_quadratic : CascadeJoint::g3_cubic;
  if (!stack.empty())
    job.align = kAligns.at(stack);
  if (points.first > 0) {
    job.options.side_intervals = points.first;
    job.options.edge_intervals = points.second;
  }

  std::vector<Section> sections;
  std::vector<CascadeProfile> profiles;
  try {
    std::vector<Eigen::MatrixXd> S;
    if (job.has_span) {
      S = stack_cascade_profiles(job.stations, job.align, job.options, &profiles);
    } else { // one profile in the cascade frame, z = 0
      profiles.push_back(cascade_profile(job.stations[0].parameters, job.options));
      S.emplace_back(profiles[0].points.rows(), 3);
      S[0] << profiles[0].points, Eigen::VectorXd::Zero(profiles[0].points.rows());
    }
    for (size_t k = 0; k < S.size(); ++k) {
      Section s;
      s.id = std::to_string(k);
      s.points = S[k];
      sections.push_back(s);
    }
  } catch (const std::invalid_argument& e) {
    throw_input_error(input, 0, e.what()); // a property of the file's parameters
  } catch (const std::runtime_error& e) {
    throw_input_error(input, 0, e.what());
  }

  std::cout << "interlin profile " << input << "\n";
  std::cout << "  sections     " << sections.size() << " x " << sections[0].points.rows()
            << " points, joint "
            << (job.options.joint == CascadeJoint::g3_cubic ? "G3 (cubic, §4.2)"
                                                            : "G2 (quadratic, §4.1)")
            << "\n";
  for (size_t k = 0; k < profiles.size(); ++k) {
    const CascadeProfile& P = profiles[k];
    const auto len = [](const std::vector<PlanarNaturalCurve>& side) {
      return side[0].length + side[1].length;
    };
    std::cout << "  section " << k << "    z " << fmt(job.stations[k].radius, 6) << ", pitch "
              << fmt(P.pitch, 6) << ", throat " << fmt(P.throat, 6) << ", suction "
              << fmt(len(P.suction), 6) << ", pressure " << fmt(len(P.pressure), 6) << ", max miss "
              << fmt(P.miss, 2) << "\n";
  }

  write_sections_csv(output, sections);
  written.push_back(output);
  if (a.has("curvature")) {
    write_file_atomically(curv, [&](std::ostream& out) {
      out.precision(17);
      out << "section,side,sbar,s,x,y,phi,k,dk\n";
      for (size_t k = 0; k < profiles.size(); ++k)
        for (const auto& [name, side] : {std::pair{"suction", &profiles[k].suction},
                                         std::pair{"pressure", &profiles[k].pressure}}) {
          const Eigen::MatrixXd T = side_curvature_plot(*side, 201);
          for (Eigen::Index i = 0; i < T.rows(); ++i) {
            out << k << ',' << name;
            for (Eigen::Index c = 0; c < T.cols(); ++c)
              out << ',' << T(i, c);
            out << '\n';
          }
        }
    });
    written.push_back(curv);
  }
  print_written(written);
}

} // namespace

int run_profile(int argc, const char* const* argv) {
  return run_command("profile", kProfileHelp, argc, argv,
                     {{"output", 'o', true, false},
                      {"joint", 0, true, false},
                      {"points", 0, true, false},
                      {"stack", 0, true, false},
                      {"curvature", 0, true, false}},
                     profile_main);
}

} // namespace interlin::cli
