#pragma once
// What `interlin implicit` reads from its input file: blade sections, a point cloud or an
// R-function model. Extensions decide, except for .csv and .txt, which both the section reader
// and the point-cloud reader accept: their content decides (docs/formats.md, "Point clouds",
// "Sections or a cloud?").

#include <string>

namespace interlin::cli {

enum class ImplicitInput { sections, cloud, model };

// The kind of `path`, and in `why` (optional) the rule that decided it, for the summary.
// .dat -> sections; .pcd .ply .xyz .xyzn -> cloud; .rf -> model; .csv and .txt by the first
// content line (not blank, not a # comment) and the blank lines:
//   1. a header with a comma-separated field `section`                  -> sections
//   2. a header of exactly x, y, z, or no header and 3 numbers a line:
//      blank lines split the data into >= 2 groups (a plain section file) -> sections,
//      one group                                                          -> cloud
//   3. any other header naming x, y and z (e.g. with nx, ny, nz)       -> cloud
//   4. no header and more than 3 numbers a line (.txt: x y z nx ny nz)  -> cloud
// Throws InputError "PATH:LINE: ..." when no rule applies (a .csv without a header in one group,
// a header naming neither a section column nor x, y, z, a .txt header that is not x y z) and
// for an unreadable file; UsageError for an extension no reader takes.
ImplicitInput implicit_input_kind(const std::string& path, std::string* why = nullptr);

} // namespace interlin::cli
