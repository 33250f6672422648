#pragma once
// Cox–de Boor recursion (de Boor 1972): the textbook evaluation of B-splines, kept as the
// independent reference that tests and benchmarks compare the explicit form (seed 001) against.

#include <Eigen/Core>

namespace interlin {

// N_{i,p}(u) on the knot vector `knots` by the triangular recursion, half-open spans
// [t_i, t_{i+1}); at the right end of the domain (u == knots(num_ctrl)) the last basis is 1.
// Outputs: values(r) = N_{span-p+r,p}(u), r = 0..p, for the span found by find_span.
Eigen::VectorXd cox_de_boor_values(const Eigen::VectorXd& knots, int p, Eigen::Index num_ctrl,
                                   double u, Eigen::Index* span = nullptr);

// Values and derivatives up to order nderiv (Piegl & Tiller, algorithm A2.3).
// Output: (nderiv+1) by (p+1), row d = d-th derivatives of N_{span-p..span, p}(u).
Eigen::MatrixXd cox_de_boor_derivatives(const Eigen::VectorXd& knots, int p, Eigen::Index num_ctrl,
                                        double u, int nderiv, Eigen::Index* span = nullptr);

} // namespace interlin
