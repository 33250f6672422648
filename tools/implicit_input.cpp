#include "implicit_input.h"

#include "cli_args.h"
#include "cli_common.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/csv_fields.h"
#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>

namespace interlin::cli {

namespace {

// The first content line of a text file and how its data is grouped by blank lines.
struct TextShape {
  long line = 0;                   // first content line (0: none)
  std::vector<std::string> fields; // its fields (split at commas and blanks), lower case
  bool header = false;             // no field is a number
  bool section_column = false;     // a comma-separated field is `section`
  int groups = 0;                  // runs of content lines separated by blank lines
};

TextShape text_shape(const std::string& text) {
  TextShape s;
  LineReader lines(text);
  std::string_view line;
  std::vector<std::string_view> f;
  bool gap = false; // a blank line since the last content line
  while (lines.next(line)) {
    const std::string_view t = trim(line);
    if (t.empty()) {
      gap = true;
      continue;
    }
    if (t.front() == '#') // comment lines do not separate groups
      continue;
    if (s.line == 0) {
      s.line = lines.number();
      split_plain(t, f);
      s.header = true;
      for (std::string_view x : f) {
        double v;
        s.fields.push_back(ascii_lower(x));
        if (parse_strict_double(x, v) != NumberKind::not_number)
          s.header = false;
      }
      split_commas(t, f);
      for (std::string_view x : f)
        s.section_column = s.section_column || ascii_lower(x) == "section";
      s.section_column = s.section_column && s.header;
      if (s.header) // groups count data lines, after the header
        continue;
    }
    s.groups += gap || s.groups == 0;
    gap = false;
  }
  return s;
}

bool names(const TextShape& s, const char* n) {
  return std::find(s.fields.begin(), s.fields.end(), n) != s.fields.end();
}

} // namespace

ImplicitInput implicit_input_kind(const std::string& path, std::string* why) {
  auto say = [&](const std::string& w) {
    if (why)
      *why = w;
  };
  const std::string e = lower_extension(path);
  if (e == ".rf")
    return ImplicitInput::model;
  if (e == ".dat")
    return ImplicitInput::sections;
  if (e == ".pcd" || e == ".ply" || e == ".xyz" || e == ".xyzn") {
    say("a point cloud (" + e + ")");
    return ImplicitInput::cloud;
  }
  if (e != ".csv" && e != ".txt")
    throw UsageError("input '" + path +
                     "': unknown kind (expected sections .csv/.txt/.dat, a point cloud "
                     ".pcd/.ply/.xyz/.xyzn/.csv/.txt or an R-function model .rf)");
  const TextShape s = text_shape(read_input_file(path));
  if (s.line == 0) // empty: the section reader says so
    return ImplicitInput::sections;
  const bool xyz = s.fields.size() == 3 && names(s, "x") && names(s, "y") && names(s, "z");
  if (s.section_column)
    return ImplicitInput::sections;
  if (!s.header && s.fields.size() == 3) {
    if (s.groups >= 2)
      return ImplicitInput::sections;
    if (e == ".txt") {
      say("a point cloud (x y z lines without blank lines between groups)");
      return ImplicitInput::cloud;
    }
    throw_input_error(path, s.line,
                      "a .csv file without a header and without blank lines between sections: "
                      "name its columns (section,x,y,z for blade sections; x,y,z[,nx,ny,nz] for "
                      "a point cloud)");
  }
  if (s.header && xyz) {
    if (s.groups >= 2)
      return ImplicitInput::sections;
    say("a point cloud (header x, y, z; no blank lines between groups)");
    return ImplicitInput::cloud;
  }
  if (!s.header) {
    if (e == ".txt") {
      say("a point cloud (" + std::to_string(s.fields.size()) + " numbers a line)");
      return ImplicitInput::cloud;
    }
    throw_input_error(path, s.line,
                      "a .csv file without a header: name its columns (section,x,y,z for blade "
                      "sections; x,y,z[,nx,ny,nz] for a point cloud)");
  }
  if (e == ".csv" && names(s, "x") && names(s, "y") && names(s, "z")) {
    say("a point cloud (header with x, y, z and no section column)");
    return ImplicitInput::cloud;
  }
  throw_input_error(path, s.line,
                    e == ".csv" ? "the header names neither a section column (blade sections) "
                                  "nor x, y and z (a point cloud)"
                                : "a .txt header must be x y z (a plain section file); a point "
                                  "cloud .txt has no header");
}

} // namespace interlin::cli
