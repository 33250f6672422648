#pragma once
// Points files: a CSV with a header naming the columns x, y, z (any order, case-insensitive,
// other columns ignored), one point per line; '#' comment lines and blank lines are skipped, a
// UTF-8 byte-order mark is allowed (docs/formats.md, "Points files").

#include <Eigen/Core>
#include <string>
#include <string_view>

namespace interlin {

// Reads the points of a points file, in file order.
// Inputs:  path  the file; used in messages
// Outputs: P     #P by 3, #P >= 1, every value finite
// Throws InputError "PATH:LINE: message" (or "PATH: message") for an unreadable file, a missing
// header or column, a repeated column, a row with another field count than the header, a field
// that is not a finite number, and a file without points.
Eigen::MatrixX3d read_points_csv(const std::string& path);

// Same as read_points_csv, from the file's content `text`; `path` names it in messages.
Eigen::MatrixX3d parse_points_csv(std::string_view text, const std::string& path);

// Points with optional normals (point-cloud CSV files, docs/formats.md "Point clouds").
//   points   #P by 3
//   normals  #P by 3 when the header names the normal columns nx, ny, nz (or normal_x,
//            normal_y, normal_z; all three or none), else 0 by 3; values as read (finite, not
//            normalised)
struct PointsAndNormals {
  Eigen::MatrixX3d points, normals;
};

// read_points_csv that also reads the normal columns; same errors, and "PATH:LINE: header names
// only some of the normal columns nx, ny, nz: give all three or none".
PointsAndNormals read_points_normals_csv(const std::string& path);
PointsAndNormals parse_points_normals_csv(std::string_view text, const std::string& path);

} // namespace interlin
