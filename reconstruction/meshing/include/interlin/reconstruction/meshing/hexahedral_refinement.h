#pragma once
// Seed 003's adaptive meshing (digest §7.2) for hexahedral meshes: 3-refinement by templates on
// the element's local 4 x 4 x 4 lattice, conforming by construction (transition templates, no
// hanging nodes).

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/adaptive_refinement.h"

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace interlin {

// The templates of a hexahedron by the set of its refined edges (an edge is trisected iff both its
// ends are refined nodes; seed 003, §7.2): none (unchanged), one edge (5 children: each face
// holding the edge split into the seed's 4-quadrilateral transition, the others unchanged), the 4
// edges of one face (13 children: that face 3 x 3, the 4 side faces 4-quadrilateral transitions,
// the opposite face unchanged) and all 12 (27 children). Any other set has no template.
enum class HexTemplate { none, edge, face, full, unsupported };

// The template of a hexahedron whose refined local vertices (VTK order) are the bits of `code`
// (the seed's 256-entry table indexed by the 8-bit refined-vertex code).
HexTemplate hex_template(unsigned code);

// The closure of a refined-node set (seed 003, §7.2: "codes with no template are handled by
// widening the refined-node set"): every hexahedron whose refined edges have no template gets
// more refined nodes, those of the face holding all its refined edges when there is one, else
// all 8, until every element has a template (terminates: nodes are only added).
// Inputs:  C #C by 8 hexahedra (VTK order)
// In/out:  refined #V flags (std::invalid_argument for a wrong size)
// Output:  the number of nodes added
long close_refined_nodes(const Eigen::MatrixXi& C, std::vector<char>& refined);

// 3-refinement of the hexahedra by given refined nodes, closed first (close_refined_nodes). New
// points are the trilinear map of their parent at its lattice points (thirds on the edges and
// faces); points on a shared edge or face are made once, keyed by the edge's or face's node ids,
// so the mesh stays conforming. New nodes on boundary facets (faces of one element whose nodes
// are all boundary nodes) are projected onto F = 0 when f has a value (gradient walk), each the
// largest fraction 1, 1/2, ..., 1/1024 of the way that folds none of its elements (held short
// otherwise, and counted). Children keep the parent's orientation: those a nearly flat parent's
// trilinear map folds are untangled (report.folded, still_folded), the new nodes of a sliver
// boundary face leaving F = 0 where they must.
// Inputs:
//   C        #C by 8 hexahedra, VTK order, positively oriented
//   refined  #V flags of the refined nodes (std::invalid_argument for a wrong size)
//   f        the body (for the projection; an empty value: new nodes stay on the trilinear map)
// In/out:
//   V        #V by 3 -> #V' by 3 (new nodes appended)
//   C        -> #C' by 8
//   boundary #V flags of nodes on F = 0 -> #V' (projected new nodes flagged)
//   values   #V nodal quantity -> #V' (new nodes: trilinear interpolation of the parent's)
// Output:    the counts (flagged: 0; refined_nodes after the closure, widened by it)
// max_elements > 0: std::length_error, before any change, when the split would make more.
RefinementReport split_hexahedra(Eigen::MatrixXd& V, Eigen::MatrixXi& C,
                                 std::vector<char>& boundary, Eigen::VectorXd& values,
                                 std::vector<char> refined, const ImplicitFunction& f = {},
                                 long max_elements = 0);

// One pass of seed 003's adaptive 3-refinement of hexahedra (§7.2 [C]): the elements with
// indicator > delta and every element sharing a vertex with one give the refined nodes
// (refined_nodes), then split_hexahedra.
// Inputs/outputs as split_hexahedra, with
//   values   #V nodal quantity (std::invalid_argument for a wrong size or non-finite values)
//   delta    threshold in [0, 1)
RefinementReport refine_hexahedra(Eigen::MatrixXd& V, Eigen::MatrixXi& C,
                                  std::vector<char>& boundary, Eigen::VectorXd& values,
                                  double delta, const ImplicitFunction& f = {},
                                  long max_elements = 0);

// Seed 003's adaptive loop on hexahedra: `iterations` times field(V, C), then refine_hexahedra;
// stops early when nothing is flagged, or when a pass leaves children folded (walls thinner than
// its cells: the valve at cell 0.4, pass 2): that pass is undone (report.undone) and the mesh of
// the passes before returned. Returns one report per pass made.
std::vector<RefinementReport> adapt_hexahedra(
    Eigen::MatrixXd& V, Eigen::MatrixXi& C, std::vector<char>& boundary,
    const std::function<Eigen::VectorXd(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C)>& field,
    double delta, int iterations, const ImplicitFunction& f = {}, long max_elements = 0);

} // namespace interlin
