#include "interlin/splines/surface_foot.h"

#include <algorithm>
#include <cmath>

namespace interlin {

using Eigen::Vector3d;

SurfaceFoot surface_foot(const PiecewiseSurface& S, const Vector3d& p, double u, double v,
                         int max_iterations) {
  const Eigen::Vector4d dom = domain(S);
  const double period = dom(1) - dom(0);
  const auto wrap_u = [&](double x) {
    if (S.closed_u)
      return x - period * std::floor((x - dom(0)) / period);
    return std::clamp(x, dom(0), dom(1));
  };
  SurfaceFoot F;
  F.u = wrap_u(u);
  F.v = std::clamp(v, dom(2), dom(3));
  F.jet = evaluate_jet(S, F.u, F.v);
  Vector3d r = F.jet.S - p;
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
        !S.closed_u && ((F.u <= dom(0) && du < 0) || (F.u >= dom(1) && du > 0) || !(det > 0));
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
      const SurfaceJet Jn = evaluate_jet(S, un, vn);
      const Vector3d rn = Jn.S - p;
      const double fn = 0.5 * rn.squaredNorm();
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
  F.clamped_u = !S.closed_u && (F.u <= dom(0) || F.u >= dom(1));
  return F;
}

} // namespace interlin
