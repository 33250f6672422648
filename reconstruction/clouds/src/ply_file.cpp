// PLY clouds: the vertices of any PLY file (reconstruction/io's PLY reader, shared with the mesh
// reader), with normals when the vertex element has nx ny nz or normal_x normal_y normal_z.
#include "cloud_formats.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/mesh_io.h"

#include <cmath>

namespace interlin::detail {

void read_ply(const std::string& path, std::string_view text, CloudRows& rows) {
  const std::vector<std::string> names{"x",  "y",        "z",        "nx",      "ny",
                                       "nz", "normal_x", "normal_y", "normal_z"};
  std::vector<bool> found;
  const Eigen::MatrixXd V = parse_ply_vertices(text, path, names, found);
  for (int c = 0; c < 3; ++c)
    if (!found[static_cast<size_t>(c)])
      throw_input_error(path, 0, "the vertex element lacks the property " + names[c]);
  // normals: nx ny nz, else normal_x normal_y normal_z (all three of one spelling)
  int n0 = -1;
  for (int s : {3, 6})
    if (n0 < 0 && found[s] && found[s + 1] && found[s + 2])
      n0 = s;
  rows.with_normals = n0 >= 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    double v[6] = {V(i, 0), V(i, 1), V(i, 2), 0, 0, 0};
    if (n0 >= 0)
      for (int c = 0; c < 3; ++c)
        v[3 + c] = V(i, n0 + c);
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(v[c]))
        throw_input_error(path, 0,
                          "vertex " + std::to_string(i) + " (binary data): " + names[c] +
                              " is not a finite value (NaN and infinity are not allowed)");
    rows.add(v, v + 3);
  }
}

} // namespace interlin::detail
