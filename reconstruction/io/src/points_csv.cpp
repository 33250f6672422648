#include "interlin/reconstruction/io/points_csv.h"

#include "csv_fields.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include <array>
#include <string_view>
#include <vector>

namespace interlin {

Eigen::MatrixX3d read_points_csv(const std::string& path) {
  return parse_points_csv(read_input_file(path), path);
}

Eigen::MatrixX3d parse_points_csv(std::string_view text, const std::string& path) {
  LineReader lines(text);
  std::string_view line;
  std::array<int, 3> col{-1, -1, -1};
  std::size_t fields = 0;
  long header_line = 0;
  std::vector<std::array<double, 3>> rows;
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
      for (std::size_t i = 0; i < f.size(); ++i) {
        const std::string name = ascii_lower(f[i]);
        for (int c = 0; c < 3; ++c)
          if (name == std::string(1, static_cast<char>('x' + c))) {
            if (col[c] >= 0)
              throw_input_error(path, number,
                                "column " + name + " appears twice in the header (fields " +
                                    std::to_string(col[c] + 1) + " and " + std::to_string(i + 1) +
                                    ")");
            col[c] = static_cast<int>(i);
          }
      }
      std::string missing;
      for (int c = 0; c < 3; ++c)
        if (col[c] < 0)
          missing += std::string(missing.empty() ? "" : ", ") + static_cast<char>('x' + c);
      if (!missing.empty())
        throw_input_error(path, number,
                          "header lacks the column(s) " + missing +
                              ": a points file starts with a header naming the columns x, y, z");
      continue;
    }
    if (f.size() != fields)
      throw_input_error(path, number,
                        "expected " + std::to_string(fields) +
                            " comma-separated fields (as in the header on line " +
                            std::to_string(header_line) + "), found " + std::to_string(f.size()));
    std::array<double, 3> p{};
    for (int c = 0; c < 3; ++c) {
      const char name[2] = {static_cast<char>('x' + c), 0};
      p[c] = field_number(f[static_cast<std::size_t>(col[c])], path, number, name);
    }
    rows.push_back(p);
  }
  if (header_line == 0)
    throw_input_error(path, 0,
                      "no header: the file is empty or holds only comments and blank lines");
  if (rows.empty())
    throw_input_error(path, 0, "no points after the header on line " + std::to_string(header_line));
  Eigen::MatrixX3d P(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int c = 0; c < 3; ++c)
      P(static_cast<Eigen::Index>(i), c) = rows[i][c];
  return P;
}

} // namespace interlin
