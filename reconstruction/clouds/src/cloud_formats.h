#pragma once
// Private to read_point_cloud: the readers of each format and the PCL decoder of binary payloads.

#include "interlin/reconstruction/clouds/point_cloud.h"

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace interlin::detail {

// Collects the points and (when `with_normals`) normals of a file as rows arrive.
struct CloudRows {
  std::vector<double> xyz, n; // 3 per point
  bool with_normals = false;
  void add(const double* p, const double* q) {
    xyz.insert(xyz.end(), p, p + 3);
    if (with_normals)
      n.insert(n.end(), q, q + 3);
  }
  Eigen::Index size() const { return static_cast<Eigen::Index>(xyz.size() / 3); }
};

// Each reader gets the whole file as `text` and throws InputError lines naming `path`.
void read_pcd(const std::string& path, std::string_view text, CloudRows& rows,
              std::vector<std::string>& notes);
void read_ply(const std::string& path, std::string_view text, CloudRows& rows,
              std::vector<std::string>& notes);
void read_xyz(const std::string& path, std::string_view text, bool normals_expected,
              CloudRows& rows, std::vector<std::string>& notes);

// Decodes the binary payload of a validated .pcd or .ply file with PCL and returns the named
// fields (PCL's names: x, y, z, normal_x, ...) as columns of doubles, one row per point in file
// order. Throws InputError "PATH: ..." when PCL rejects the file or a field is missing.
Eigen::MatrixXd pcl_binary_fields(const std::string& path, bool ply,
                                  const std::vector<std::string>& names);

// Bytes a binary payload of `points` records of `record` bytes needs, and the InputError on line
// `line` when the file holds fewer (the header's counts are never trusted for allocation).
void require_payload(const std::string& path, long line, const std::string& what, double points,
                     double record, std::size_t available);

} // namespace interlin::detail
