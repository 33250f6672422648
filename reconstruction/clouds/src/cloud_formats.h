#pragma once
// Private to read_point_cloud: the parsers of each format and the decoding of binary values.

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

// Each parser gets the whole file as `text` and throws InputError lines naming `path`.
void read_pcd(const std::string& path, std::string_view text, CloudRows& rows,
              std::vector<std::string>& notes);
void read_ply(const std::string& path, std::string_view text, CloudRows& rows);
void read_xyz(const std::string& path, std::string_view text, bool normals_expected,
              CloudRows& rows, std::vector<std::string>& notes);

// The value of one binary field at p: `type` 'F' (float), 'I' (signed) or 'U' (unsigned) of
// `size` bytes (1, 2, 4, 8; floats 4 or 8), little-endian unless `big_endian`.
double binary_value(const char* p, char type, int size, bool big_endian = false);

// Bytes a binary payload of `points` records of `record` bytes needs, and the InputError on line
// `line` when the file holds fewer (the header's counts are never trusted for allocation).
void require_payload(const std::string& path, long line, const std::string& what, double points,
                     double record, std::size_t available);

} // namespace interlin::detail
