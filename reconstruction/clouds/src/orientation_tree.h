#pragma once
// Private to reconstruction/clouds: Hoppe's orientation propagation (orient_normals.h) as steps,
// for orient_normals (one root per component) and orient_by_winding_number (grown again from the
// decided patches).

#include <Eigen/Core>
#include <vector>

namespace interlin::detail {

// Symmetric neighbour lists from the k-nearest-neighbour table (#P by k).
std::vector<std::vector<int>> neighbour_graph(const Eigen::MatrixXi& K);

// Hoppe, DeRose, Duchamp, McDonald, Stuetzle 1992, §3.3: Prim's minimum spanning tree over the
// graph g with the edge cost of orient_normals.h, grown from all `seeds` at once (their normals
// are kept); each point reached takes the sign that agrees with its tree parent. done[i] != 0
// marks points already oriented (seeds included); on return it marks every point reached.
// Returns how many normals were negated.
Eigen::Index grow_orientation(const Eigen::MatrixX3d& P, Eigen::MatrixX3d& N,
                              const std::vector<std::vector<int>>& g, const std::vector<int>& seeds,
                              std::vector<char>& done);

} // namespace interlin::detail
