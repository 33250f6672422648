#pragma once
// Untangling of hexahedral meshes, shared by the mesher (pillows) and the refinement (children of
// nearly flat parents).

#include <Eigen/Core>

#include <vector>

namespace interlin::detail {

// Rounds of functional (15) with a sharp exponent (local max-min untangling) over the free nodes
// (not in `fixed`) of the inverted hexahedra and their neighbours, until none is inverted or the
// rounds stop helping (volume_mesh.cpp, untangle_rounds). Returns the elements still inverted.
// Inputs:  C #C by 8 hexahedra, fixed #V flags, threads (0: all cores)
// In/out:  V
long untangle_hexahedra(const Eigen::MatrixXi& C, const std::vector<char>& fixed, int threads,
                        Eigen::MatrixXd& V);

} // namespace interlin::detail
