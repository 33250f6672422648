// Shape diagnostics: convexity / concavity signs of the parameter lines of known surfaces.
#include "interlin/interlineation/interlinate_curves.h"
#include "interlin/interlineation/shape_diagnostics.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Closed section at height z of a body of revolution with radius r(z) and a dent: the polar
// curve r(t) = 1 + d cos(2t)... with d = 0.35, the section is concave near t = pi/2, 3pi/2
// (polar curvature sign r^2 + 2 r'^2 - r r'' < 0 there) and convex elsewhere.
BSplineCurve section(double z, double r, bool reverse = false) {
  const int N = 64;
  MatrixXd P(N, 3);
  VectorXd u(N + 1);
  for (int i = 0; i < N; ++i) {
    const double t = 2 * M_PI * (reverse ? N - i : i) / N, rho = r * (1 + 0.35 * std::cos(2 * t));
    P.row(i) << rho * std::cos(t), rho * std::sin(t), z;
    u(i) = double(i) / N;
  }
  u(N) = 1;
  return periodic_to_clamped(interpolate_closed(P, u, 3), 0.0);
}

double polar_convexity(double t) {
  const double r = 1 + 0.35 * std::cos(2 * t), r1 = -0.7 * std::sin(2 * t),
               r2 = -1.4 * std::cos(2 * t);
  return r * r + 2 * r1 * r1 - r * r2;
}

} // namespace

TEST_CASE("Shape map of a lofted dented tube: concave dents around, bulge along", "[shape]") {
  // Radius along z: r(z) = 1 + 0.3 sin(pi z): bulging outward (convex along v) for z in (0, 1).
  std::vector<BSplineCurve> cs;
  const VectorXd z = VectorXd::LinSpaced(9, 0, 1);
  for (double zk : z)
    cs.push_back(section(zk, 1 + 0.3 * std::sin(M_PI * zk)));
  const PiecewiseSurface S = to_piecewise(interlinate_curves(cs, z, 3, true));
  const VectorXd u = VectorXd::LinSpaced(73, 0, 1).head(72),
                 v = VectorXd::LinSpaced(11, 0.05, 0.95);
  const ShapeMap m = shape_map(S, u, v, 1e-3);
  int agree = 0, checked = 0;
  for (Index i = 0; i < u.size(); ++i) {
    const double c = polar_convexity(2 * M_PI * u(i));
    if (std::abs(c) < 0.05)
      continue; // near an inflection the sampled spline may differ in sign
    for (Index j = 0; j < v.size(); ++j) {
      ++checked;
      agree += m.along_u(i, j) == (c > 0 ? 1 : -1);
    }
  }
  CHECK(agree == checked);
  CHECK((m.along_v.array() == 1).all());
  // Reversed sections (u -> 1 - u, so S_u x S_v points inward): the normal is flipped outward
  // and the signs are the same.
  std::vector<BSplineCurve> rs;
  for (double zk : z)
    rs.push_back(section(zk, 1 + 0.3 * std::sin(M_PI * zk), true));
  const ShapeMap mr = shape_map(to_piecewise(interlinate_curves(rs, z, 3, true)), u, v, 1e-3);
  for (Index i = 1; i < u.size(); ++i)
    CHECK((mr.along_u.row(u.size() - i) - m.along_u.row(i)).cwiseAbs().maxCoeff() == 0);
  CHECK((mr.along_v.array() == 1).all());
  const ShapeSummary s = summarize(m);
  CHECK(s.convex_v == 1.0);
  CHECK(s.concave_u > 0.1);
  CHECK(s.convex_u > 0.5);
  // Runs along one v line: convex, concave, convex, concave, convex (the dents at pi/2, 3pi/2).
  const std::vector<SignRun> runs = sign_runs(u, m.along_u.col(5));
  REQUIRE(runs.size() == 5);
  CHECK(runs[1].sign == -1);
  CHECK(runs[1].begin < 0.25);
  CHECK(runs[1].end > 0.25);
}
