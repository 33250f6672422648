#pragma once
// Internal: the mesh formats interlin writes and reads itself because OpenMesh 9 converts every
// coordinate to float on the way in and out: PLY (binary little-endian, double or float vertex
// properties; any PLY on reading) and Wavefront OBJ (shortest decimals that read back exactly).
// See mesh_io.h for the public entry points and docs/formats.md "Mesh files".

#include <Eigen/Core>
#include <iosfwd>
#include <string>
#include <string_view>

namespace interlin::detail {

// PLY: header "format binary_little_endian 1.0", vertex x, y, z as `double` (or `float` when
// !double_precision), faces as "list uchar int vertex_indices".
void write_ply(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
               bool double_precision);

// OBJ: "v x y z" lines with the shortest decimals that read back to the same double (float
// when !double_precision), then "f a b c" lines (1-based).
void write_obj(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
               bool double_precision);

// Any PLY file (ascii, binary little- or big-endian; vertex x, y, z of any scalar type, faces
// from the list property vertex_indices or vertex_index; other elements and properties
// skipped; polygons split into fans). Element counts are checked against the bytes that are
// left before anything is allocated. Throws InputError "PATH:LINE: ..." (header lines) or
// "PATH: ..." (data).
void parse_ply(std::string_view text, const std::string& path, Eigen::MatrixXd& V,
               Eigen::MatrixXi& F);

// OBJ: "v" and "f" lines (f a, a/t, a/t/n, a//n; negative indices count back from the last
// vertex); polygons split into fans; other lines ignored. Throws InputError "PATH:LINE: ...".
void parse_obj(std::string_view text, const std::string& path, Eigen::MatrixXd& V,
               Eigen::MatrixXi& F);

} // namespace interlin::detail
