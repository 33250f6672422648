#pragma once
// Seed 003's adaptive meshing (digest §7.2, §11.6) for tetrahedral meshes: elements where a nodal
// quantity C (an FE solution such as von Mises stress, or any field) changes by more than a
// fraction delta of its global range are refined by templates, conforming by construction.

#include "interlin/interflatation/implicit_function.h"

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace interlin {

// The seed's indicator per element: error(e) = max_{i, j in e} |C_i - C_j| / (max C - min C)
// (the denominator over all nodes; 0 everywhere when C is constant).
// Inputs:  C #C by k elements (any k), values #V nodal quantity (finite)
// Output:  #C indicator values in [0, 1]
Eigen::VectorXd refinement_indicator(const Eigen::MatrixXi& C, const Eigen::VectorXd& values);

// The seed code's refined nodes (digest §7.2 [C]): the vertices of the elements with indicator >
// delta and of every element sharing a vertex with one.
// Inputs:  C #C by k elements, indicator #C, delta, nodes #V
// Output:  #V flags; flagged (optional): the number of elements with indicator > delta
std::vector<char> refined_nodes(const Eigen::MatrixXi& C, const Eigen::VectorXd& indicator,
                                double delta, long nodes, long* flagged = nullptr);

struct RefinementReport {
  long flagged = 0;       // elements with indicator > delta
  long refined_nodes = 0; // vertices of the flagged elements and of their vertex neighbours
                          // (hexahedra: after the closure) ...
  long widened = 0;       // ... of which added by the closure (hexahedra; tetrahedra: 0)
  long folded = 0;        // hexahedra: children the parent's trilinear map folds (nearly flat
                          // parents) before untangling ...
  long still_folded = 0;  // ... and after it (and after the projection's untangling)
  bool undone = false; // hexahedra, adapt_hexahedra: the pass left children folded and was undone
  long split = 0;      // elements replaced by children
  long new_nodes = 0;  // edge midpoints added
  long projected = 0;  // of those, on boundary edges and moved onto F = 0 ...
  long held = 0;       // ... of which held short of it (the largest of 1, 1/2, ... 1/1024 of the
                       // way that inverts no element; 0: left on the edge) ...
  std::vector<long> held_nodes; // ... these nodes (flagged boundary: they stay in smoothing)
};

// One pass of the seed code's 2-refinement of tetrahedra (digest §7.2 [C]): the elements with
// indicator > delta are flagged; every element sharing a vertex with a flagged one joins them, and
// all their vertices become refined nodes; an edge is halved iff both its ends are refined, so a
// tetrahedron with 2, 3 or 4 refined vertices becomes 2 (edge bisected), 4 (face split 1 -> 4,
// joined to the opposite vertex) or 8 children (4 corners and the octahedron cut along the
// diagonal between the midpoints of edges 0-2 and 1-3). A face then has 0, 1 or 3 halved edges
// and both elements sharing it cut it alike: no hanging nodes. New nodes on edges of boundary
// facets are projected onto F = 0 (gradient walk, steps of a quarter edge) when f has a value, so
// that refinement follows the curved boundary (the seed code projects every edge between two
// boundary nodes; only facet edges lie on the surface). Children keep positive orientation.
// Inputs:
//   C        #C by 4 positive tetrahedra ((p1 - p0) x (p2 - p0) . (p3 - p0) > 0)
//   values   #V nodal quantity (std::invalid_argument for a wrong size or non-finite values)
//   delta    threshold in [0, 1)
//   f        the body (for the projection; an empty value: midpoints stay)
// In/out:
//   V        #V by 3 -> #V' by 3 (new nodes appended)
//   C        -> #C' by 4
//   boundary #V flags of nodes on F = 0 -> #V' (projected midpoints flagged)
//   values   -> #V' (midpoints get the mean of their edge's ends)
// Output:    the counts
// max_elements > 0: std::length_error, before any change, when the pass would make more elements.
RefinementReport refine_tetrahedra(Eigen::MatrixXd& V, Eigen::MatrixXi& C,
                                   std::vector<char>& boundary, Eigen::VectorXd& values,
                                   double delta, const ImplicitFunction& f = {},
                                   long max_elements = 0);

// Seed 003's adaptive loop: `iterations` times, evaluate the nodal quantity on the current mesh
// (field(V, C): the FE solve in the seed), then refine_tetrahedra. Stops early when nothing is
// flagged. Inputs/outputs as refine_tetrahedra; returns one report per pass made.
std::vector<RefinementReport> adapt_tetrahedra(
    Eigen::MatrixXd& V, Eigen::MatrixXi& C, std::vector<char>& boundary,
    const std::function<Eigen::VectorXd(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C)>& field,
    double delta, int iterations, const ImplicitFunction& f = {}, long max_elements = 0);

} // namespace interlin
