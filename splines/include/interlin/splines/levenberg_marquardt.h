#pragma once
// Levenberg–Marquardt on a residual vector (Marquardt 1963), the default solver of the
// natural-parametrization shooting problems. The book (seed 004 §2.5) minimises the miss with
// Hooke–Jeeves; digest 004 §2.5 [V] recommends least squares on residuals, which converges to
// round-off where Hooke–Jeeves stalls on the non-smooth miss distance.

#include <Eigen/Core>
#include <functional>

namespace interlin {

// r(x): residual vector (fixed size m) at the unknowns x (n).
using ResidualFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
// feasible(x): false rejects a trial step (for example a non-positive arc length).
using FeasibleFunction = std::function<bool(const Eigen::VectorXd&)>;

struct LevenbergMarquardtOptions {
  int max_iterations = 200;
  double residual_tolerance = 1e-14; // stop when |r| <= this
  double step_tolerance = 1e-15;     // stop when the relative step is below this
  double fd_step = 1e-7;             // central differences: h_j = fd_step * max(1, |x_j|)
};

struct LevenbergMarquardtResult {
  Eigen::VectorXd x;
  Eigen::VectorXd residual;
  double norm = 0; // |residual|
  int iterations = 0;
};

// Minimises |r(x)|^2 from x0 with a central-difference Jacobian and damping mu (J^T J + mu D)
// (D = diag(J^T J)). Never returns a non-finite x: steps with non-finite residuals or outside
// `feasible` are rejected. Throws std::invalid_argument if r(x0) is not finite or x0 infeasible.
LevenbergMarquardtResult levenberg_marquardt(const ResidualFunction& r, const Eigen::VectorXd& x0,
                                             const LevenbergMarquardtOptions& options = {},
                                             const FeasibleFunction& feasible = nullptr);

} // namespace interlin
