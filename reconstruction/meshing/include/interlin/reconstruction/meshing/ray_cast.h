#pragma once
// Rays against closed triangle meshes: the inside test by ray parity (an independent check of
// implicit functions against meshes) and first-hit distances (local thickness).

#include <Eigen/Core>
#include <vector>

namespace interlin {

// Inside test by ray parity: a ray from each point crosses a closed mesh an odd number of times
// iff the point is inside. The rays run along +x, tilted by 1e-4 and 2e-4 in y and z so that
// they do not meet edges and vertices of axis-aligned meshes; the triangles are bucketed on a
// y-z grid, so a query costs the triangles of one bucket.
// Inputs:  V #V by 3, F #F by 3 (closed, consistently oriented or not: only parity counts),
//          P #P by 3
// Output:  #P flags, 1 inside.
std::vector<char> inside_by_ray_parity(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                       const Eigen::MatrixXd& P);

// Distance along each ray O_i + t D_i (t > 0, D_i need not be unit: t is in units of |D_i|) to
// the nearest triangle it hits (Moller-Trumbore), +infinity when it hits none. Every triangle's
// box is tested (slab test against the best hit so far) before the triangle: O(#rays x #F) box
// tests, for checks on test-sized meshes.
Eigen::VectorXd ray_hit_distance(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                 const Eigen::MatrixXd& O, const Eigen::MatrixXd& D);

} // namespace interlin
