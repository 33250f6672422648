#pragma once
// Blade-section files: a CSV with a header naming the columns section, x, y, z (index optional),
// or plain x y z lines with blank lines between sections. The formats and every error and warning
// are described in docs/formats.md ("Section files").

#include <Eigen/Core>
#include <iosfwd>
#include <string>
#include <vector>

namespace interlin {

// One closed profile; the closing edge from the last point back to the first is implicit.
//   id      the `section` value as written in the file ("1", "2", ... for plain x y z files)
//   points  #P by 3 (x, y, z), in profile order, #P >= 4, no point equal to its predecessor and
//           the last point different from the first
//   lines   #P source line numbers (1-based), lines[i] is the line of points.row(i)
struct Section {
  std::string id;
  Eigen::MatrixXd points;
  std::vector<long> lines;
};

// The content of one section file.
//   path      the file name used in messages
//   sections  at least 2, ordered by id: numerically when every id is a number, otherwise
//             lexicographically (byte order); no two sections have identical point lists
//   warnings  one "FILE:LINE: ..." line per dropped point (repeated or closing points)
struct SectionSet {
  std::string path;
  std::vector<Section> sections;
  std::vector<std::string> warnings;
};

// Reads a section file (CSV with header, or plain x y z; detected from the first content line).
// Inputs:
//   path  file to read
// Outputs:
//   the sections and warnings; throws InputError with one line "FILE:LINE: message" (or
//   "FILE: message") when the file cannot be read or is not a valid section file.
SectionSet read_sections(const std::string& path);

// Same as read_sections, reading from a stream.
// Inputs:
//   in                 the file content
//   path_for_messages  the name used in messages and stored in SectionSet::path
SectionSet parse_sections(std::istream& in, const std::string& path_for_messages);

// Writes sections as CSV with header "section,index,x,y,z", index 0..#P-1 per section, the
// values with 17 significant digits (%.17g, locale-independent) so that reading the file back
// gives bit-identical points. The file appears atomically (whole or not at all).
// Inputs:
//   path      output file
//   sections  each with points #P by 3, finite; ids non-empty, without commas, line breaks,
//             surrounding spaces or a leading '#'
// Throws std::invalid_argument for sections that break these rules, std::runtime_error when the
// file cannot be written.
void write_sections_csv(const std::string& path, const std::vector<Section>& sections);

} // namespace interlin
