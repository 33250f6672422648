#pragma once
// Test geometry shared by the suites: random clamped knot vectors, a closed cubic ring, random
// bicubic patches and the ring swept into a tube.

#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/bspline_surface.h"
#include "interlin/splines/knot_insertion.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace interlin::test {

// Clamped knot vector on [a, b] for n control points of degree p: a and b with multiplicity
// p + 1, sorted random interior knots in (a, b); with double_knot (and >= 3 interior knots, p >= 2)
// the second and third interior knots are made equal.
inline Eigen::VectorXd random_clamped_knots(std::mt19937& rng, int p, Eigen::Index n, double a,
                                            double b, bool double_knot = false) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> inner;
  for (Eigen::Index k = 0; k < n - p - 1; ++k)
    inner.push_back(a + (b - a) * (0.05 + 0.9 * unit(rng)));
  std::sort(inner.begin(), inner.end());
  if (double_knot && inner.size() >= 3 && p >= 2)
    inner[2] = inner[1];
  Eigen::VectorXd t(n + p + 1);
  t.head(p + 1).setConstant(a);
  t.tail(p + 1).setConstant(b);
  for (size_t k = 0; k < inner.size(); ++k)
    t(p + 1 + static_cast<Eigen::Index>(k)) = inner[k];
  return t;
}

// A closed ring in the plane z = 0: the periodic uniform cubic B-spline with 8 control points at
// radius 2 + wobble cos(3 angle), clamped at u = 0 by periodic_to_clamped (so the curve is closed
// and C^2 across the seam), u in [0, 1].
inline BSplineCurve clamped_ring(double wobble) {
  const int p = 3;
  const Eigen::Index N = 8;
  BSplineCurve ring;
  ring.degree = p;
  ring.periodic = true;
  ring.knots.resize(N + 2 * p + 1);
  for (Eigen::Index k = 0; k < ring.knots.size(); ++k)
    ring.knots(k) = static_cast<double>(k - p) / static_cast<double>(N);
  ring.ctrl.resize(N + p, 3);
  for (Eigen::Index k = 0; k < N + p; ++k) {
    const double a = 2.0 * M_PI * static_cast<double>(k % N) / static_cast<double>(N);
    const double r = 2.0 + wobble * std::cos(3.0 * a);
    ring.ctrl.row(k) << r * std::cos(a), r * std::sin(a), 0.0;
  }
  return periodic_to_clamped(ring, 0.0);
}

// Random bicubic surface, control points in [-size, size]^3 (non-uniform simple knots: C2),
// u in [0, 1], v in [0, v1].
inline BSplineSurface random_bicubic(Eigen::Index nu, Eigen::Index nv, double size, unsigned seed,
                                     double v1 = 1.0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(-size, size);
  BSplineSurface s;
  s.num_u = nu;
  s.num_v = nv;
  s.knots_u = random_clamped_knots(rng, 3, nu, 0.0, 1.0);
  s.knots_v = random_clamped_knots(rng, 3, nv, 0.0, v1);
  s.ctrl.resize(nu * nv, 3);
  for (Eigen::Index r = 0; r < s.ctrl.rows(); ++r)
    for (int c = 0; c < 3; ++c)
      s.ctrl(r, c) = coord(rng);
  return s;
}

// clamped_ring(0.3) swept up z = 0..10 and scaled by (1 + 0.2 t, 1 - 0.1 t) at height 10 t (one
// Bezier span of degree pv along v, v in [0, 5]): closed in u, planar sections of area
// A0 (1 + 0.2 t)(1 - 0.1 t).
inline BSplineSurface swept_tube(int pv) {
  const BSplineCurve ring = clamped_ring(0.3);
  BSplineSurface s;
  s.degree_u = 3;
  s.degree_v = pv;
  s.num_u = ring.ctrl.rows();
  s.num_v = pv + 1;
  s.knots_u = ring.knots;
  s.knots_v.resize(2 * pv + 2);
  s.knots_v.head(pv + 1).setZero();
  s.knots_v.tail(pv + 1).setConstant(5.0);
  s.closed_u = true;
  s.ctrl.resize(s.num_u * s.num_v, 3);
  for (Eigen::Index j = 0; j < s.num_v; ++j) {
    const double t = static_cast<double>(j) / static_cast<double>(pv);
    for (Eigen::Index i = 0; i < s.num_u; ++i)
      s.ctrl.row(i + s.num_u * j) << ring.ctrl(i, 0) * (1.0 + 0.2 * t),
          ring.ctrl(i, 1) * (1.0 - 0.1 * t), 10.0 * t;
  }
  return s;
}

} // namespace interlin::test
