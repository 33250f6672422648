// Point-cloud files: dispatch by extension, the x y z text format, and the checks shared by all
// formats (normals, payload sizes).
#include "interlin/reconstruction/clouds/read_point_cloud.h"

#include "cloud_formats.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/csv_fields.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/points_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>

namespace interlin {

namespace detail {

double binary_value(const char* p, char type, int size, bool big_endian) {
  char b[8];
  std::memcpy(b, p, static_cast<size_t>(size));
  if (big_endian)
    std::reverse(b, b + size);
  auto get = [&b](auto v) {
    std::memcpy(&v, b, sizeof v);
    return static_cast<double>(v);
  };
  if (type == 'F')
    return size == 4 ? get(float{}) : get(double{});
  if (type == 'I')
    return size == 1   ? get(std::int8_t{})
           : size == 2 ? get(std::int16_t{})
           : size == 4 ? get(std::int32_t{})
                       : get(std::int64_t{});
  return size == 1   ? get(std::uint8_t{})
         : size == 2 ? get(std::uint16_t{})
         : size == 4 ? get(std::uint32_t{})
                     : get(std::uint64_t{});
}

void require_payload(const std::string& path, long line, const std::string& what, double points,
                     double record, std::size_t available) {
  const double need = points * record;
  if (need > static_cast<double>(available)) {
    std::ostringstream s;
    s.precision(15);
    s << what << " needs " << need << " bytes of binary data, the file holds " << available
      << " after the header";
    throw_input_error(path, line, s.str());
  }
}

void read_xyz(const std::string& path, std::string_view text, bool normals_expected,
              CloudRows& rows, std::vector<std::string>& notes) {
  LineReader lines(text);
  std::string_view line;
  std::vector<std::string_view> f;
  size_t columns = 0;
  long first_line = 0;
  bool unit = true; // columns 4-6 of every row are unit vectors so far
  std::vector<double> extra;
  while (lines.next(line)) {
    const std::string_view t = trim(line);
    if (t.empty() || t.front() == '#')
      continue;
    split_plain(t, f);
    if (columns == 0) {
      columns = f.size();
      first_line = lines.number();
      if (columns < 3)
        throw_input_error(path, lines.number(),
                          "expected at least 3 fields (x y z), found " + std::to_string(columns));
      if (normals_expected && columns < 6)
        throw_input_error(path, lines.number(),
                          "expected 6 fields (x y z nx ny nz) in an .xyzn file, found " +
                              std::to_string(columns));
    } else if (f.size() != columns) {
      throw_input_error(path, lines.number(),
                        "expected " + std::to_string(columns) + " fields (as on line " +
                            std::to_string(first_line) + "), found " + std::to_string(f.size()));
    }
    double p[3], n[3] = {0, 0, 0};
    static const char* const kNames[6] = {"x", "y", "z", "nx", "ny", "nz"};
    for (int c = 0; c < 3; ++c)
      p[c] = field_number(f[static_cast<size_t>(c)], path, lines.number(), kNames[c]);
    if (columns >= 6 && (normals_expected || unit)) {
      for (int c = 0; c < 3; ++c) {
        const std::string_view field = f[static_cast<size_t>(c + 3)];
        if (normals_expected)
          n[c] = field_number(field, path, lines.number(), kNames[c + 3]);
        else if (parse_strict_double(field, n[c]) != NumberKind::ok)
          unit = false; // not numbers: other data, ignored
      }
      // kUnitTolerance: normals written with 3 to 4 significant digits still pass
      constexpr double kUnitTolerance = 1e-2;
      unit = unit &&
             std::abs(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) <= kUnitTolerance;
      extra.insert(extra.end(), n, n + 3);
    }
    rows.xyz.insert(rows.xyz.end(), p, p + 3);
  }
  if (columns == 0)
    throw_input_error(path, 0,
                      "no points: the file is empty or holds only comments and blank lines");
  // Columns 4-6 are normals in .xyzn files, and in .xyz/.txt files when every row holds a unit
  // vector there (colour or intensity columns do not).
  if (columns >= 6 && (normals_expected || unit)) {
    rows.with_normals = true;
    rows.n = std::move(extra);
  } else if (columns > 3) {
    notes.push_back(path + ": columns 4-" + std::to_string(columns) +
                    " ignored (not unit normals; name the file .xyzn to force normals)");
  }
}

} // namespace detail

namespace {

std::string lower_extension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
    return "";
  return ascii_lower(path.substr(dot));
}

// The rows as a cloud; normals normalised, or dropped (with a note) when one is not usable.
PointCloud to_cloud(const std::string& path, detail::CloudRows& rows,
                    std::vector<std::string>& notes) {
  const Eigen::Index n = rows.size();
  if (n == 0)
    throw_input_error(path, 0, "no points");
  PointCloud c;
  c.points = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      rows.xyz.data(), n, 3);
  if (!rows.with_normals)
    return c;
  Eigen::MatrixX3d N = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
      rows.n.data(), n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double len = N.row(i).norm();
    if (!std::isfinite(len) || len < 1e-12) {
      notes.push_back(path + ": normals ignored: point " + std::to_string(i + 1) +
                      " has a zero or non-finite normal (normals will be estimated)");
      return c;
    }
    N.row(i) /= len;
  }
  c.normals = N;
  return c;
}

} // namespace

bool is_point_cloud_file(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".pcd" || e == ".ply" || e == ".xyz" || e == ".xyzn" || e == ".txt" || e == ".csv";
}

PointCloud read_point_cloud(const std::string& path, std::vector<std::string>* notes) {
  if (!is_point_cloud_file(path))
    throw_input_error(path, 0,
                      "unknown point-cloud extension '" + lower_extension(path) +
                          "' (use .pcd .ply .xyz .xyzn .txt .csv)");
  return parse_point_cloud(read_input_file(path), path, notes);
}

PointCloud parse_point_cloud(std::string_view text, const std::string& path,
                             std::vector<std::string>* notes_out) {
  std::vector<std::string> notes;
  const std::string ext = lower_extension(path);
  detail::CloudRows rows;
  if (ext == ".csv") {
    const PointsAndNormals pn = parse_points_normals_csv(text, path);
    rows.with_normals = pn.normals.rows() > 0;
    for (Eigen::Index i = 0; i < pn.points.rows(); ++i) {
      const Eigen::RowVector3d p = pn.points.row(i);
      const Eigen::RowVector3d q = rows.with_normals ? pn.normals.row(i) : p;
      rows.add(p.data(), q.data());
    }
  } else if (ext == ".pcd") {
    detail::read_pcd(path, text, rows, notes);
  } else if (ext == ".ply") {
    detail::read_ply(path, text, rows);
  } else if (is_point_cloud_file(path)) {
    detail::read_xyz(path, text, ext == ".xyzn", rows, notes);
  } else {
    throw_input_error(path, 0,
                      "unknown point-cloud extension '" + ext +
                          "' (use .pcd .ply .xyz .xyzn .txt .csv)");
  }
  PointCloud c = to_cloud(path, rows, notes);
  if (notes_out)
    notes_out->insert(notes_out->end(), notes.begin(), notes.end());
  return c;
}

} // namespace interlin
