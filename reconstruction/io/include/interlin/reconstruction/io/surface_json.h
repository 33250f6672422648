#pragma once
// Exact text form of a B-spline surface (JSON), for exchange with scripts and for regression data.
//
// {"format": "interlin-bspline-surface", "version": 1,
//  "degree": [pu, pv], "closed_u": bool, "size": [num_u, num_v],
//  "knots_u": [...], "knots_v": [...],           // num_u + pu + 1, num_v + pv + 1 numbers
//  "control_points": [[x, y, z], ...],           // num_u * num_v rows, row i + num_u * j
//  "meta": {"key": "value", ...}}                // optional, free text key/values

#include "interlin/splines/bspline_surface.h"

#include <map>
#include <string>
#include <string_view>

namespace interlin {

// Writes `s` (checked with check_surface; std::invalid_argument otherwise) as JSON. Numbers are
// the shortest decimals that read back to the same doubles, so a round trip is bit-exact.
// Inputs:
//   path  output file, written atomically (a failure leaves no file behind)
//   s     the surface
//   meta  free key/value strings stored under "meta" (source file, units, deviation, ...);
//         omitted from the file when empty
// Throws std::runtime_error("cannot write PATH: ...") when the file cannot be written.
void write_surface_json(const std::string& path, const BSplineSurface& s,
                        const std::map<std::string, std::string>& meta = {});

// Reads a file written by write_surface_json and validates everything: format and version,
// field types, sizes, finiteness, non-decreasing knots, then check_surface. Unknown top-level
// keys are ignored.
// Inputs:
//   path  JSON file
// Outputs:
//   meta  (optional) receives the "meta" object; values that are not strings are stored as
//         their JSON text
// Throws InputError("PATH:LINE: ...") on a JSON syntax error and InputError("PATH: message
// naming the field") on any other problem.
BSplineSurface read_surface_json(const std::string& path,
                                 std::map<std::string, std::string>* meta = nullptr);

// Same as read_surface_json, from the file's content; `path` names it in messages.
BSplineSurface parse_surface_json(std::string_view content, const std::string& path,
                                  std::map<std::string, std::string>* meta = nullptr);

} // namespace interlin
