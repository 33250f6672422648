#pragma once
// Cascade profile parameter files (interlin profile PARAMS.{json,toml}): the 13 parameters of
// seed 004 §4.1, an optional span law and profile options, validated with one error line per
// problem (docs/formats.md, "Cascade profile parameters").

#include "interlin/splines/cascade_stack.h"

#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace interlin::cli {

// What a parameter file asks for: the stations (one without a span law), profile options and
// the stacking line.
struct ProfileJob {
  std::vector<SpanStation> stations;
  CascadeOptions options;
  StackAlign align = StackAlign::centroid;
  bool has_span = false;
};

// The stacking lines by name, as the file's "stack" and --stack give them.
inline const std::map<std::string, StackAlign> kAligns = {{"centroid", StackAlign::centroid},
                                                          {"le", StackAlign::leading_edge},
                                                          {"te", StackAlign::trailing_edge},
                                                          {"none", StackAlign::none}};

// Reads and validates the parameter file, JSON or TOML by extension. Throws InputError
// "PATH:LINE: what" (TOML, JSON syntax errors) or "PATH: what" naming the key.
ProfileJob read_profile_parameters(const std::string& path);

// Same, from the file's content; `toml` selects the syntax, `path` names the file in messages.
ProfileJob parse_profile_parameters(std::string_view content, const std::string& path, bool toml);

} // namespace interlin::cli
