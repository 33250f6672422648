#include "profile_curves.h"

#include "nearest_neighbours.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace interlin::detail {

using Eigen::Index;
using Eigen::MatrixXd;

namespace {

// Knot weights: each interval's share of the arc length plus this times its share of the
// turning angle (measured 0, 1 and 2: 0 loses 3x on the section family, 2 loses 17 % there and
// gains 11 % on Rotor 37).
constexpr double kTurningShare = 1.0;
// Closest points: the largest Newton step (share of the period) and the most steps.
constexpr double kMaxNewtonStep = 0.01;
constexpr int kClosestSteps = 20;
// A point stops when its next step is below this share of the period.
constexpr double kConverged = 1e-10;
// Global starts of closest_parameters: samples per knot span.
constexpr Index kFootSamples = 8;
// Knot spans hold at least this many points (capped_knot_weights).
constexpr Index kPointsPerSpan = 3;

// The parameter of the curve sample nearest to each point (kFootSamples evenly in each knot span,
// FLANN): a start in the basin of the closest point, which a start from a neighbour's foot on a
// thin profile's other side is not.
Eigen::VectorXd nearest_samples(const PiecewiseCurve& pc, const MatrixXd& P) {
  const Index spans = pc.breaks.size() - 1;
  Eigen::VectorXd t(spans * kFootSamples);
  for (Index j = 0; j < spans; ++j)
    t.segment(j * kFootSamples, kFootSamples) =
        Eigen::VectorXd::LinSpaced(kFootSamples + 1, pc.breaks(j), pc.breaks(j + 1))
            .head(kFootSamples);
  const NeighbourIndex samples(evaluate(pc, t));
  Eigen::VectorXd u(P.rows());
  std::vector<int> idx;
  std::vector<double> d2;
  for (Index i = 0; i < P.rows(); ++i) {
    samples.knn(P.row(i).transpose(), 1, idx, d2);
    u(i) = t(idx.front());
  }
  return u;
}

} // namespace

// Arc-length share plus kTurningShare x turning-angle share per interval.
Eigen::VectorXd turning_weights(const BSplineCurve& c, const Eigen::VectorXd& t) {
  const PiecewiseCurve pc = to_piecewise(c);
  const MatrixXd C = evaluate(pc, t), T = evaluate(pc, t, 1);
  const Index n = t.size() - 1;
  Eigen::VectorXd ds(n), dtheta(n);
  for (Index i = 0; i < n; ++i) {
    ds(i) = (C.row(i + 1) - C.row(i)).norm();
    const double cosine = T.row(i).normalized().dot(T.row(i + 1).normalized());
    dtheta(i) = std::acos(std::clamp(cosine, -1.0, 1.0));
  }
  return ds / std::max(ds.sum(), 1e-300) + kTurningShare * dtheta / std::max(dtheta.sum(), 1e-300);
}

Eigen::VectorXd capped_knot_weights(const Eigen::VectorXd& w, const Eigen::VectorXd& m,
                                    const Eigen::VectorXd& u, Index control) {
  const double W = w.sum(), c = double(control);
  Eigen::VectorXd r(w.size());
  for (Index i = 0; i < w.size(); ++i)
    r(i) = std::min({w(i), m(i) * W / (double(kPointsPerSpan) * c),
                     W * (u(i + 1) - u(i)) / (4 * kKnotGrid * c)}) +
           1e-12 * W;
  return r;
}

Eigen::VectorXd closest_parameters(const BSplineCurve& c, const MatrixXd& P, Eigen::VectorXd u) {
  const double a = domain_begin(c), T = domain_end(c) - a;
  const PiecewiseCurve pc = to_piecewise(c);
  const auto wrap = [&](double x) { return a + T * ((x - a) / T - std::floor((x - a) / T)); };
  const Eigen::VectorXd g = nearest_samples(pc, P);
  const MatrixXd Cu = evaluate(pc, u), Cg = evaluate(pc, g);
  for (Index i = 0; i < u.size(); ++i)
    if ((Cg.row(i) - P.row(i)).squaredNorm() < (Cu.row(i) - P.row(i)).squaredNorm())
      u(i) = g(i);
  std::vector<Index> active(size_t(u.size()));
  for (Index i = 0; i < u.size(); ++i)
    active[size_t(i)] = i;
  Eigen::VectorXd limit = Eigen::VectorXd::Constant(u.size(), kMaxNewtonStep * T);
  for (int step = 0; step < kClosestSteps && !active.empty(); ++step) {
    const Eigen::VectorXd ua = u(active);
    const MatrixXd C = evaluate(pc, ua), D1 = evaluate(pc, ua, 1), D2 = evaluate(pc, ua, 2);
    Eigen::VectorXd next(ua.size());
    for (Index j = 0; j < ua.size(); ++j) {
      const Index i = active[size_t(j)];
      const Eigen::RowVectorXd r = C.row(j) - P.row(i);
      const double h = D1.row(j).squaredNorm() + r.dot(D2.row(j)), g = r.dot(D1.row(j));
      // Newton where the distance is convex, else a step of the limit's length downhill
      const double du = h > 0 ? g / h : (g > 0 ? limit(i) : -limit(i));
      next(j) = wrap(ua(j) - std::clamp(du, -limit(i), limit(i)));
    }
    const MatrixXd Cn = evaluate(pc, next);
    std::vector<Index> still;
    for (Index j = 0; j < ua.size(); ++j) {
      const Index i = active[size_t(j)];
      const double step = std::abs(std::remainder(next(j) - ua(j), T));
      if ((Cn.row(j) - P.row(i)).squaredNorm() <= (C.row(j) - P.row(i)).squaredNorm())
        u(i) = next(j);
      else
        limit(i) = 0.5 * step; // overshot: at most half as far next time
      if (step > kConverged * T)
        still.push_back(i);
    }
    active = std::move(still);
  }
  return u;
}

} // namespace interlin::detail
