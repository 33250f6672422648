#pragma once
// Private to reconstruction/clouds: which side of each point of a closed scan is the outside,
// read from a voxel grid by a flood fill (the inside/outside test of volumetric hole filling,
// e.g. Nooruddin and Turk, "Simplification and repair of polygonal models using volumetric
// techniques", IEEE TVCG 9(2), 2003). The voxels within one voxel of a point are the shell (the
// dilation closes the sampling's gaps); the free voxels the 6-connected flood fill reaches from
// the grid's border are outside, the other free voxels inside. Unlike the normals' propagation
// or the winding number of a wrongly oriented cloud, this reads only the points' positions.

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace interlin::detail {

// Voxels of this many point spacings: finer ones let the fill leak through the sampling's gaps,
// coarser ones vote wrong more often (docs/benchmarks.md, "Orientation by a flood fill").
constexpr double kVoxelSpacings = 1.5;

// The flood-filled voxel grid: voxel (x, y, z) is the cube lo + h [x, x + 1] x ... of state
// kInside, kShell or kOutside.
struct ExteriorGrid {
  enum : std::uint8_t { kInside = 0, kShell = 1, kOutside = 2 };
  Eigen::Array3d lo;
  double h = 0;
  std::array<long, 3> n{};
  std::vector<std::uint8_t> state;
};

// The grid of points P with voxels of size `voxel` (doubled until it holds at most 2^26), its
// shell marked and its outside flood-filled. P #P by 3, not empty; voxel > 0.
ExteriorGrid exterior_grid(const Eigen::MatrixX3d& P, double voxel);

// The side of x the grid reads: +1 outside (also beyond the grid), -1 inside, 0 in the shell.
int exterior_side(const ExteriorGrid& g, const Eigen::Vector3d& x);

// Inside parts (face-connected free voxels the fill did not reach) that the generalized winding
// number w reads as outside, made outside: pockets whose way out the shell closes, such as an
// impeller's passages between blades under its shroud, narrower than about 4 voxels. A part of
// n voxels is a pocket when the median of w at every max(1, n / 64)-th of its voxel centres in
// fill order (at most 127 of them) is below 1/2 (w is about 1 inside a closed surface with
// outward normals, 0 outside). Returns the number of voxels opened.
long open_pockets(ExteriorGrid& g, const std::function<double(const Eigen::Vector3d&)>& winding,
                  int threads = 0);

// Free voxels next to the shell (a face neighbour in it): their centres (#S by 3) and sides (+1
// outside, -1 inside), every k-th in storage order with k chosen so that #S <= most.
struct ExteriorSamples {
  Eigen::MatrixX3d X;
  std::vector<int> side;
};
ExteriorSamples shell_neighbours(const ExteriorGrid& g, long most);

// The side each normal points to.
// Inputs:  P #P by 3 points, N #P by 3 unit normals (any orientation), voxel: the voxel size
// Output:  #P votes: +1 when the first free voxel along +n_i is outside and the first along -n_i
//          inside, -1 for the reverse, 0 otherwise (a wall thinner than the shell, a cloud with
//          a hole the shell does not close, a march that finds no free voxel within 6 voxels).
// The grid is coarsened (voxel doubled) until it holds at most 2^26 voxels.
std::vector<signed char> exterior_votes(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                                        double voxel);

} // namespace interlin::detail
