#pragma once
// The regular background grid of implicit-surface extraction: seed 002's "support points" in the
// bounding box, seed 003's hexahedral background mesh. Nodes are numbered x fastest.

#include "interlin/interflatation/implicit_function.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace interlin {

struct RegularGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();   // node (0, 0, 0)
  Eigen::Vector3d spacing = Eigen::Vector3d::Ones();  // node step along x, y, z (> 0)
  Eigen::Array3i nodes = Eigen::Array3i::Constant(2); // node counts along x, y, z (>= 2)

  long size() const { return long(nodes(0)) * nodes(1) * nodes(2); }
  long index(long i, long j, long k) const { return i + nodes(0) * (j + nodes(1) * k); }
  // origin + (i, j, k) .* spacing: the same double for the same node wherever it is computed.
  Eigen::Vector3d point(long i, long j, long k) const {
    return {origin(0) + double(i) * spacing(0), origin(1) + double(j) * spacing(1),
            origin(2) + double(k) * spacing(2)};
  }
  Eigen::AlignedBox3d box() const {
    return {origin, point(nodes(0) - 1, nodes(1) - 1, nodes(2) - 1)};
  }
  // Whether node (i, j, k) lies on the outer layer, the faces of the grid's box.
  bool outer(long i, long j, long k) const {
    return i == 0 || j == 0 || k == 0 || i == nodes(0) - 1 || j == nodes(1) - 1 ||
           k == nodes(2) - 1;
  }
};

// Whether a value F sampled at an outer node means the body reaches the box there: a mesh of
// {F > 0} on the grid is then cut by the box (implicit_mesh and volume_mesh count such nodes, and
// `interlin mesh` warns).
inline bool reaches_box(double F) {
  return F > 0;
}

// The outer nodes of g whose value in S (#g nodes, node order) reaches the box (reaches_box).
long nodes_reaching_box(const RegularGrid& g, const Eigen::VectorXd& S);

// A grid of cubic cells covering `box`: `cells` cells along the box's longest side (cell size
// h = longest side / cells) and ceil(side / h) cells along the others, each axis centred on the
// box (so the outer nodes lie on the box faces or just outside).
// Throws std::invalid_argument for an empty or non-finite box, cells < 1, or more than 2^31
// nodes.
RegularGrid grid_with_resolution(const Eigen::AlignedBox3d& box, int cells);

// The same with the cell size h given (> 0).
RegularGrid grid_with_cell(const Eigen::AlignedBox3d& box, double h);

// Samples f at every node of g, in batches of one z-slice, on `threads` threads (0: all cores).
// Output: S #nodes, S(g.index(i, j, k)) = F(g.point(i, j, k)). Non-finite values are kept as
// returned.
void sample_grid(const ImplicitFunction& f, const RegularGrid& g, Eigen::VectorXd& S,
                 int threads = 0);

} // namespace interlin
