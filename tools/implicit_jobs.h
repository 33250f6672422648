#pragma once
// The jobs of `interlin implicit` (cmd_implicit.cpp: sections, R-function models; cmd_implicit_
// cloud.cpp: point clouds) and what they share.

#include "cli_args.h"
#include "cli_common.h"

#include "interlin/interflatation/models/ifl_file.h"
#include "interlin/reconstruction/implicit/section_body_build.h"

#include <string>

namespace interlin::cli {

// --resolution, --band, --margin, --threads of a section body, progress lines through `progress`.
SectionBodyOptions section_body_options(const ParsedArgs& a, const Progress& progress);

// The summary lines of a section body build (stdout), after `sections` (what was lofted).
void print_section_body(const SectionBodyBuild& b, const std::string& sections);

// Writes the .ifl file whole or not at all.
void write_model(const std::string& path, const IflBlock& model);

// A point cloud (read_point_cloud formats) -> a sectioned scan's section body or the
// unstructured partition-of-unity implicit. `why` says how the input was recognised.
void cloud_job(const ParsedArgs& a, const std::string& input, const std::string& output,
               const Progress& progress, const std::string& why);

} // namespace interlin::cli
