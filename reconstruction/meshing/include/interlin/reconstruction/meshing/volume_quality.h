#pragma once
// Shape quality of tetrahedral and hexahedral meshes: the figures finite-element users check
// before an analysis (the definitions of the Verdict library / Knupp's metrics).

#include <Eigen/Core>
#include <vector>

namespace interlin {

struct ElementQuality {
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  // Tetrahedra: 6 V sqrt(2) / (largest product of the three edge lengths at a corner): 1 for the
  // regular tetrahedron. Hexahedra: the smallest, over the 8 corners and the centre, of the
  // determinant of the unit edge (or principal axis) vectors: 1 for a cube. <= 0: inverted.
  double scaled_jacobian = 0;
  // Tetrahedra: 3 r_in / R_circumscribed (1 regular, 0 flat). Hexahedra: not defined (no
  // inscribed and circumscribed spheres of a general hexahedron): NaN.
  double radius_ratio = 0;
  double volume = 0;     // signed; hexahedra: the trilinear element's exact volume
  bool inverted = false; // some corner's alpha (triple product of its edges) <= 0, or
                         // (hexahedra) the Jacobian at the centre <= 0
};

// One element. Inputs: P 4 by 3 (tetrahedron, (p1 - p0) x (p2 - p0) . (p3 - p0) > 0 when valid)
// or 8 by 3 (hexahedron, VTK order).
ElementQuality element_quality(const Eigen::MatrixXd& P);

struct VolumeQuality {
  long elements = 0, inverted = 0;
  double volume = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  double min_scaled_jacobian = 0, mean_scaled_jacobian = 0;
  double min_radius_ratio = 0, mean_radius_ratio = 0; // NaN for hexahedra
  // Elements with a dihedral angle outside [10, 170] degrees (a common acceptance window of FE
  // codes: elements outside it stiffen or ill-condition the stiffness matrix).
  long outside_10_170 = 0;
};

// All elements; per-element figures optional.
// Inputs:  V #V by 3, C #C by 4 or #C by 8 (std::invalid_argument otherwise or for indices out of
//          range); threads (0: all cores)
// Outputs: the summary; per_element optional, #C entries
VolumeQuality volume_quality(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C, int threads = 0,
                             std::vector<ElementQuality>* per_element = nullptr);

} // namespace interlin
