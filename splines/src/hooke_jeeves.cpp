// Hooke–Jeeves direct search (seed 004 §2.5, ref. [85]; digest 004 §2.5 pseudo-code).
#include "interlin/splines/hooke_jeeves.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace interlin {

using Eigen::VectorXd;

HookeJeevesResult hooke_jeeves(const std::function<double(const VectorXd&)>& f0, const VectorXd& x0,
                               const HookeJeevesOptions& o) {
  HookeJeevesResult res;
  const auto f = [&](const VectorXd& x) {
    ++res.evaluations;
    const double v = f0(x);
    return std::isfinite(v) ? v : std::numeric_limits<double>::infinity();
  };
  res.x = x0;
  res.f = f(x0);
  if (!std::isfinite(res.f))
    throw std::invalid_argument("Hooke-Jeeves: objective not finite at the starting point");
  VectorXd step = VectorXd::Constant(x0.size(), o.initial_step);
  // Exploratory move: per variable try +step, then -step, keep what improves.
  const auto explore = [&](VectorXd x, double& fx) {
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      for (double sign : {1.0, -1.0}) {
        VectorXd t = x;
        t(i) += sign * step(i);
        const double ft = f(t);
        if (ft < fx) {
          x = t;
          fx = ft;
          break;
        }
      }
    }
    return x;
  };
  while (step.maxCoeff() >= o.min_step && res.f > o.target && res.evaluations < o.max_evaluations) {
    double f1 = res.f;
    VectorXd x1 = explore(res.x, f1);
    if (f1 < res.f) {
      // Pattern moves while they keep improving.
      while (res.evaluations < o.max_evaluations) {
        const VectorXd p = x1 + (x1 - res.x);
        res.x = x1;
        res.f = f1;
        double f2 = f(p);
        const VectorXd x2 = explore(p, f2);
        if (f2 < res.f) {
          x1 = x2;
          f1 = f2;
        } else {
          break;
        }
      }
    } else {
      step *= 0.5;
    }
  }
  return res;
}

} // namespace interlin
