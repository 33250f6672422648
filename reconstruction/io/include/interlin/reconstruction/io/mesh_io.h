#pragma once
// Triangle mesh files through OpenMesh: .stl (binary), .obj, .ply (binary little-endian), .off.

#include <Eigen/Core>
#include <string>

namespace interlin {

// Writes the mesh in the format named by the extension of `path` (case-insensitive): .stl binary
// STL, .obj Wavefront OBJ, .ply binary little-endian PLY, .off ASCII OFF. The file is written
// atomically (a temporary file beside it, renamed on success).
// Precision: OpenMesh 9 hands every writer single-precision points, so coordinates are stored
// rounded to float (relative error <= 2^-24) in every format; ASCII formats print enough digits
// to recover that float exactly.
// Inputs:
//   path  output file
//   V     #V by 3 vertex positions
//   F     #F by 3 vertex indices (0-based, in [0, #V)); written as given, no connectivity needed
// Throws std::invalid_argument for an unknown extension (the message lists the supported ones) or
// inconsistent V/F, std::runtime_error naming the path when writing fails (no file is left).
void write_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Reads a triangle mesh (any format OpenMesh reads; polygons are triangulated). STL stores
// no shared vertices: vertices with equal positions are merged, so #V and the vertex order may
// differ from what was written while the faces keep their order and corner order.
// Inputs:  path
// Outputs: V #V by 3, F #F by 3
// Throws std::runtime_error naming the path when the file cannot be read.
void read_mesh(const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F);

} // namespace interlin
