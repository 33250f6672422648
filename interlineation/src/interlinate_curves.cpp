// seed 001 §2.5; digest 001 §5.1 [SUPPLEMENT] (one-family Gordon = spline-blended interlineation).
#include "interlin/interlineation/interlinate_curves.h"

#include "interlin/splines/interpolate_curve.h"

#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

BSplineSurface interlinate_curves(const std::vector<BSplineCurve>& curves, const VectorXd& v,
                                  int degree_v, bool closed_u) {
  const Index K = static_cast<Index>(curves.size());
  if (K < 2)
    throw std::invalid_argument("interlination needs at least 2 curves");
  if (v.size() != K)
    throw std::invalid_argument("interlination: one parameter per curve expected");
  const BSplineCurve& c0 = curves[0];
  for (Index k = 0; k < K; ++k) {
    const BSplineCurve& c = curves[k];
    if (c.periodic || c.degree != c0.degree || c.knots.size() != c0.knots.size() ||
        c.knots != c0.knots || c.ctrl.cols() != 3)
      throw std::invalid_argument("interlination: curve " + std::to_string(k) +
                                  " is not compatible (same degree and knot vector, clamped, 3-D)");
  }
  const Index n = c0.ctrl.rows();
  // Row k of P holds all control points of curve k: interpolating the columns along v gives the
  // net whose column j is the v-spline through the j-th control points.
  MatrixXd P(K, 3 * n);
  for (Index k = 0; k < K; ++k)
    for (Index j = 0; j < n; ++j)
      P.block(k, 3 * j, 1, 3) = curves[k].ctrl.row(j);
  const BSplineCurve blend = interpolate_open(P, v, degree_v);
  BSplineSurface s;
  s.degree_u = c0.degree;
  s.degree_v = blend.degree;
  s.knots_u = c0.knots;
  s.knots_v = blend.knots;
  s.num_u = n;
  s.num_v = blend.ctrl.rows();
  s.closed_u = closed_u;
  s.ctrl.resize(s.num_u * s.num_v, 3);
  for (Index j = 0; j < s.num_v; ++j)
    for (Index i = 0; i < n; ++i)
      s.ctrl.row(i + n * j) = blend.ctrl.block(j, 3 * i, 1, 3);
  return s;
}

} // namespace interlin
