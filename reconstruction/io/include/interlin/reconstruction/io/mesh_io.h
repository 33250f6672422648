#pragma once
// Triangle mesh files: .ply (binary little-endian, double) and .obj (exact decimals) by interlin,
// .stl (binary) and .off through OpenMesh.

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace interlin {

// Coordinates in PLY and OBJ files: double (default; exact) or float (half the PLY vertex
// data). STL stores float by definition, OFF is written by OpenMesh in float.
enum class MeshPrecision { float64, float32 };

// Writes the mesh in the format named by the extension of `path` (case-insensitive): .ply binary
// little-endian PLY with `double` (or `float`) vertex properties, .obj Wavefront OBJ with the
// shortest decimals that read back to the same double (or float), .stl binary STL, .off ASCII
// OFF (both single precision, through OpenMesh, which hands its writers floats). The file is
// written atomically (a temporary file beside it, renamed on success). docs/formats.md "Mesh
// files" says which format carries what.
// Inputs:
//   path       output file
//   V          #V by 3 vertex positions
//   F          #F by 3 vertex indices (0-based, in [0, #V)); written as given, no connectivity
//              needed
//   precision  of the PLY and OBJ coordinates
// Throws std::invalid_argument for an unknown extension (the message lists the supported ones) or
// inconsistent V/F, std::runtime_error naming the path when writing fails (no file is left).
void write_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                MeshPrecision precision = MeshPrecision::float64);

// Reads a triangle mesh; polygons are split into fans. PLY (any: ASCII or binary, any scalar
// types; element counts checked against the file size) and OBJ are read by interlin and give
// back exactly what write_mesh wrote; other formats (STL, OFF, ...) go through OpenMesh, which
// reads float. STL stores no shared vertices: vertices with equal positions are merged, so #V
// and the vertex order may differ from what was written while the faces keep their order and
// corner order.
// Inputs:  path
// Outputs: V #V by 3, F #F by 3
// Throws InputError "PATH:LINE: ..." for a malformed PLY or OBJ file and for an unreadable
// file, std::runtime_error naming the path when OpenMesh cannot read it.
void read_mesh(const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F);

// read_mesh of PLY and OBJ from the file's content; `path` names the file in messages and its
// extension (.ply or .obj, else std::invalid_argument) the format.
void parse_mesh(std::string_view content, const std::string& path, Eigen::MatrixXd& V,
                Eigen::MatrixXi& F);

// The vertex element of a PLY file (any PLY parse_mesh reads: ASCII or binary of either byte
// order, counts checked against the file size, other elements skipped): the scalar properties
// `names` of every vertex, one column per name in file order of the vertices; found[c] tells
// whether the file has property names[c] (its column is 0 when not). Values as stored (not
// checked for finiteness in binary files; ASCII values must be finite numbers).
// Throws InputError "PATH:LINE: ..." (header, ASCII data) or "PATH: ..." (binary data).
// Used by the point-cloud reader (reconstruction/clouds).
Eigen::MatrixXd parse_ply_vertices(std::string_view text, const std::string& path,
                                   const std::vector<std::string>& names, std::vector<bool>& found);

} // namespace interlin
