#pragma once
// Parameter values for interpolation through a polyline.

#include <Eigen/Core>

namespace interlin {

// Cumulative |P_{i+1} - P_i|^exponent normalised to [0, 1]: exponent 1 is chord length,
// 0.5 centripetal (Lee 1989), 0 uniform.
//   P       #P by dim, consecutive points distinct
//   closed  append the closing segment P_{n-1} -> P_0
// Output: #P values (open) or #P + 1 values (closed; the last, 1, belongs to the closing point).
// Throws std::invalid_argument for fewer than 2 points or a zero-length polyline.
Eigen::VectorXd chord_parameters(const Eigen::MatrixXd& P, bool closed, double exponent = 1.0);

} // namespace interlin
