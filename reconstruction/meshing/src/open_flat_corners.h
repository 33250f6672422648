#pragma once
// Hexahedra's flat corners opened by moving the interior nodes at them (a local max-min search).
#include <Eigen/Core>

#include <vector>

namespace interlin::detail {

// Every interior node (fixed[v] == 0) of a hexahedron whose smallest corner scaled Jacobian is
// below `flat` moves, one node at a time in node order, by a compass search to the position that
// maximises the smallest corner scaled Jacobian of its elements (steps from a quarter of its
// mean edge, halved down to 1e-3 of it; a move that does not raise that minimum is not made), 3
// passes. The untangling's max-min rounds leave such corners where two crease lines meet (seed
// 003's body (11) at 128 cells: 2.5e-15). Boundary nodes stay, so the mesh's volume does too.
// Returns the hexahedra still below `flat`.
long open_flat_corners(const Eigen::MatrixXi& C, const std::vector<char>& fixed, double flat,
                       Eigen::MatrixXd& V);

} // namespace interlin::detail
