// Cascade profile parameter files: JSON or TOML -> stations and options (docs/formats.md,
// "Cascade profile parameters").
#include "profile_parameters.h"

#include "cli_common.h"
#include "toml_as_json.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace interlin::cli {

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

ParamDoc read_json_document(std::string_view content, const std::string& path) {
  ParamDoc doc{path, {}, {}};
  try {
    doc.root = json::parse(content.begin(), content.end());
  } catch (const json::parse_error& e) {
    // nlohmann's text: "[json.exception.parse_error.101] parse error at line L, column C: what".
    const std::string msg = e.what();
    const auto col = msg.find("column"), p = msg.find(": ", col == std::string::npos ? 0 : col);
    throw_input_error(path, line_at(content, e.byte > 0 ? e.byte - 1 : 0),
                      "JSON syntax error: " + (p == std::string::npos ? msg : msg.substr(p + 2)));
  } catch (const json::exception& e) { // a number beyond the double range
    throw_json_number_error(content, path, e.what());
  }
  return doc;
}

} // namespace

ProfileJob read_profile_parameters(const std::string& path) {
  return parse_profile_parameters(read_input_file(path), path, lower_extension(path) == ".toml");
}

ProfileJob parse_profile_parameters(std::string_view content, const std::string& path, bool toml) {
  ParamDoc doc;
  if (toml) {
    TomlAsJson t = parse_toml_as_json(content, path);
    doc = {path, std::move(t.value), std::move(t.lines)};
  } else {
    doc = read_json_document(content, path);
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

} // namespace interlin::cli
