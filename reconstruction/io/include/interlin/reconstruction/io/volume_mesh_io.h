#pragma once
// Tetrahedral and hexahedral meshes for analysis: VTK XML unstructured grid (.vtu, ParaView),
// Gmsh MSH 4.1 (.msh) and Abaqus / CalculiX input (.inp).

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace interlin {

// Named scalar fields written to .vtu (point and cell data); the other formats ignore them.
struct VolumeMeshFields {
  std::vector<std::pair<std::string, Eigen::VectorXd>> node;    // #V values each
  std::vector<std::pair<std::string, Eigen::VectorXd>> element; // #C values each
};

// Writes the mesh in the format named by the extension of `path` (case-insensitive), atomically
// (a temporary file renamed on success). Coordinates are exact: the shortest decimal that reads
// back to the same double (.msh), binary doubles (.vtu); in .inp the same where it fits
// CalculiX's 20-character fields, else as many digits as fit (numbers with an exponent: at
// least 14 significant digits).
//   .vtu  VTK XML UnstructuredGrid 1.0, little-endian appended raw data (UInt64 headers): points
//         Float64, cells VTK_TETRA (10) or VTK_HEXAHEDRON (12), the boundary facets are not
//         cells; point data "boundary" (1 on the boundary surface) and the given fields.
//   .msh  Gmsh MSH 4.1 ASCII: volume entity 1 (physical group 2 "solid") with the elements
//         (type 4 tetrahedron or 5 hexahedron) and the interior nodes, surface entity 1
//         (physical group 1 "boundary") with the facets (type 2 triangle or 3 quadrangle) and
//         the boundary nodes; node and element tags 1-based, nodes in mesh order.
//   .inp  Abaqus / CalculiX: *NODE, *ELEMENT TYPE=C3D4 or C3D8 ELSET=SOLID, *NSET BOUNDARY (the
//         nodes of the facets), *SURFACE NAME=BOUNDARY TYPE=ELEMENT (element, face S1..S6 of
//         every boundary facet) for loads and contact.
// Element node order is the one of VTK, Gmsh and Abaqus alike: tetrahedra with
// (p1 - p0) x (p2 - p0) . (p3 - p0) > 0, hexahedra with face 0-1-2-3 counter-clockwise seen from
// face 4-5-6-7 and node 4 + j above node j.
// Inputs:
//   V  #V by 3 nodes
//   C  #C by 4 tetrahedra or #C by 8 hexahedra (0-based)
//   B  #B by 3 or #B by 4 boundary facets (faces of the elements, outward), may be empty
//   fields  optional .vtu data
// Throws std::invalid_argument for an unknown extension, inconsistent sizes or indices out of
// range, std::runtime_error naming the path when writing fails (no file is left).
void write_volume_mesh(const std::string& path, const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                       const Eigen::MatrixXi& B, const VolumeMeshFields& fields = {});

// True for the extensions write_volume_mesh handles (.vtu .msh .inp, any case).
bool is_volume_mesh_path(const std::string& path);

} // namespace interlin
