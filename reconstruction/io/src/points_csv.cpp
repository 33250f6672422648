#include "interlin/reconstruction/io/points_csv.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/csv_fields.h"
#include "interlin/reconstruction/io/input_error.h"

#include <array>
#include <string_view>
#include <vector>

namespace interlin {

namespace {

// Header names of the three normal columns (either spelling, not mixed).
const std::array<std::vector<std::string>, 2> kNormalNames{
    {{"nx", "ny", "nz"}, {"normal_x", "normal_y", "normal_z"}}};

// The normal columns of the header: all three of one spelling (its index into kNormalNames in
// `spelling`), or none (-1).
std::array<int, 3> normal_columns(const std::vector<std::string_view>& f, const std::string& path,
                                  long line, size_t& spelling) {
  for (spelling = 0; spelling < kNormalNames.size(); ++spelling) {
    const auto& names = kNormalNames[spelling];
    const std::vector<int> col = header_columns(f, names, path, line);
    const int found = (col[0] >= 0) + (col[1] >= 0) + (col[2] >= 0);
    if (found == 3)
      return {col[0], col[1], col[2]};
    if (found > 0)
      throw_input_error(path, line,
                        std::string("header names only some of the normal columns ") + names[0] +
                            ", " + names[1] + ", " + names[2] + ": give all three or none");
  }
  return {-1, -1, -1};
}

Eigen::MatrixX3d to_matrix(const std::vector<std::array<double, 3>>& rows) {
  Eigen::MatrixX3d M(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int c = 0; c < 3; ++c)
      M(static_cast<Eigen::Index>(i), c) = rows[i][c];
  return M;
}

// The parser behind parse_points_csv and parse_points_normals_csv.
PointsAndNormals parse_csv(std::string_view text, const std::string& path, bool with_normals) {
  LineReader lines(text);
  std::string_view line;
  std::array<int, 3> col{-1, -1, -1}, ncol{-1, -1, -1};
  std::size_t fields = 0, spelling = 0;
  long header_line = 0;
  std::vector<std::array<double, 3>> rows, normals;
  std::vector<std::string_view> f; // the fields of the current line
  while (lines.next(line)) {
    const long number = lines.number();
    const std::string_view t = trim(line);
    if (t.empty() || t.front() == '#')
      continue;
    split_commas(line, f);
    if (header_line == 0) {
      header_line = number;
      fields = f.size();
      const std::vector<std::string> xyz{"x", "y", "z"};
      const std::vector<int> found = header_columns(f, xyz, path, number);
      col = {found[0], found[1], found[2]};
      const std::string missing = missing_columns(found, xyz, 3);
      if (!missing.empty())
        throw_input_error(path, number,
                          "header lacks the column(s) " + missing +
                              ": a points file starts with a header naming the columns x, y, z");
      if (with_normals)
        ncol = normal_columns(f, path, number, spelling);
      continue;
    }
    if (f.size() != fields)
      throw_input_error(path, number,
                        "expected " + std::to_string(fields) +
                            " comma-separated fields (as in the header on line " +
                            std::to_string(header_line) + "), found " + std::to_string(f.size()));
    std::array<double, 3> p{}, n{};
    for (int c = 0; c < 3; ++c) {
      const char name[2] = {static_cast<char>('x' + c), 0};
      p[c] = field_number(f[static_cast<std::size_t>(col[c])], path, number, name);
    }
    rows.push_back(p);
    if (ncol[0] >= 0) {
      for (int c = 0; c < 3; ++c)
        n[c] = field_number(f[static_cast<std::size_t>(ncol[c])], path, number,
                            kNormalNames[spelling][c].c_str());
      normals.push_back(n);
    }
  }
  if (header_line == 0)
    throw_input_error(path, 0,
                      "no header: the file is empty or holds only comments and blank lines");
  if (rows.empty())
    throw_input_error(path, 0, "no points after the header on line " + std::to_string(header_line));
  return {to_matrix(rows), normals.empty() ? Eigen::MatrixX3d(0, 3) : to_matrix(normals)};
}

} // namespace

Eigen::MatrixX3d read_points_csv(const std::string& path) {
  return parse_points_csv(read_input_file(path), path);
}

Eigen::MatrixX3d parse_points_csv(std::string_view text, const std::string& path) {
  return parse_csv(text, path, false).points;
}

PointsAndNormals read_points_normals_csv(const std::string& path) {
  return parse_points_normals_csv(read_input_file(path), path);
}

PointsAndNormals parse_points_normals_csv(std::string_view text, const std::string& path) {
  return parse_csv(text, path, true);
}

} // namespace interlin
