#pragma once
// Hexahedra dual to the grid's inside nodes (Zhang & Bajaj 2006, "Adaptive and quality
// quadrilateral/hexahedral meshing from volumetric data", §3: one hexahedron per inside grid
// point, its corners the points of the 8 cells around it): a boundary for seed 003's solid
// elements that keeps walls one node layer thick, each side of the wall on its own cells' points.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>
#include <vector>

namespace interlin {

struct DualHexahedra {
  Eigen::MatrixXd V;          // #V by 3: one point per cell of g with an inside node (cell order)
  Eigen::MatrixXi C;          // #C by 8 hexahedra (VTK order, positive), one per inside node
  std::vector<char> boundary; // #V: the cell also has a node that is not inside (its point is
                              // meant to lie on F = 0)
  std::vector<char> held;     // #V: boundary points held short of F = 0 so that no element folds,
                              // or whose projection found no root
  long unprojected = 0;       // boundary points whose projection found no root near the cell
  long held_points = 0;       // boundary points held (unprojected ones not counted)
};

// Steps: (1) inside nodes are S > epsilon; nodes on the grid's outer layer are skipped (pad the
// grid by a cell); (2) every cell with an inside node gets a point: its centre when all 8 nodes
// are inside, else the mean of the roots of the linear interpolant on its edges from an inside to
// an outside node, projected onto F = 0 along -grad F (project_along; kept at the mean when no root
// lies within a cell); a wall one node layer thick thus gets its top points from the cells above
// it and its bottom points from those below; (3) each inside node's hexahedron has the points of
// its 8 cells as corners; (4) while an element has a corner whose scaled Jacobian (corner_alphas
// over the edge lengths) is below 0.2, its boundary points go halfway back towards their cells'
// centres (after 10 rounds all the way: the centres make the grid's dual cubes, so the loop ends
// with every corner at 0.2 or better); (5) each held point in turn (3 sweeps) goes back towards
// F = 0 as far as (1, 3/4, 1/2, 1/4 of the way) keeps the elements around it at 0.2; (6) each
// point still held is projected onto F = 0 from where it stands (along -grad F, within a cell)
// and kept there when the elements around it stay at 0.2. Without a buffer layer (pillowing) a
// hexahedron at an oblique surface has several corners on F = 0 and needs holding: 10-17 % of
// the boundary points end short of F = 0 on the benchmark models (36-52 % without step 5, 11-18 %
// without step 6; VolumeMeshInfo::held; docs/benchmarks.md).
// Inputs:  f (value; gradient when available), g, S #g nodes (sample_grid), epsilon >= 0,
//          threads (0: all cores)
// Output:  the mesh; its boundary facets are boundary_facets(C)
// See also: volume_mesh (VolumeBoundary::dual), cut_tetrahedra
DualHexahedra dual_hexahedra(const ImplicitFunction& f, const RegularGrid& g,
                             const Eigen::VectorXd& S, double epsilon, int threads = 0);

struct PillowedHexahedra {
  Eigen::MatrixXd V;          // #V by 3: one core point per cell of g with an inside node (cell
                              // order), then the surface points
  Eigen::MatrixXi C;          // #C by 8 hexahedra (VTK order): the core (one per inside node),
                              // then the pillow layer (one per inside-outside grid edge)
  std::vector<char> boundary; // #V: a surface point (the pillow layer's top)
  std::vector<char> missed;   // #V: a surface point whose projection found no root (left at the
                              // linear roots' mean: the box, or features thinner than the grid)
  long core = 0;              // core hexahedra (the first rows of C)
  long split = 0;             // cells with more than one surface point (one per side)
  long trimmed = 0;           // inside nodes left out of the core to make it manifold
};

// Dual hexahedra with a buffer layer (pillowing; Mitchell & Tautges 1995, "Pillowing doublets:
// refining a mesh to ensure that faces share at most one edge", and the boundary layer of Zhang &
// Bajaj 2006 §3): a core of dual hexahedra none of whose points is on F = 0, and one hexahedron
// between each boundary quadrilateral of the core and its image on F = 0, so every boundary node
// is a surface point and no element has more than one face on the surface.
// Steps: (1) inside nodes are S > epsilon, the grid's outer layer excluded (pad the grid by a
// cell); the core is made manifold where the pillows need it: two inside nodes at opposite
// corners of a grid square whose outside corners are joined around a cube on it, or the only two
// inside corners of a cube, opposite ones, have dual hexahedra meeting along an edge or at a point
// only, under one surface point over core faces facing opposite ways (no valid pillow); the one
// with the smaller S leaves the core (in passes; its neighbours' pillows reach F = 0 past it);
// (2) in every cell with an inside node, the outside corners fall into components connected
// along the cell's edges: one side of the surface each (a wall one node layer thick, or two sheets
// of the core meeting at the cell's point, gives two); each component's surface point is the mean
// of the linear roots on the edges from inside corners to it, projected onto F = 0 along those
// edges' mean direction, else along -grad F (project_along, within a cell, then two; kept on the
// component's side of its inside corners; a last try along -grad F on either side); (3) the cell's
// core point: its centre when all 8 nodes are inside, else halfway from the mean of its inside
// nodes to the mean of its surface points; (4) each inside node's core hexahedron has the core
// points of its 8 cells as corners; (5) each grid edge from an inside node n to an outside node m
// gets the pillow hexahedron between the core face dual to it (the core points of the 4 cells
// around the edge) and those cells' surface points of m's component. Conforming: neighbouring
// pillows of one side share their surface points. The caller untangles and smooths the core points
// (interior nodes; volume_mesh, VolumeBoundary::pillow). Inputs:  f (value; gradient when
// available), g, S #g nodes (sample_grid), epsilon >= 0,
//          threads (0: all cores)
// Output:  the mesh (its elements may be inverted before smoothing); boundary_facets(C) are the
//          pillows' tops
// See also: dual_hexahedra, volume_mesh
PillowedHexahedra pillowed_hexahedra(const ImplicitFunction& f, const RegularGrid& g,
                                     const Eigen::VectorXd& S, double epsilon, int threads = 0);

} // namespace interlin
