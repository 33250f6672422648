#pragma once
// The background tetrahedra clipped at F = 0 (marching tetrahedra on the volume): a boundary for
// seed 003's solid elements that needs no projection, so thin walls, touching parts and concave
// creases cannot fold it over.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>

namespace interlin {

struct CutTetrahedra {
  Eigen::MatrixXd V;  // #V by 3: the used grid nodes (grid order), then the cut points
  Eigen::MatrixXi C;  // #C by 4 positive tetrahedra
  long whole = 0;     // background tetrahedra kept whole (the first rows of C)
  long cut_nodes = 0; // nodes on F = 0 found on grid edges (the last rows of V)
  long warped = 0;    // grid nodes moved onto a cut point of one of their edges
};

// Every Kuhn tetrahedron of the grid (6 per cube, as boundary_mesh) is intersected with the body:
// nodes are inside (S > epsilon), on the surface (|S| <= epsilon) or outside; each edge from an
// inside to an outside node is cut at the root of F (roots_on_segments, one point per edge, shared
// by the tetrahedra around it). The inside part of a tetrahedron with 1, 2 or 3 inside-or-surface
// nodes is a tetrahedron or a prism; prisms are split into 3 tetrahedra along the quadrilateral
// diagonals from their smallest global index (Dompierre et al., so neighbours agree), pieces with a
// repeated node (a surface node's edges are not cut) are dropped. With the cut points at the roots
// of the linear interpolant every piece is convex and every tetrahedron positive; at the roots of
// F they stay positive unless F bends by more than the cell over a cell (measured by the caller).
// Inputs:  f (value), g, S #g nodes sampled values (sample_grid), epsilon >= 0, threads (0: all)
// Output:  the mesh; its boundary facets are boundary_facets(C) and every node on them is on F = 0
//          (a cut point or a surface node), unless the body leaves the grid's box
CutTetrahedra cut_tetrahedra(const ImplicitFunction& f, const RegularGrid& g,
                             const Eigen::VectorXd& S, double epsilon, int threads = 0);

} // namespace interlin
