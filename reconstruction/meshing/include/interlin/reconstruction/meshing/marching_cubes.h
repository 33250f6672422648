#pragma once
// Marching cubes on a sampled regular grid (the zero level of seed 002's visualiser and of
// seed 000's models for 3D printing), with the asymptotic decider on ambiguous faces so that the
// surface is closed and 2-manifold, and optional parallel extraction in slabs merged exactly
// along their common grid planes.

#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>
#include <vector>

namespace interlin {

// The grid edge a surface vertex lies on: from node `node` (RegularGrid::index) one step along
// `axis` (0, 1, 2), with the sampled values f0 at `node` and f1 at the other end (one of them
// inside, > 0, the other not).
struct EdgeVertex {
  long node = 0;
  int axis = 0;
  double f0 = 0, f1 = 0;
};

// Interpolation parameters along an edge are kept in [kEdgeClamp, 1 - kEdgeClamp], so that the
// vertices of the edges around a node where S = 0 stay distinct and no triangle degenerates.
inline constexpr double kEdgeClamp = 1e-6;

// Extracts the surface S = 0 between inside nodes (S > 0; +inf counts as inside) and the others
// (S <= 0, -inf, NaN).
// Each grid edge with one inside end carries one vertex, at the linear interpolation of S along
// the edge (parameter clamped as above); triangles come from a case table generated from the cube
// geometry (see src/mc_table.cpp). Ambiguous faces are resolved by the asymptotic decider: the
// inside corners are connected across the face iff the product of their values exceeds the
// product of the outside values (the sign of the bilinear saddle). Both cubes of a face decide
// alike, so the result is crack-free and every edge has exactly two triangles; triangles are
// oriented with normals pointing out of the inside region. The surface is closed when no node of
// the grid's outer layer is inside.
// Inputs:
//   g        grid
//   S        #nodes values, S(g.index(i, j, k)); std::invalid_argument on a size mismatch
//   threads  0: all cores; with more than one, slabs across y or z are extracted in parallel
//            and merged by grid edge: the same mesh, with the vertices in another order
// Outputs:
//   V  #V by 3 vertex positions, one per crossed grid edge
//   F  #F by 3 triangles into V
//   E  optional, #V edges the vertices lie on (for projection onto the true surface)
void marching_cubes(const RegularGrid& g, const Eigen::VectorXd& S, Eigen::MatrixXd& V,
                    Eigen::MatrixXi& F, std::vector<EdgeVertex>* E = nullptr, int threads = 0);

} // namespace interlin
