#pragma once
// Evaluates an accepted surface (value and mixed first derivative) on a 3 x 3 grid of its domain:
// a reader that lets an invalid surface through shows up as a crash here.

#include "interlin/splines/bspline_surface.h"

namespace interlin::fuzz {

inline void probe_surface(const BSplineSurface& s) {
  const PiecewiseSurface p = to_piecewise(s);
  const Eigen::Vector4d d = domain(p);
  for (const double u : {d(0), 0.5 * (d(0) + d(1)), d(1)})
    for (const double v : {d(2), 0.5 * (d(2) + d(3)), d(3)})
      (void)evaluate(p, u, v, 1, 1);
}

} // namespace interlin::fuzz
