#pragma once
// Internal: the far field of the implicit models, the tricubic interpolant of signed distances,
// extended outside its node box by f(q) - |p - q| (q the nearest point of the box), and the blend
// of a near-field signed distance into it.

#include "interlin/interflatation/models/section_body.h"
#include "interlin/interflatation/operators/cubic_grid.h"

#include <cmath>

namespace interlin::detail {

inline double far_field(const CubicGrid& G, const Eigen::Vector3d& p, Eigen::Vector3d& g) {
  const Eigen::Vector3d lo = G.origin, hi = grid_max(G);
  const Eigen::Vector3d q = p.cwiseMax(lo).cwiseMin(hi);
  double f = evaluate(G, q, &g);
  const Eigen::Vector3d r = p - q;
  const double out = r.norm();
  if (out > 0) {
    for (int a = 0; a < 3; ++a)
      if (r(a) != 0)
        g(a) = 0;
    f -= out;
    g -= r / out;
  }
  return f;
}

// omega = f + chi(|d|) (d - f) and its gradient.
inline double blend(double d, const Eigen::Vector3d& gd, double f, const Eigen::Vector3d& gf,
                    double inner, double outer, Eigen::Vector3d& g) {
  double slope = 0;
  const double w = band_weight(std::abs(d), inner, outer, &slope);
  g = gf + w * (gd - gf) + (d - f) * slope * (d < 0 ? -1.0 : 1.0) * gd;
  return f + w * (d - f);
}

} // namespace interlin::detail
