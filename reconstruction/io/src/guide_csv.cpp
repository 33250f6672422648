// Guide-line CSV reader (docs/formats.md, "Guide files").
#include "interlin/reconstruction/io/guide_csv.h"

#include "interlin/reconstruction/io/csv_fields.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <string_view>

namespace interlin {

namespace {

using std::string_view;

struct Row {
  long line, index;
  Eigen::Vector3d p;
};

// One guide from its rows: sorted by index (stable: file order without an index column),
// checked for repeated indices and repeated points, at least 2 points.
Guide guide_of_rows(const std::string& id, std::vector<Row>& rs, const std::string& path) {
  std::stable_sort(rs.begin(), rs.end(),
                   [](const Row& a, const Row& b) { return a.index < b.index; });
  Guide g;
  g.id = id;
  g.points.resize(static_cast<Eigen::Index>(rs.size()), 3);
  for (size_t i = 0; i < rs.size(); ++i) {
    if (i > 0 && rs[i].index == rs[i - 1].index)
      throw_input_error(path, std::max(rs[i].line, rs[i - 1].line),
                        "duplicate index " + std::to_string(rs[i].index) + " in guide " + id +
                            " (also on line " +
                            std::to_string(std::min(rs[i].line, rs[i - 1].line)) + ")");
    if (i > 0 && rs[i].p == rs[i - 1].p)
      throw_input_error(path, rs[i].line,
                        "point repeats the previous point of guide " + id + " (line " +
                            std::to_string(rs[i - 1].line) + ")");
    g.points.row(static_cast<Eigen::Index>(i)) = rs[i].p.transpose();
    g.lines.push_back(rs[i].line);
  }
  if (rs.size() < 2)
    throw_input_error(path, rs[0].line, "guide " + id + " has 1 point; need at least 2");
  return g;
}

} // namespace

GuideSet parse_guides(std::istream& in, const std::string& path) {
  GuideSet set;
  set.path = path;
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  LineReader lines(text);
  string_view line;
  bool header = false;
  int col_guide = -1, col_index = -1, col_xyz[3] = {-1, -1, -1};
  size_t nfields = 0;
  std::vector<std::string> order;               // guide ids in order of first appearance
  std::map<std::string, std::vector<Row>> rows; // per guide
  std::map<std::string, long> last_line;        // last row of each guide (contiguity check)
  std::string previous;
  std::vector<string_view> f; // the fields of the current line
  while (lines.next(line)) {
    const long lineno = lines.number();
    const string_view t = trim(line);
    if (t.empty() || t.front() == '#')
      continue;
    split_commas(line, f);
    if (!header) {
      header = true;
      nfields = f.size();
      const std::vector<std::string> names{"guide", "x", "y", "z", "index"};
      const std::vector<int> col = header_columns(f, names, path, lineno);
      col_guide = col[0];
      col_xyz[0] = col[1];
      col_xyz[1] = col[2];
      col_xyz[2] = col[3];
      col_index = col[4];
      const std::string missing = missing_columns(col, names, 4);
      if (!missing.empty())
        throw_input_error(path, lineno,
                          "header lacks the required column(s) " + missing +
                              ": a guide file's header names the columns guide, x, y, z (index "
                              "optional, other columns ignored)");
      continue;
    }
    if (f.size() != nfields)
      throw_input_error(path, lineno,
                        "expected " + std::to_string(nfields) +
                            " comma-separated fields (as in the header), found " +
                            std::to_string(f.size()));
    const std::string id(f[static_cast<size_t>(col_guide)]);
    if (id.empty())
      throw_input_error(path, lineno, "column guide: empty value");
    Row r{lineno, 0, {}};
    const char* names[3] = {"x", "y", "z"};
    for (int c = 0; c < 3; ++c)
      r.p(c) = field_number(f[static_cast<size_t>(col_xyz[c])], path, lineno, names[c]);
    if (col_index >= 0)
      r.index = field_index(f[static_cast<size_t>(col_index)], path, lineno);
    if (!rows.count(id))
      order.push_back(id);
    else if (col_index < 0 && previous != id)
      throw_input_error(path, lineno,
                        "rows of guide " + id +
                            " resume here after other guides (its previous "
                            "run ended at line " +
                            std::to_string(last_line[id]) +
                            "); make them contiguous or add an index column");
    r.index = col_index >= 0 ? r.index : static_cast<long>(rows[id].size());
    rows[id].push_back(r);
    last_line[id] = lineno;
    previous = id;
  }
  if (!header)
    throw_input_error(path, 0,
                      "no data rows (the file is empty or holds only comments and blank "
                      "lines)");
  if (order.empty())
    throw_input_error(path, 0, "no data rows after the header");
  for (const std::string& id : order)
    set.guides.push_back(guide_of_rows(id, rows[id], path));
  return set;
}

GuideSet read_guides(const std::string& path) {
  std::istringstream in(read_input_file(path));
  return parse_guides(in, path);
}

} // namespace interlin
