#pragma once
// Private to reconstruction/clouds: evaluation of the local functions of the partition of unity
// (cloud_implicit.h) and the weight function, inline because the evaluator calls them for every
// point and every overlapping leaf.

#include "interlin/reconstruction/clouds/cloud_implicit.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace interlin::detail {

// Normals within 60 degrees of each other lie on one sheet: a quadratic height function over
// the tangent plane then has slopes up to tan 60 = 1.7 (the fit's one-sheet test; the smoothing's
// neighbours; the other side of a thin wall is not the same sheet).
inline constexpr double kSheetCos = 0.5;

// The rows t1, t2, n of an orthonormal frame whose third axis is the unit vector n.
inline Eigen::Matrix3d tangent_frame(const Eigen::Vector3d& n) {
  const Eigen::Vector3d a =
      std::abs(n(0)) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d t1 = n.cross(a).normalized();
  Eigen::Matrix3d F;
  F << t1.transpose(), n.cross(t1).transpose(), n.transpose();
  return F;
}

// Wendland's C2 function psi(r) = (1 - r)^4 (4 r + 1) on [0, 1), 0 beyond.
inline double wendland(double r) {
  if (r >= 1)
    return 0;
  const double a = (1 - r) * (1 - r);
  return a * a * (4 * r + 1);
}

// The sheet's height h(u, v) = c0 u^2 + c1 u v + c2 v^2 + c3 u + c4 v + c5 over its tangent plane.
[[gnu::always_inline]] inline double sheet_height(const HeightSheet& s, double u, double v) {
  const auto& c = s.c;
  return (c[0] * u + c[1] * v + c[3]) * u + (c[2] * v + c[4]) * v + c[5];
}

// Q = h(u, v) - w of one sheet, and its gradient when g is not null.
[[gnu::always_inline]] inline double sheet_value(const HeightSheet& s, const Eigen::Vector3d& x,
                                                 Eigen::Vector3d* g) {
  const Eigen::Vector3d d = x - s.origin;
  const Eigen::Vector3d l = s.frame * d; // (u, v, w)
  const double u = l(0), v = l(1);
  const auto& c = s.c;
  const double h = sheet_height(s, u, v);
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

// A closed interval [lo, hi] of real numbers, with the interval arithmetic the box bounds need.
struct Interval {
  double lo = 0, hi = 0;
};
inline Interval operator+(Interval a, Interval b) {
  return {a.lo + b.lo, a.hi + b.hi};
}
inline Interval operator*(double c, Interval a) {
  return c >= 0 ? Interval{c * a.lo, c * a.hi} : Interval{c * a.hi, c * a.lo};
}
inline Interval operator*(Interval a, Interval b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
}
inline Interval square(Interval a) {
  const double l = a.lo * a.lo, h = a.hi * a.hi;
  return a.lo <= 0 && a.hi >= 0 ? Interval{0, std::max(l, h)}
                                : Interval{std::min(l, h), std::max(l, h)};
}

// The values of Q = h(u, v) - w of one sheet over the box B, bounded: (u, v, w) each take the
// exact range of a linear function over B, h is bounded by interval arithmetic (an outer bound,
// as the three are treated as independent).
inline Interval sheet_range(const HeightSheet& s, const Eigen::AlignedBox3d& B) {
  const Eigen::Vector3d mid = s.frame * (B.center() - s.origin);
  const Eigen::Vector3d half = s.frame.cwiseAbs() * (0.5 * B.sizes());
  const Interval u{mid(0) - half(0), mid(0) + half(0)}, v{mid(1) - half(1), mid(1) + half(1)};
  const auto& c = s.c;
  const Interval h = c[0] * square(u) + c[1] * (u * v) + c[2] * square(v) + c[3] * u + c[4] * v +
                     Interval{c[5], c[5]};
  return {h.lo - mid(2) - half(2), h.hi - mid(2) + half(2)};
}

// +1 (-1) when the local function is certainly > 0 (< 0) on the box B, else 0. Rvachev's R0
// conjunction is > 0 exactly where both arguments are, < 0 where either is; the disjunction dually.
inline int fit_sign_on_box(const LocalFit& f, const Eigen::AlignedBox3d& B) {
  auto sign = [](Interval q) { return q.lo > 0 ? 1 : q.hi < 0 ? -1 : 0; };
  const int a = sign(sheet_range(f.sheet[0], B));
  if (f.sheets == 1)
    return a;
  const int b = sign(sheet_range(f.sheet[1], B));
  const int agree = f.conjunction ? 1 : -1; // both must be this for the join to be it
  if (a == agree && b == agree)
    return agree;
  return a == -agree || b == -agree ? -agree : 0;
}

} // namespace interlin::detail
