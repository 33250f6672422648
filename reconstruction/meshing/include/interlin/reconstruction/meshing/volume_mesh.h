#pragma once
// Implicit solid -> tetrahedral or hexahedral finite-element mesh: seed 003's solid-element method
// (digest §6.2): the background cells inside the body, a boundary layer of elements between the
// inner cells' boundary facets and their projections onto F = 0, then the seed's smoothing
// functionals: (12) over the boundary surface (optional) and (13)-(15) over the interior nodes.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/cut_tetrahedra.h"
#include "interlin/reconstruction/meshing/regular_grid.h"
#include "interlin/reconstruction/meshing/uncovered_volume.h"
#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cfloat>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

enum class VolumeElements { tetrahedra, hexahedra };

// How the mesh meets F = 0. cut (default): tetrahedra: the grid's tetrahedra clipped at the roots
// of F on their edges (cut_tetrahedra; no inverted element by construction, thin walls down to a
// node layer kept); hexahedra: pillow, on the grid offset by half, then a quarter of a cell
// where pillows stay folded, or dual where those fold too or lose walls. projected: seed 003's
// layer of prisms (hexahedra) between the inner cells' boundary facets and their copies
// projected onto F = 0 (where a wall is thinner than about 4 cells or parts touch it would
// invert elements: those nodes are held short of F = 0, VolumeMeshInfo::held, and walls without
// inner cells are lost). dual (hexahedra only): one
// hexahedron per inside grid node, its corners the points of the 8 cells around it, on F = 0 for
// cells cut by the surface (dual_hexahedra, Zhang & Bajaj 2006): walls down to one node layer
// keep their volume, each side on its own cells' points. pillow (hexahedra only): the dual
// hexahedra as a core inside the body and one layer of hexahedra between its boundary and F = 0
// (pillowed_hexahedra; the core made manifold, the surface points split by side where a wall is
// one node layer thick): every boundary node on F = 0 but the few held short of it where a pillow
// stays folded after untangling (0-1 % on the shipped models at their benchmark cells, 3.8 % on
// the valve at 0.1, which still folds; docs/benchmarks.md).
enum class VolumeBoundary { cut, projected, dual, pillow };
inline constexpr VolumeBoundary kVolumeBoundaries[] = {
    VolumeBoundary::cut, VolumeBoundary::projected, VolumeBoundary::dual, VolumeBoundary::pillow};

// The boundary's name as the CLI and the Python module spell it: "cut", "projected", "dual",
// "pillow"; and back (std::invalid_argument for another name).
inline const char* boundary_name(VolumeBoundary b) {
  constexpr const char* kNames[] = {"cut", "projected", "dual", "pillow"};
  return kNames[int(b)];
}
inline VolumeBoundary boundary_named(const std::string& name) {
  for (VolumeBoundary b : kVolumeBoundaries)
    if (name == boundary_name(b))
      return b;
  throw std::invalid_argument("unknown volume boundary '" + name + "'");
}

struct VolumeMeshOptions {
  VolumeElements elements = VolumeElements::tetrahedra;
  // Tetrahedra: cut or projected. Hexahedra: cut (the default) means pillow; where the pillow
  // mesh keeps a folded element, pillow on the grid offset by half, then a quarter of a cell,
  // and dual where those keep one too (VolumeMeshInfo::boundary, folded_pillows, offset_grid); or
  // projected, dual or pillow.
  VolumeBoundary boundary = VolumeBoundary::cut;
  // Tetrahedra with the cut boundary: the background lattice clipped (cut_tetrahedra). bcc: the
  // BCC lattice on the grid padded by a cell (isosurface stuffing; dihedral angles 60/90 degrees
  // before the cut); kuhn: the grid's Kuhn tetrahedra (45/60/90 before the cut).
  Lattice lattice = Lattice::bcc;
  Eigen::AlignedBox3d box; // region (the grid covers it); empty: the function's own box
  int resolution = 64;     // cells along the box's longest side (grid_with_resolution) ...
  double cell = 0;         // ... unless a cell size h > 0 is given (grid_with_cell)
  // Inside test of the grid nodes (seed 003: strict F > epsilon in its code and tetrahedral
  // example, inclusive F >= -epsilon in its hexahedral example).
  ZeroRule rule = ZeroRule::strict;
  double epsilon = 1000 * DBL_EPSILON;
  // Inside nodes nearer to F = 0 than margin x h (F changes sign within margin x h down the
  // gradient) count as outside, so that no boundary-layer element is thinner than about margin x h
  // (the seed's rule, margin 0, makes zero-thickness layer elements wherever a node lies on or next
  // to the surface).
  double margin = 0.35;
  int surface_sweeps = 0; // sweeps of functional (12) over the boundary nodes (seed: >= 4
                          // captures sharp edges; about 3000 evaluations per node and sweep)
  // Sweeps of functional (15) over the interior nodes (seed: 8-10); -1: interior_sweeps_of's
  // default.
  int interior_sweeps = -1;
  int threads = 0;                                  // 0: all cores
  std::function<void(const std::string&)> progress; // stage messages
};

// The interior sweeps o asks for: o.interior_sweeps, or by default 8, but none for tetrahedra cut
// from the BCC lattice: functional (15) favours right-angled corners and only distorts them
// (impeller at cell 0.25: min dihedral 19.4 -> 9.4 degrees, 0 -> 16 elements outside [10, 170];
// car at 0.3: 4 -> 71; docs/benchmarks.md, "Tetrahedra on the BCC lattice").
inline int interior_sweeps_of(const VolumeMeshOptions& o) {
  const bool bcc = o.elements == VolumeElements::tetrahedra && o.boundary == VolumeBoundary::cut &&
                   o.lattice == Lattice::bcc;
  return o.interior_sweeps >= 0 ? o.interior_sweeps : bcc ? 0 : 8;
}

struct VolumeMesh {
  Eigen::MatrixXd V;          // #V by 3 nodes
  Eigen::MatrixXi C;          // #C by 4 tetrahedra ((p1 - p0) x (p2 - p0) . (p3 - p0) > 0) or
                              // #C by 8 hexahedra (VTK order), 0-based
  Eigen::MatrixXi B;          // #B by 3 or 4 boundary facets, counter-clockwise from outside
  std::vector<char> boundary; // #V: node lies on the boundary surface (projected onto F = 0)
};

struct VolumeMeshInfo {
  RegularGrid grid;
  VolumeBoundary boundary = VolumeBoundary::cut; // the boundary the mesh has (default hexahedra:
                                                 // pillow or dual)
  long folded_pillows = 0; // default hexahedra: the pillow mesh's elements folded at a corner or
                           // at the centre (scaled Jacobian <= 0), for which it was meshed again
                           // on the grid offset by half, then a quarter of a cell (offset_grid),
                           // or, where pillows fold there too, replaced by the dual one (0:
                           // pillows kept)
  double offset_grid = 0;  // default hexahedra: pillows on the grid offset by this fraction of a
                           // cell towards -x, -y, -z (0.5 or 0.25; 0: on the grid)
  long inside_nodes = 0;   // grid nodes inside by the rule
  long dropped_nodes = 0;  // of those, nearer to F = 0 than the margin (pillow: left out of the
                           // core to make it manifold)
  long removed_cells = 0;  // background cells removed by the touching-configuration cleanup and
                           // (margin > 0) where the inner cells were one cell thin
  long inner_cells = 0;    // background cells kept (the elements copied unchanged)
  long layer_elements = 0; // boundary-layer elements (facets, or 3 tetrahedra per facet; cut:
                           // the pieces of the cut background tetrahedra)
  long unprojected = 0;    // boundary nodes whose projection found no sign change (cut: 0)
  long held = 0;           // projected layer: boundary nodes held short of F = 0 so that no
                           // element folds (cut: 0)
  // Boundary nodes on F = 0: neither held nor unprojected, and |F| <= 1e-6 h |grad F| there (the
  // nodes on the box faces where the body reaches the box are not); max_boundary_f is the largest
  // |F| over them (0 when there is none).
  long on_zero = 0;
  double max_boundary_f = 0;
  long clipped = 0; // outer grid nodes where the body reaches the box (reaches_box): the mesh is
                    // cut by the box there, its boundary nodes on the box faces off F = 0
  VolumeSmoothingReport smoothing;
  // Projected layer: the body's volume on this grid and the part of it no element covers (walls
  // with no inner cell under the layer; uncovered_volume). cut: not measured (all 0; the mesh is
  // the clipped grid).
  UncoveredVolume coverage;
  // Where more than kLostVolumeWarning is lost: a cell at which the loss is predicted within it
  // (projected layer: cell_keeping with kCellsAcrossWall and kKeptWallCells on the lost walls'
  // local thickness; dual: coverage.thickness() / kCellsAcrossDualWall). 0: nothing to suggest.
  double suggested_cell = 0;
  // The fraction of the body's volume left out (0 when not measured).
  double lost_fraction() const { return coverage.body > 0 ? coverage.lost / coverage.body : 0; }
};

// The lost fraction above which the CLI and Python warn: the volume target of issue 14 (0.5 %).
constexpr double kLostVolumeWarning = 0.005;

// Cells across a wall (its local thickness, UncoveredVolume::lost_by_thickness) for the projected
// layer to keep it (default margin): two inner cells stacked along the worst direction span
// (sqrt 3 + 1 / sqrt 3) h, each face gives up 0.35 h, plus up to a cell for the grid's offset;
// measured on spherical shells (every orientation; radius 0.25 and 0.4, T = 0.06 and 0.1): 28-35 %
// lost at T / 4 (0 on one), nothing at T / 4.5 (test_uncovered_volume.cpp, docs/benchmarks.md).
constexpr double kCellsAcrossWall = 4.5;

// Walls at least this many cells thick lose nothing to the missing inner cells (shells: nothing
// lost from 4.5 cells on); what they lose is at sharp edges and under held nodes, which shrink
// with the cell (cell_keeping). 5.5: at 6 the car's walls 4.5-6 cells thick counted as edges and
// the suggestion lost 0.63-0.71 %; at 5 shells 4 cells thick counted as edges (5.7x too fine).
constexpr double kKeptWallCells = 5.5;

// The same for dual hexahedra: a slab thicker than a cell holds a layer of grid nodes in any
// orientation, which the dual mesh keeps; 2 leaves a cell of room. Their coverage also counts the
// slivers under boundary points held short of F = 0, which shrink about as h (a spherical shell:
// 0.65, 0.41, 0.22 % at cells 0.05, 0.03, 0.015; docs/benchmarks.md).
constexpr double kCellsAcrossDualWall = 2;

// Steps (digest §6.2): (1) grid over the box (cubic cells, o.resolution or o.cell), F sampled at
// the nodes in parallel; (2) inside nodes by o.rule, minus those within the margin; background
// cells (cubes, or each cube's 6 Kuhn tetrahedra) with all nodes inside survive, touching
// configurations are removed (boundary_mesh); (3) every boundary node gets a copy projected onto
// F = 0 along its smoothed normal (project_boundary_nodes); each boundary facet and its projected
// copy make one hexahedron, or a prism split into 3 tetrahedra by the minimum-global-index rule
// (Dompierre et al.; neighbouring prisms agree on their shared quadrilaterals); (4)
// o.surface_sweeps of functional (12) on the boundary surface (smooth_on_surface; quadrilaterals
// split along their shorter diagonal), the nodes of folded layer elements held short of F = 0
// (towards their inner nodes, or above their bottom facets), then o.interior_sweeps of (15) with
// the boundary fixed (smooth_volume); (5) the projected layer's coverage of the body
// (uncovered_volume on cut_tetrahedra of the same grid, VolumeMeshInfo::coverage). Tetrahedra with
// o.boundary == cut (the default) replace steps (2)-(3) by cut_tetrahedra (inside nodes by F >
// epsilon, nodes on internal zero sheets inside; the boundary nodes are roots of F on grid edges,
// warped grid nodes among them) and keep their boundary fixed in step (4); every smoothing step
// only accepts node moves that fold no further element corner. The seed's published configurations
// (projected layer, margin 0, tetrahedra with the strict rule, hexahedra with the inclusive one)
// give its counts: 2158 boundary nodes and 4332 facets, 3064 and 3072. Hexahedra with o.boundary ==
// dual or pillow replace steps (2)-(3) by dual_hexahedra or pillowed_hexahedra (the latter
// untangled before step (4): core points free, surface points sliding on F = 0); by default
// (o.boundary == cut) hexahedra are pillowed, on the grid offset by half, then a quarter of a
// cell when a pillow stays folded, and made dual instead when one folds there too (or those grids
// lose walls).
// Inputs:  f (value; gradient when
// available, else central differences, for the margin),
//          o (std::invalid_argument for no box, bad resolution/cell, margin outside [0, 1))
// Output:  the mesh; info optional
VolumeMesh volume_mesh(const ImplicitFunction& f, const VolumeMeshOptions& o = {},
                       VolumeMeshInfo* info = nullptr);

// The facets used by exactly one element, oriented outward (counter-clockwise seen from outside).
// Inputs:  C #C by 4 (positive tetrahedra) or #C by 8 (hexahedra, VTK order), threads (0: all
//          cores; the result does not depend on it)
// Output:  #B by 3 or #B by 4, in order of the elements
Eigen::MatrixXi boundary_facets(const Eigen::MatrixXi& C, int threads = 0);

} // namespace interlin
