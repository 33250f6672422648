#include "interlin/splines/surface_foot.h"

namespace interlin {

using Eigen::Vector3d;

SurfaceFoot surface_foot(const PiecewiseSurface& S, const Vector3d& p, double u, double v,
                         int max_iterations) {
  const auto jet = [&S](double a, double b) { return evaluate_jet(S, a, b); };
  return surface_foot(jet, domain(S), S.closed_u, p, u, v, max_iterations);
}

} // namespace interlin
