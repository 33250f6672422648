#pragma once
// The background tetrahedra clipped at F = 0 (marching tetrahedra on the volume): a boundary for
// seed 003's solid elements that needs no projection, so thin walls, touching parts and concave
// creases cannot fold it over.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>
#include <stdexcept>
#include <string>

namespace interlin {

// The background tetrahedra: kuhn, the 6 Kuhn tetrahedra of each cube (as boundary_mesh); bcc, the
// body-centred cubic lattice of the grid nodes and the cube centres (Labelle & Shewchuk 2007,
// "Isosurface Stuffing"): 4 tetrahedra per face shared by two cubes, each spanning the two cube
// centres and an edge of the face, every dihedral angle 60 or 90 degrees (Kuhn: 45 to 90).
enum class Lattice { kuhn, bcc };

// The lattice's name as the CLI and the Python module spell it, and back (std::invalid_argument
// for another name).
inline const char* lattice_name(Lattice l) {
  return l == Lattice::kuhn ? "kuhn" : "bcc";
}
inline Lattice lattice_named(const std::string& name) {
  for (Lattice l : {Lattice::kuhn, Lattice::bcc})
    if (name == lattice_name(l))
      return l;
  throw std::invalid_argument("unknown lattice '" + name + "'");
}

// The cube centres of g as a grid (origin + spacing / 2, one node fewer along each axis): the
// second half of the BCC lattice's nodes.
inline RegularGrid cube_centres(const RegularGrid& g) {
  RegularGrid c = g;
  c.origin += g.spacing / 2;
  c.nodes -= 1;
  return c;
}

struct CutTetrahedra {
  Eigen::MatrixXd V;  // #V by 3: the used lattice nodes (grid order, then the cube centres in
                      // theirs), then the cut points
  Eigen::MatrixXi C;  // #C by 4 positive tetrahedra
  long whole = 0;     // background tetrahedra kept whole (the first rows of C)
  long cut_nodes = 0; // nodes on F = 0 found on lattice edges (the last rows of V)
  long warped = 0;    // lattice nodes moved onto a cut point of one of their edges
};

// Every background tetrahedron of the lattice (Kuhn or BCC) is intersected with the body:
// nodes are inside (S > epsilon), on the surface (|S| <= epsilon) or outside; each edge from an
// inside to an outside node is cut at the root of F (roots_on_segments, one point per edge, shared
// by the tetrahedra around it). The inside part of a tetrahedron with 1, 2 or 3 inside-or-surface
// nodes is a tetrahedron or a prism; prisms are split into 3 tetrahedra along the quadrilateral
// diagonals from their smallest global index (Dompierre et al., so neighbours agree), pieces with a
// repeated node (a surface node's edges are not cut) are dropped. With the cut points at the roots
// of the linear interpolant every piece is convex and every tetrahedron positive; at the roots of
// F they stay positive unless F bends by more than the cell over a cell (measured by the caller).
// Nodes within alpha of an edge's length from its cut point are warped onto it (isosurface
// stuffing): Kuhn alpha 0.2; BCC the paper's alpha_long 0.24999 (edges of length h) and
// alpha_short 0.41189 (centre-corner edges, sqrt(3) h / 2), for dihedral angles in [10.7, 164.8]
// degrees where the surface is flat on the lattice scale. The BCC lattice covers the cubes whose
// 6 neighbours are in g (pad g by a cell to mesh all of its box).
// Inputs:  f (value), g, S sampled values (sample_grid): #g nodes (kuhn), or #g nodes then
//          #cube_centres(g) nodes (bcc), epsilon >= 0, threads (0: all), lattice
// Output:  the mesh; its boundary facets are boundary_facets(C) and every node on them is on F = 0
//          (a cut point or a surface node), unless the body leaves the grid's box
CutTetrahedra cut_tetrahedra(const ImplicitFunction& f, const RegularGrid& g,
                             const Eigen::VectorXd& S, double epsilon, int threads = 0,
                             Lattice lattice = Lattice::kuhn);

} // namespace interlin
