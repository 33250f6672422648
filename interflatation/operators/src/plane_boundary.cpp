// Chords of axis-parallel lines in plane regions (operators/plane_boundary.h).
#include "interlin/interflatation/operators/plane_boundary.h"

#include "sign_runs.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace interlin {

using Eigen::Vector2d;

namespace {

// Bisection iterations: halving the sample spacing 60 times reaches round-off for any box.
constexpr int kBisections = 60;

// Sorted crossings -> chords: the region lies between crossings 0-1, 2-3, ... (a closed curve
// crosses a line an even number of times; an odd count, from a tangency, drops the last one).
std::vector<double> pair_up(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  if (x.size() % 2 == 1)
    x.pop_back();
  return x;
}

} // namespace

PlaneBoundary implicit_boundary(std::function<double(const Vector2d&)> g,
                                const Eigen::AlignedBox2d& box, int samples) {
  if (samples < 2 || box.isEmpty())
    throw std::invalid_argument("implicit_boundary: need samples >= 2 and a non-empty box");
  PlaneBoundary b;
  b.box = box;
  b.chords = [g = std::move(g), box, samples](int axis, double c) {
    const int other = 1 - axis;
    Vector2d p;
    p(axis) = c;
    return detail::sign_runs(
        [&](double s) {
          p(other) = s;
          return g(p) > 0;
        },
        box.min()(other), box.max()(other), samples);
  };
  return b;
}

PlaneBoundary polygon_boundary(const Eigen::MatrixX2d& V) {
  if (V.rows() < 3 || !V.allFinite())
    throw std::invalid_argument("polygon_boundary: need >= 3 finite vertices");
  PlaneBoundary b;
  b.box =
      Eigen::AlignedBox2d(V.colwise().minCoeff().transpose(), V.colwise().maxCoeff().transpose());
  b.chords = [V](int axis, double c) {
    const int other = 1 - axis;
    std::vector<double> x;
    for (Eigen::Index i = 0; i < V.rows(); ++i) {
      const Vector2d p = V.row(i), q = V.row((i + 1) % V.rows());
      if (std::min(p(axis), q(axis)) < c && c <= std::max(p(axis), q(axis)))
        x.push_back(p(other) + (c - p(axis)) / (q(axis) - p(axis)) * (q(other) - p(other)));
    }
    return pair_up(std::move(x));
  };
  return b;
}

PlaneBoundary curve_boundary(const BSplineCurve& curve, int samples_per_span) {
  if (curve.ctrl.cols() != 2 || samples_per_span < 2)
    throw std::invalid_argument("curve_boundary: need a 2-D curve and >= 2 samples per span");
  auto pc = std::make_shared<PiecewiseCurve>(to_piecewise(curve));
  const long n = (pc->breaks.size() - 1) * samples_per_span;
  const Eigen::VectorXd t =
      Eigen::VectorXd::LinSpaced(n + 1, pc->breaks(0), pc->breaks(pc->breaks.size() - 1));
  const Eigen::MatrixXd P = evaluate(*pc, t);
  const double diagonal = (P.colwise().maxCoeff() - P.colwise().minCoeff()).norm();
  if ((P.row(0) - P.row(n)).norm() > 1e-9 * diagonal)
    throw std::invalid_argument("curve_boundary: the curve is not closed");
  PlaneBoundary b;
  b.box =
      Eigen::AlignedBox2d(P.colwise().minCoeff().transpose(), P.colwise().maxCoeff().transpose());
  b.chords = [pc, t, P](int axis, double c) {
    auto point = [&](double s) -> Eigen::RowVector2d {
      return evaluate(*pc, Eigen::VectorXd::Constant(1, s)).row(0);
    };
    std::vector<double> x;
    // Half-open rule on each sample interval, as for polygons: counted once at a sample point.
    for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
      double s0 = t(i), s1 = t(i + 1);
      const double a = P(i, axis) - c, e = P(i + 1, axis) - c;
      if (!((a < 0 && e >= 0) || (a >= 0 && e < 0)))
        continue;
      const bool rising = a < 0;
      for (int k = 0; k < kBisections; ++k) {
        const double m = 0.5 * (s0 + s1);
        ((point(m)(axis) < c) == rising ? s0 : s1) = m;
      }
      x.push_back(point(0.5 * (s0 + s1))(1 - axis));
    }
    return pair_up(std::move(x));
  };
  return b;
}

} // namespace interlin
