#include "interlin/reconstruction/io/surface_json.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace interlin {
namespace {

using nlohmann::json;

constexpr const char* kFormat = "interlin-bspline-surface";
constexpr int kVersion = 1;

// Shortest decimal that reads back to x (valid JSON: "0.1", "3", "-2.5e-07", "1e+20").
std::string number(double x) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  const std::string text(buf.data(), res.ptr);
  // "-0" would be read back as the integer 0: keep the sign with a fraction.
  return text == "-0" ? "-0.0" : text;
}

// A JSON string literal; bytes that are not valid UTF-8 become U+FFFD.
std::string quoted(const std::string& s) {
  return json(s).dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string number_list(const Eigen::VectorXd& v) {
  std::string out = "[";
  for (Eigen::Index k = 0; k < v.size(); ++k)
    out += (k ? ", " : "") + number(v(k));
  return out + "]";
}

// Field access with errors that name the field.
struct Reader {
  const std::string& path;
  [[noreturn]] void fail(const std::string& message) const { throw_input_error(path, 0, message); }

  const json& field(const json& j, const char* name) const {
    const auto it = j.find(name);
    if (it == j.end())
      fail(std::string("missing field \"") + name + "\"");
    return *it;
  }
  long long integer(const json& j, const std::string& what) const {
    if (!j.is_number_integer())
      fail(what + " must be an integer");
    return j.get<long long>();
  }
  double real(const json& j, const std::string& what) const {
    if (!j.is_number())
      fail(what + " must be a number");
    const double x = j.get<double>();
    if (!std::isfinite(x))
      fail(what + " is not a finite number");
    return x;
  }
  const json& array(const json& j, const std::string& what, std::int64_t size) const {
    if (!j.is_array())
      fail(what + " must be an array");
    if (size >= 0 && static_cast<std::int64_t>(j.size()) != size)
      fail(what + " must have " + std::to_string(size) + " entries, has " +
           std::to_string(j.size()));
    return j;
  }
  std::array<long long, 2> pair(const json& root, const char* name) const {
    const std::string what = std::string("\"") + name + "\"";
    const json& a = array(field(root, name), what, 2);
    return {integer(a[0], what + "[0]"), integer(a[1], what + "[1]")};
  }
  Eigen::VectorXd knots(const json& root, const char* name, std::int64_t size, int degree) const {
    const std::string what = std::string("\"") + name + "\"";
    const json& a = array(field(root, name), what, size);
    Eigen::VectorXd k(size);
    for (Eigen::Index q = 0; q < size; ++q) {
      k(q) = real(a[static_cast<std::size_t>(q)], what + "[" + std::to_string(q) + "]");
      if (q > 0 && k(q) < k(q - 1))
        fail(what + " is not non-decreasing: entry " + std::to_string(q) + " (" + number(k(q)) +
             ") < entry " + std::to_string(q - 1) + " (" + number(k(q - 1)) + ")");
    }
    if (!(k(degree) < k(size - degree - 1)))
      fail(what + " has an empty parameter domain");
    return k;
  }
};

} // namespace

void write_surface_json(const std::string& path, const BSplineSurface& s,
                        const std::map<std::string, std::string>& meta) {
  check_surface(s);
  std::string text = "{\n";
  text += "  \"format\": " + quoted(kFormat) + ",\n";
  text += "  \"version\": " + std::to_string(kVersion) + ",\n";
  text +=
      "  \"degree\": [" + std::to_string(s.degree_u) + ", " + std::to_string(s.degree_v) + "],\n";
  text += std::string("  \"closed_u\": ") + (s.closed_u ? "true" : "false") + ",\n";
  text += "  \"size\": [" + std::to_string(s.num_u) + ", " + std::to_string(s.num_v) + "],\n";
  text += "  \"knots_u\": " + number_list(s.knots_u) + ",\n";
  text += "  \"knots_v\": " + number_list(s.knots_v) + ",\n";
  text += "  \"control_points\": [\n";
  for (Eigen::Index r = 0; r < s.ctrl.rows(); ++r)
    text += "    [" + number(s.ctrl(r, 0)) + ", " + number(s.ctrl(r, 1)) + ", " +
            number(s.ctrl(r, 2)) + (r + 1 < s.ctrl.rows() ? "],\n" : "]\n");
  text += "  ]";
  if (!meta.empty()) {
    text += ",\n  \"meta\": {\n";
    std::size_t k = 0;
    for (const auto& [key, value] : meta)
      text += "    " + quoted(key) + ": " + quoted(value) + (++k < meta.size() ? ",\n" : "\n");
    text += "  }";
  }
  text += "\n}\n";
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

BSplineSurface read_surface_json(const std::string& path,
                                 std::map<std::string, std::string>* meta) {
  return parse_surface_json(read_input_file(path), path, meta);
}

BSplineSurface parse_surface_json(std::string_view content, const std::string& path,
                                  std::map<std::string, std::string>* meta) {
  json root;
  try {
    root = json::parse(content.begin(), content.end());
  } catch (const json::parse_error& e) {
    // e.byte: 1-based index of the last character read.
    const std::string what = e.what();
    const auto colon = what.find(": ");
    throw_input_error(path, line_at(content, e.byte > 0 ? e.byte - 1 : 0),
                      "JSON syntax error: " +
                          (colon == std::string::npos ? what : what.substr(colon + 2)));
  } catch (const json::exception& e) {
    throw_json_number_error(content, path, e.what());
  }

  const Reader r{path};
  if (!root.is_object())
    r.fail("the top level is not a JSON object");
  const json& format = r.field(root, "format");
  if (!format.is_string() || format.get<std::string>() != kFormat)
    r.fail(std::string("\"format\" is ") + format.dump() + ", expected \"" + kFormat + "\"");
  const long long version = r.integer(r.field(root, "version"), "\"version\"");
  if (version != kVersion)
    r.fail("unsupported \"version\" " + std::to_string(version) + " (this reader knows " +
           std::to_string(kVersion) + ")");

  const auto degree = r.pair(root, "degree");
  constexpr long long kMaxDegree = 64;
  for (int d = 0; d < 2; ++d)
    if (degree[d] < 1 || degree[d] > kMaxDegree)
      r.fail("\"degree\"[" + std::to_string(d) + "] = " + std::to_string(degree[d]) +
             " is outside 1.." + std::to_string(kMaxDegree));
  const json& closed = r.field(root, "closed_u");
  if (!closed.is_boolean())
    r.fail("\"closed_u\" must be true or false");
  const auto size = r.pair(root, "size");
  constexpr long long kMaxSize = 100'000'000;
  for (int d = 0; d < 2; ++d)
    if (size[d] < degree[d] + 1 || size[d] > kMaxSize)
      r.fail("\"size\"[" + std::to_string(d) + "] = " + std::to_string(size[d]) +
             " must be at least degree + 1 = " + std::to_string(degree[d] + 1));

  BSplineSurface s;
  s.degree_u = static_cast<int>(degree[0]);
  s.degree_v = static_cast<int>(degree[1]);
  s.num_u = static_cast<Eigen::Index>(size[0]);
  s.num_v = static_cast<Eigen::Index>(size[1]);
  s.closed_u = closed.get<bool>();
  s.knots_u = r.knots(root, "knots_u", size[0] + degree[0] + 1, s.degree_u);
  s.knots_v = r.knots(root, "knots_v", size[1] + degree[1] + 1, s.degree_v);

  const std::int64_t num_ctrl = size[0] * size[1];
  const json& points = r.array(r.field(root, "control_points"), "\"control_points\"", num_ctrl);
  s.ctrl.resize(num_ctrl, 3);
  for (std::int64_t q = 0; q < num_ctrl; ++q) {
    const std::string what = "\"control_points\"[" + std::to_string(q) + "]";
    const json& p = r.array(points[static_cast<std::size_t>(q)], what, 3);
    for (int c = 0; c < 3; ++c)
      s.ctrl(q, c) = r.real(p[static_cast<std::size_t>(c)], what + "[" + std::to_string(c) + "]");
  }

  const auto meta_it = root.find("meta");
  if (meta_it != root.end() && !meta_it->is_object())
    r.fail("\"meta\" must be an object");
  if (meta) {
    meta->clear();
    if (meta_it != root.end())
      for (const auto& [key, value] : meta_it->items())
        (*meta)[key] = value.is_string() ? value.get<std::string>() : value.dump();
  }

  try {
    check_surface(s);
  } catch (const std::invalid_argument& e) {
    r.fail(std::string("invalid surface: ") + e.what());
  }
  return s;
}

} // namespace interlin
