#include "interlin/splines/parameterization.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::VectorXd;

VectorXd chord_parameters(const Eigen::MatrixXd& P, bool closed, double exponent) {
  const Index n = P.rows();
  if (n < 2)
    throw std::invalid_argument("chord_parameters: need at least 2 points");
  const Index m = closed ? n + 1 : n;
  VectorXd t(m);
  t(0) = 0;
  for (Index i = 1; i < m; ++i) {
    const double d = (P.row(i % n) - P.row(i - 1)).norm();
    t(i) = t(i - 1) + std::pow(d, exponent);
    if (exponent > 0 && !(d > 0))
      throw std::invalid_argument("chord_parameters: points " + std::to_string(i - 1) + " and " +
                                  std::to_string(i % n) + " coincide");
  }
  if (!(t(m - 1) > 0) || !std::isfinite(t(m - 1)))
    throw std::invalid_argument("chord_parameters: polyline has no length");
  return t / t(m - 1);
}

} // namespace interlin
