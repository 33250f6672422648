#include "toml_as_json.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include <toml++/toml.h>

#include <sstream>

namespace interlin::cli {
namespace {

// JSON pointer escaping (RFC 6901): '~' -> "~0", '/' -> "~1".
std::string pointer_token(const std::string& key) {
  std::string t;
  for (char c : key)
    t += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
  return t;
}

nlohmann::json convert(const toml::node& node, const std::string& pointer,
                       std::map<std::string, long>& lines) {
  lines[pointer] = static_cast<long>(node.source().begin.line);
  if (const toml::table* t = node.as_table()) {
    nlohmann::json o = nlohmann::json::object();
    for (const auto& [key, value] : *t) {
      const std::string k(key.str());
      o[k] = convert(value, pointer + "/" + pointer_token(k), lines);
    }
    return o;
  }
  if (const toml::array* a = node.as_array()) {
    nlohmann::json arr = nlohmann::json::array();
    for (size_t i = 0; i < a->size(); ++i)
      arr.push_back(convert(*a->get(i), pointer + "/" + std::to_string(i), lines));
    return arr;
  }
  if (const auto* v = node.as_integer())
    return static_cast<long long>(v->get());
  if (const auto* v = node.as_floating_point())
    return v->get();
  if (const auto* v = node.as_boolean())
    return v->get();
  if (const auto* v = node.as_string())
    return v->get();
  std::ostringstream text; // a date, time or date-time
  node.visit([&](const auto& n) { text << n; });
  return text.str();
}

} // namespace

TomlAsJson read_toml_as_json(const std::string& path) {
  return parse_toml_as_json(read_input_file(path), path);
}

TomlAsJson parse_toml_as_json(std::string_view content, const std::string& path) {
  toml::table root;
  try {
    root = toml::parse(content, path);
  } catch (const toml::parse_error& e) {
    throw_input_error(path, static_cast<long>(e.source().begin.line),
                      "TOML syntax error: " + std::string(e.description()) + " (column " +
                          std::to_string(e.source().begin.column) + ")");
  }
  TomlAsJson doc;
  doc.value = convert(root, "", doc.lines);
  doc.lines[""] = 0; // the document as a whole has no one line
  return doc;
}

} // namespace interlin::cli
