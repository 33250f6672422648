#pragma once
// Hooke–Jeeves direct search (Hooke & Jeeves 1961, seed 004 ref. [85]): the derivative-free
// minimiser the book uses for every shooting problem (seed 004 §2.5; algorithm as in digest 004
// §2.5: exploratory moves per variable, pattern moves, step halving).

#include <Eigen/Core>
#include <functional>

namespace interlin {

struct HookeJeevesOptions {
  double initial_step = 0.1; // per variable, absolute
  double min_step = 1e-10;   // stop when every step is below this
  double target = 0;         // stop as soon as f <= target
  long max_evaluations = 1000000;
};

struct HookeJeevesResult {
  Eigen::VectorXd x;
  double f = 0;
  long evaluations = 0;
};

// Minimises f from x0. Trial points where f is not finite count as worse.
// Throws std::invalid_argument if f(x0) is not finite.
HookeJeevesResult hooke_jeeves(const std::function<double(const Eigen::VectorXd&)>& f,
                               const Eigen::VectorXd& x0, const HookeJeevesOptions& options = {});

} // namespace interlin
