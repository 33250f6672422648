#pragma once
// Seed 003's projection method (digest §5.1): the boundary surface of the background cells that
// lie inside the body, with its nodes projected onto F = 0. Hexahedral backgrounds give quads,
// their 6-tetrahedra (Kuhn) split gives triangles. The node and facet counts of the seed's test
// body (11) on a 21^3 grid are reproduced exactly (tests/reconstruction/test_boundary_mesh.cpp).

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>
#include <cfloat>
#include <vector>

namespace interlin {

enum class BackgroundCells {
  hexahedra, // the grid's cubes
  tetrahedra // each cube split into 6 tetrahedra around its diagonal (i,j,k)-(i+1,j+1,k+1)
};

// Which nodes count as inside: seed 003's code uses strict (F > eps); its published hexahedral
// example needs inclusive (F >= -eps).
enum class ZeroRule { strict, inclusive };

struct BoundaryMeshOptions {
  BackgroundCells cells = BackgroundCells::hexahedra;
  ZeroRule rule = ZeroRule::strict;
  double epsilon = 1000 * DBL_EPSILON; // the seed code's tolerance on F
  bool project = true;                 // move the nodes onto F = 0 (else they stay grid nodes)
  int normal_sweeps = -1; // smoothing sweeps of the vertex normals; -1: the seed code's 10 for
                          // triangles, 4 for quads
  int threads = 0;        // sampling and projection; 0: all cores
  // Projection: the scan along the normal goes in steps of scan_step x h up to reach x h (h = half
  // the smallest grid spacing; the seed code's 0.01 and 100). Nodes beyond it are then projected
  // by the gradient walk (steps of h, at most reach of them), else left where they are (counted in
  // unprojected).
  double reach = 100, scan_step = 0.01;
  // Also remove the cells at nodes where two boundary facets face opposite ways (more than 143
  // degrees apart), repeatedly: parts one cell thin, where one projected copy of a node cannot
  // serve boundary-layer elements on both sides (volume meshing). Not in the seed's method.
  bool thin_cleanup = false;
};

struct BoundaryMesh {
  Eigen::MatrixXd V;    // #V by 3 boundary nodes (projected when asked)
  Eigen::MatrixXi P;    // #P by 4 quads or #P by 3 triangles, outward (counter-clockwise seen
                        // from outside)
  Eigen::VectorXi node; // #V grid node (RegularGrid::index) of each vertex
  long inside_nodes = 0;
  long cells = 0;         // surviving background cells
  std::vector<long> kept; // their ids, increasing: cube q = i + cx (j + cy k) (cx, cy cubes per
                          // axis), or 6 q + t for tetrahedron t of cube q
  long removed = 0;       // cells removed by the touching-configuration cleanup (stage 2)
  long thinned = 0;       // cells removed by the thin-part cleanup (options.thin_cleanup)
  long unprojected = 0;   // nodes whose projection found no sign change (left in place)
};

// The projection method on a sampled grid (no projection: V holds the grid nodes).
// Steps (digest §5.1): (1) a cell survives iff all its nodes are inside; (2) while the boundary
// surface has an edge with more than two facets or a vertex whose facets form more than one fan
// (cells touching along an edge or at a node), the surviving cell with the smallest "power"
// (sum over its nodes of the surviving cells at that node; seed 003 code) among those at such a
// vertex is removed; (3) the facets of one surviving cell only, outward.
// Inputs: g grid, S #nodes values, o options (cells, rule, epsilon)
BoundaryMesh boundary_mesh(const RegularGrid& g, const Eigen::VectorXd& S,
                           const BoundaryMeshOptions& o = {});

// Samples f on g and runs the method; with o.project, project_boundary_nodes.
BoundaryMesh boundary_mesh(const ImplicitFunction& f, const RegularGrid& g,
                           const BoundaryMeshOptions& o = {});

// Moves every node of m with |S| > o.epsilon onto F = 0 along its smoothed vertex normal (seed
// 003 code: unit facet normals summed at each corner, then smoothed in place with the edge
// neighbours, o.normal_sweeps times; findBorder with the step h = half the smallest grid spacing,
// project_along, up to o.reach x h; nodes that find no sign change there walk along the gradient
// for at most the same distance, project_by_gradient_walk). Nodes that find no surface stay and
// are counted in m.unprojected.
// Inputs:  f, g and S (the grid and values m was built from), o (epsilon, normal_sweeps, threads)
// In/out:  m.V (#V by 3), m.unprojected
void project_boundary_nodes(const ImplicitFunction& f, const RegularGrid& g,
                            const Eigen::VectorXd& S, BoundaryMesh& m,
                            const BoundaryMeshOptions& o = {});

// Grid nodes of background cells, positively oriented: #ids by 4 for tetrahedra (the Kuhn split:
// (p1 - p0) x (p2 - p0) . (p3 - p0) > 0), #ids by 8 for cubes in VTK order (the face 0-1-2-3
// counter-clockwise seen from the face 4-5-6-7, node 4 + j above node j).
// Inputs:  g, cells (the kind), ids as in BoundaryMesh::kept
Eigen::MatrixXi background_cell_nodes(const RegularGrid& g, BackgroundCells cells,
                                      const std::vector<long>& ids);

// Splits each quad (a, b, c, d) into two triangles along its shorter diagonal.
// Inputs: V #V by 3, Q #Q by 4. Output: #Q*2 by 3 triangles, same orientation.
Eigen::MatrixXi triangulate_quads(const Eigen::MatrixXd& V, const Eigen::MatrixXi& Q);

} // namespace interlin
