#pragma once
// TOML parameter files as JSON values, so that a command validates one document model whichever
// of the two formats the user wrote (docs/formats.md, "Cascade profile parameters").

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <string_view>

namespace interlin::cli {

// A TOML file as the JSON value of the same structure, with the line of every value.
struct TomlAsJson {
  nlohmann::json value;
  std::map<std::string, long> lines; // JSON pointer ("/span/radius/3") -> line in the file
};

// Parses the TOML file `path` (toml++): tables become objects, arrays arrays; integers, floats
// (including inf and nan), booleans and strings stay what they are; dates and times become
// their TOML text. Throws InputError "PATH: cannot open: why" or
// "PATH:LINE: TOML syntax error: what (column C)".
TomlAsJson read_toml_as_json(const std::string& path);

// Same as read_toml_as_json, from the file's content; `path` names it in messages.
TomlAsJson parse_toml_as_json(std::string_view content, const std::string& path);

} // namespace interlin::cli
