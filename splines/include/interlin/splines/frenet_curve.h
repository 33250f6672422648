#pragma once
// seed 004 §2.4 (digest 004 §2.3, §4.3): space curves from curvature k(s) and torsion tau(s)
// by integrating the Frenet equations
//   t' = k n,   n' = -k t + tau b,   b' = -tau n,   r' = t,
// with k and tau piecewise linear in the arc length (the book's "epures"). The book uses
// Ralston's RK4 with Hamming's predictor–corrector; here fixed-step classical RK4 and an adaptive
// Dormand–Prince 5(4) pair, both restarted at every break of k or tau (where the right-hand side
// is only continuous), which keeps their full order.

#include <Eigen/Core>
#include <vector>

namespace interlin {

// A piecewise-linear function of arc length: values at increasing breaks s, linear between,
// constant beyond the ends. One break means a constant.
struct PiecewiseLinearLaw {
  Eigen::VectorXd s;
  Eigen::VectorXd value;
};

// Value at s. Throws std::invalid_argument for an empty law, mismatched sizes, non-finite values
// or breaks that do not increase strictly.
double evaluate(const PiecewiseLinearLaw& law, double s);

// Position and Frenet frame (tangent, normal, binormal; orthonormal, right-handed).
struct FrenetFrame {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  Eigen::Vector3d t = Eigen::Vector3d::UnitX();
  Eigen::Vector3d n = Eigen::Vector3d::UnitY();
  Eigen::Vector3d b = Eigen::Vector3d::UnitZ();
};

enum class FrenetIntegrator { rk4, adaptive };

struct FrenetOptions {
  FrenetIntegrator method = FrenetIntegrator::adaptive;
  double step = 1e-2;       // rk4: largest step
  double tolerance = 1e-12; // adaptive: local error per unit length
};

// Frames at the arc lengths s (non-decreasing, >= 0) starting from `start` at s = 0 (the book's
// default start: origin, t = e_x, n = e_y, b = e_z). Throws std::invalid_argument for bad laws,
// a start frame that is not orthonormal and right-handed, or bad options.
std::vector<FrenetFrame> integrate_frenet(const PiecewiseLinearLaw& k,
                                          const PiecewiseLinearLaw& tau, const Eigen::VectorXd& s,
                                          const FrenetFrame& start = {},
                                          const FrenetOptions& options = {});

} // namespace interlin
