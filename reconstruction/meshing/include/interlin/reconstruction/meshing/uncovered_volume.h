#pragma once
// How much of the body {F > 0} a volume mesh leaves out: the projected boundary layer of seed 003
// (digest §6.2) stands on inner cells, so walls too thin to hold one are lost; this measures them
// on the grid's tetrahedra clipped at F = 0 (cut_tetrahedra, the default tetrahedral mesh's
// boundary), the body as the grid resolves it.

#include "interlin/reconstruction/meshing/cut_tetrahedra.h"
#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>

#include <utility>
#include <vector>

namespace interlin {

struct UncoveredVolume {
  double body = 0;      // volume of the clipped tetrahedra (the body on this grid)
  double lost = 0;      // of it, the pieces whose centroid lies in no element of the mesh
  double lost_area = 0; // area of F = 0 (the clipped tetrahedra's boundary) bounding those pieces
  // Mean thickness of the lost walls, 2 lost / lost_area (a sheet has two faces; 0: none lost).
  double thickness() const { return lost_area > 0 ? 2 * lost / lost_area : 0; }
  // The lost volume by local wall thickness, thinnest first: (thickness, volume) per background
  // cube holding lost pieces, the thickness 2 V / A of the body's volume V and boundary area A
  // within kThicknessReach cubes of it along each axis (infinite with no boundary there). A wall's
  // own thickness, not that of its lost part (which partial cover thins), and local: a tapering
  // wall is thin at its edge and thick at its root.
  std::vector<std::pair<double, double>> lost_by_thickness;
};

// Cubes along each axis either side of a cube whose body volume and area give its local
// thickness: lost walls are up to about 6 cells thick, 4 either side spans them (3 overestimated
// shells 4 cells thick by 15 %, which then counted as edges).
constexpr int kThicknessReach = 4;

// The largest cell h' (of h 2^(-k / 32), k >= 1; at most 8 halvings) whose predicted loss is within
// `budget`: the lost walls thinner than kept_wall_cells h stay lost while thinner than
// cells_across_wall h'; what was lost from thicker walls (sharp edges, held nodes) shrinks as
// h' / h (slower than measured: discs' rims lose h^1 .. h^2). 0 when u.lost is within budget.
// Inputs: u (uncovered_volume at cell h), budget (volume), the two wall rules in cells.
double cell_keeping(const UncoveredVolume& u, double h, double budget, double cells_across_wall,
                    double kept_wall_cells);

// Each piece of `body` (a convex tetrahedron inside a background cube of g) is lost when no
// element of (V, C) contains its centroid: elements are bucketed by the cubes their bounding boxes
// overlap; a tetrahedron contains a point when no barycentric coordinate is below -1e-9, a
// hexahedron when one of its 6 tetrahedra around the diagonal 0-6 does (exact for planar faces;
// curved faces of neighbours may leave slivers, small against a cube).
// Inputs:  body (cut_tetrahedra on g), g, V #V by 3, C #C by 4 (tetrahedra) or #C by 8 (hexahedra,
//          VTK order), threads (0: all cores)
// Output:  the body's volume, the lost volume, the area of F = 0 around it and the lost volume by
//          local wall thickness
// See also: volume_mesh (VolumeMeshInfo::coverage), cut_tetrahedra
UncoveredVolume uncovered_volume(const CutTetrahedra& body, const RegularGrid& g,
                                 const Eigen::MatrixXd& V, const Eigen::MatrixXi& C,
                                 int threads = 0);

} // namespace interlin
