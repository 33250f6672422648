#pragma once
// Private to reconstruction/clouds: evaluation of the local functions of the partition of unity
// (cloud_implicit.h) and the weight function, inline because the evaluator calls them for every
// point and every overlapping leaf.

#include "interlin/reconstruction/clouds/cloud_implicit.h"

#include <cmath>

namespace interlin::detail {

// Wendland's C2 function psi(r) = (1 - r)^4 (4 r + 1) on [0, 1), 0 beyond.
inline double wendland(double r) {
  if (r >= 1)
    return 0;
  const double a = (1 - r) * (1 - r);
  return a * a * (4 * r + 1);
}

// Q = h(u, v) - w of one sheet, and its gradient when g is not null.
[[gnu::always_inline]] inline double sheet_value(const HeightSheet& s, const Eigen::Vector3d& x,
                                                 Eigen::Vector3d* g) {
  const Eigen::Vector3d d = x - s.origin;
  const Eigen::Vector3d l = s.frame * d; // (u, v, w)
  const double u = l(0), v = l(1);
  const auto& c = s.c;
  const double h = (c[0] * u + c[1] * v + c[3]) * u + (c[2] * v + c[4]) * v + c[5];
  if (g) {
    const double hu = 2 * c[0] * u + c[1] * v + c[3], hv = c[1] * u + 2 * c[2] * v + c[4];
    *g = s.frame.transpose() * Eigen::Vector3d(hu, hv, -1.0);
  }
  return h - l(2);
}

// Rvachev's R0 conjunction (sign = -1) or disjunction (sign = +1) of a and b, with gradient.
[[gnu::always_inline]] inline double r_join(double a, double b, double sign,
                                            const Eigen::Vector3d& ga, const Eigen::Vector3d& gb,
                                            Eigen::Vector3d* g) {
  const double s = std::sqrt(a * a + b * b);
  if (g)
    *g = s > 0 ? Eigen::Vector3d(ga + gb + sign * (a * ga + b * gb) / s) : Eigen::Vector3d(ga + gb);
  return a + b + sign * s;
}

[[gnu::always_inline]] inline double fit_value(const LocalFit& f, const Eigen::Vector3d& x,
                                               Eigen::Vector3d* g) {
  if (f.sheets == 1)
    return sheet_value(f.sheet[0], x, g);
  Eigen::Vector3d g1, g2;
  const double q1 = sheet_value(f.sheet[0], x, g ? &g1 : nullptr);
  const double q2 = sheet_value(f.sheet[1], x, g ? &g2 : nullptr);
  return r_join(q1, q2, f.conjunction ? -1.0 : 1.0, g1, g2, g);
}

} // namespace interlin::detail
