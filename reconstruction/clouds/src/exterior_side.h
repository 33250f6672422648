#pragma once
// Private to reconstruction/clouds: which side of each point of a closed scan is the outside,
// read from a voxel grid by a flood fill (the inside/outside test of volumetric hole filling,
// e.g. Nooruddin and Turk, "Simplification and repair of polygonal models using volumetric
// techniques", IEEE TVCG 9(2), 2003). The voxels within one voxel of a point are the shell (the
// dilation closes the sampling's gaps); the free voxels the 6-connected flood fill reaches from
// the grid's border are outside, the other free voxels inside. Unlike the normals' propagation
// or the winding number of a wrongly oriented cloud, this reads only the points' positions.

#include <Eigen/Core>
#include <vector>

namespace interlin::detail {

// The side each normal points to.
// Inputs:  P #P by 3 points, N #P by 3 unit normals (any orientation), voxel: the voxel size
// Output:  #P votes: +1 when the first free voxel along +n_i is outside and the first along -n_i
//          inside, -1 for the reverse, 0 otherwise (a wall thinner than the shell, a cloud with
//          a hole the shell does not close, a march that finds no free voxel within 6 voxels).
// The grid is coarsened (voxel doubled) until it holds at most 2^26 voxels.
std::vector<signed char> exterior_votes(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                                        double voxel);

} // namespace interlin::detail
