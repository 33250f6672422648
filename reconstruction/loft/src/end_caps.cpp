// Ruled caps of a closed loft.
#include "interlin/reconstruction/loft/end_caps.h"

#include "interlin/splines/knot_insertion.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

namespace {

// The curve traversed backwards, still on [0, 1].
BSplineCurve reversed(const BSplineCurve& c) {
  BSplineCurve r = c;
  r.ctrl = c.ctrl.colwise().reverse();
  for (long i = 0; i < c.knots.size(); ++i)
    r.knots(i) = 1 - c.knots(c.knots.size() - 1 - i);
  return r;
}

} // namespace

BSplineCurve end_loop(const BSplineSurface& s, bool at_end) {
  check_surface(s);
  BSplineCurve c;
  c.degree = s.degree_u;
  c.knots = s.knots_u;
  const Eigen::Index j = at_end ? s.num_v - 1 : 0;
  c.ctrl = s.ctrl.middleRows(j * s.num_u, s.num_u);
  return c;
}

StepCap end_cap(const BSplineSurface& s, bool at_end) {
  if (!s.closed_u)
    throw std::invalid_argument("end_cap: the surface must be closed around (closed_u)");
  const BSplineCurve loop = end_loop(s, at_end);
  const double u0 = domain_begin(loop), u1 = domain_end(loop);
  // The farthest pair on a fine uniform sampling (enough for choosing corners).
  constexpr int kSamples = 512;
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(kSamples + 1, u0, u1);
  const Eigen::MatrixXd X = evaluate(loop, u);
  long a = 0, b = 0;
  double far = -1;
  for (int i = 0; i < kSamples; ++i)
    for (int j = i + 1; j < kSamples; ++j)
      if ((X.row(i) - X.row(j)).squaredNorm() > far)
        far = (X.row(i) - X.row(j)).squaredNorm(), a = i, b = j;
  if (!(far > 0))
    throw std::invalid_argument("end_cap: the end loop is a single point");
  StepCap cap;
  cap.corner_u = {u(a), u(b)};
  cap.v = at_end ? s.knots_v(s.num_v) : s.knots_v(s.degree_v);
  // The two halves from corner 0 to corner 1 on one knot vector, then the ruled net.
  const std::vector<BSplineCurve> halves =
      make_compatible({curve_piece(loop, u(a), u(b)), reversed(curve_piece(loop, u(b), u(a)))});
  BSplineSurface& P = cap.patch;
  P.degree_u = halves[0].degree;
  P.degree_v = 1;
  P.knots_u = halves[0].knots;
  P.knots_v = Eigen::Vector4d(0, 0, 1, 1);
  P.num_u = halves[0].ctrl.rows();
  P.num_v = 2;
  P.ctrl.resize(2 * P.num_u, 3);
  P.ctrl << halves[0].ctrl, halves[1].ctrl;
  return cap;
}

} // namespace interlin
