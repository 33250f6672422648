#pragma once
// The foot of the perpendicular from a point to a surface patch: Newton's method on
// |S(u,v) - p|^2 / 2 from a given start, with the parameter domain as box constraints. The local
// step every closest-point search ends with (global searches choose the starts).

#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace interlin {

// Result of surface_foot.
//   u, v       parameters of the foot
//   distance   |S(u,v) - p|
//   jet        S and its derivatives up to order 2 at the foot (jet.S is the foot)
//   clamped_u, clamped_v  the foot lies on that boundary of the domain (an open-u surface's u
//              bounds, the v bounds), where the residual need not be normal to the surface
//   iterations Newton steps taken
struct SurfaceFoot {
  double u = 0, v = 0, distance = 0;
  SurfaceJet jet;
  bool clamped_u = false, clamped_v = false;
  int iterations = 0;
};

// Inputs:
//   S       the surface; closed_u surfaces wrap in u, otherwise u is kept in its domain; v is
//           always kept in its domain
//   p       the point
//   u, v    the start (any values; wrapped or clamped into the domain)
//   max_iterations  Newton steps at most
// Method: Newton on f = |S - p|^2 / 2 with the exact Hessian (S_u.S_u + S_uu.r, ...) where it is
// positive definite, Gauss-Newton otherwise; a coordinate on its bound whose step points out of
// the domain is held (active set) and the other one takes its 1-D Newton step; halving line
// search on f, a step that turns S_u by more than 45 degrees halved too. Stops when the foot moves
// less than 1e-15 x (|p| + 1) or f stops decreasing. Output: a local minimum of the distance (the
// nearest foot when the start is in its basin).
SurfaceFoot surface_foot(const PiecewiseSurface& S, const Eigen::Vector3d& p, double u, double v,
                         int max_iterations = 50);

// The same iteration on any surface given by its jet: jet(u, v) -> SurfaceJet, domain
// (u0, u1, v0, v1), closed_u as above (e.g. another library's surface, measured with our code).
// See also: project_to_surface (reconstruction/loft/closest_point.h), the global search.
template <class JetFn>
SurfaceFoot surface_foot(const JetFn& jet, const Eigen::Vector4d& dom, bool closed_u,
                         const Eigen::Vector3d& p, double u, double v, int max_iterations) {
  const double period = dom(1) - dom(0);
  const auto wrap_u = [&](double x) {
    if (closed_u)
      return x - period * std::floor((x - dom(0)) / period);
    return std::clamp(x, dom(0), dom(1));
  };
  SurfaceFoot F;
  F.u = wrap_u(u);
  F.v = std::clamp(v, dom(2), dom(3));
  F.jet = jet(F.u, F.v);
  Eigen::Vector3d r = F.jet.S - p;
  double f = 0.5 * r.squaredNorm();
  const double tiny = 1e-15 * (p.cwiseAbs().maxCoeff() + 1);
  for (; F.iterations < max_iterations; ++F.iterations) {
    const SurfaceJet& J = F.jet;
    const double gu = J.Su.dot(r), gv = J.Sv.dot(r);
    const double a = J.Su.dot(J.Su), b = J.Su.dot(J.Sv), c = J.Sv.dot(J.Sv);
    double huu = a + J.Suu.dot(r), huv = b + J.Suv.dot(r), hvv = c + J.Svv.dot(r);
    if (!(huu > 0 && hvv > 0 && huu * hvv - huv * huv > 1e-12 * huu * hvv))
      huu = a, huv = b, hvv = c; // Gauss-Newton: the first-order part is positive semi-definite
    double du = 0, dv = 0;
    const double det = huu * hvv - huv * huv;
    if (det > 0) {
      du = -(hvv * gu - huv * gv) / det;
      dv = -(huu * gv - huv * gu) / det;
    }
    // Active set: a coordinate on its bound whose step leaves the domain is held there.
    const bool hold_v = (F.v <= dom(2) && dv < 0) || (F.v >= dom(3) && dv > 0) || !(det > 0);
    const bool hold_u =
        !closed_u && ((F.u <= dom(0) && du < 0) || (F.u >= dom(1) && du > 0) || !(det > 0));
    if (hold_v && hold_u)
      du = dv = 0;
    else if (hold_v) {
      dv = 0;
      du = huu > 0 ? -gu / huu : 0;
    } else if (hold_u) {
      du = 0;
      dv = hvv > 0 ? -gv / hvv : 0;
    }
    if (!std::isfinite(du) || !std::isfinite(dv) || (du == 0 && dv == 0))
      break;
    bool moved = false;
    double t = 1;
    for (int ls = 0; ls < 40; ++ls, t *= 0.5) {
      const double un = wrap_u(F.u + t * du), vn = std::clamp(F.v + t * dv, dom(2), dom(3));
      const SurfaceJet Jn = jet(un, vn);
      const Eigen::Vector3d rn = Jn.S - p;
      const double fn = 0.5 * rn.squaredNorm();
      // A step may turn S_u by 45 degrees at most: a longer one can leap round a thin edge (a
      // blade's trailing edge) onto the other sheet's local minimum, which the test on f accepts
      // when that sheet is nearer than the start. (S_v may reverse: folds between sections.)
      if (J.Su.dot(Jn.Su) < std::cos(M_PI / 4) * J.Su.norm() * Jn.Su.norm())
        continue;
      // Near the minimum f changes below its own round-off: accept such steps too.
      if (fn <= f + 1e-13 * f + 1e-300) {
        const double step = (Jn.S - J.S).norm();
        F.u = un, F.v = vn, F.jet = Jn, r = rn, f = fn;
        moved = step > tiny;
        break;
      }
    }
    if (!moved)
      break;
  }
  F.distance = r.norm();
  F.clamped_v = F.v <= dom(2) || F.v >= dom(3);
  F.clamped_u = !closed_u && (F.u <= dom(0) || F.u >= dom(1));
  return F;
}

} // namespace interlin
