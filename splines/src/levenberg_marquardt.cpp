// Levenberg–Marquardt on residual vectors (Marquardt 1963) for the seed 004 shooting problems.
#include "interlin/splines/levenberg_marquardt.h"

#include <Eigen/Dense>
#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::MatrixXd;
using Eigen::VectorXd;

LevenbergMarquardtResult levenberg_marquardt(const ResidualFunction& r, const VectorXd& x0,
                                             const LevenbergMarquardtOptions& o,
                                             const FeasibleFunction& feasible) {
  const auto ok = [&](const VectorXd& x) { return x.allFinite() && (!feasible || feasible(x)); };
  if (!ok(x0))
    throw std::invalid_argument("Levenberg-Marquardt: infeasible starting point");
  LevenbergMarquardtResult res;
  res.x = x0;
  res.residual = r(x0);
  if (!res.residual.allFinite())
    throw std::invalid_argument("Levenberg-Marquardt: residual not finite at the starting point");
  double f = res.residual.squaredNorm();
  const Eigen::Index n = x0.size(), m = res.residual.size();
  double mu = 1e-3;
  for (res.iterations = 0; res.iterations < o.max_iterations; ++res.iterations) {
    if (std::sqrt(f) <= o.residual_tolerance)
      break;
    // Central-difference Jacobian; a one-sided difference where a side is infeasible.
    MatrixXd J(m, n);
    bool jac_ok = true;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double h = o.fd_step * std::max(1.0, std::abs(res.x(j)));
      VectorXd xp = res.x, xm = res.x;
      xp(j) += h;
      xm(j) -= h;
      const bool p = ok(xp), q = ok(xm);
      const VectorXd rp = p ? r(xp) : res.residual, rm = q ? r(xm) : res.residual;
      J.col(j) = (rp - rm) / ((p ? h : 0.0) + (q ? h : 0.0));
      jac_ok = jac_ok && (p || q) && J.col(j).allFinite();
    }
    if (!jac_ok)
      break;
    const MatrixXd A = J.transpose() * J;
    const VectorXd g = J.transpose() * res.residual;
    const VectorXd D = A.diagonal().cwiseMax(1e-12 * std::max(1.0, A.diagonal().maxCoeff()));
    bool improved = false, tiny = false;
    for (int tries = 0; tries < 40 && !improved; ++tries) {
      MatrixXd Am = A;
      Am.diagonal() += mu * D;
      const VectorXd step = -Am.ldlt().solve(g);
      if (!step.allFinite()) {
        mu *= 10;
        continue;
      }
      tiny = step.norm() <= o.step_tolerance * (res.x.norm() + o.step_tolerance);
      const VectorXd x = res.x + step;
      if (ok(x)) {
        const VectorXd rx = r(x);
        if (rx.allFinite() && rx.squaredNorm() < f) {
          res.x = x;
          res.residual = rx;
          f = rx.squaredNorm();
          mu = std::max(mu / 3, 1e-12);
          improved = true;
          break;
        }
      }
      if (tiny)
        break;
      mu *= 4;
    }
    if (!improved)
      break;
  }
  res.norm = std::sqrt(f);
  return res;
}

} // namespace interlin
