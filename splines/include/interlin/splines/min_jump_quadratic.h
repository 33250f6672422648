#pragma once
// seed 001, Theorem 2 (digest 001 §2.3): the interpolating quadratic spline with the minimal sum
// of squared jumps of S''.
//
// On [x_i, x_{i+1}] the spline is the chord plus a parabola vanishing at both nodes,
//   S_{N,i}(x) = [(x_{i+1}-x) y_i + (x-x_i) y_{i+1}] / h_i + M_{i,i+1} (x-x_i)(x-x_{i+1}) / 2,
// so it interpolates every node; C^1 at the interior nodes gives the recurrence
//   M_{i,i+1} = (2 Delta_{2,i-1} - h_{i-1} M_{i-1,i}) / h_i,   i = 2..N-1,
// and the one free value M_{1,2} minimises J = sum_i (M_{i,i+1} - M_{i+1,i+2})^2.
// The spline is exact on polynomials of degree 2 (the seed's claim, test T7).

#include <Eigen/Core>

namespace interlin {

// The spline: nodes x (N, strictly increasing), values y (N), second derivatives M (N-1),
// M(i) = S'' on [x(i), x(i+1)] (0-based; the seed's M_{i+1,i+2}).
struct MinJumpQuadratic {
  Eigen::VectorXd x;
  Eigen::VectorXd y;
  Eigen::VectorXd M;
};

// seed 001 Theorem 2, M_{1,2} closed form [DERIVED]:
//   a_j = 1/h_{j-1} + 1/h_j,  A_1 = 0,  A_j = (2/h_j) sum_{k=2}^{j} (-1)^{j-k} Delta_{2,k-1},
//   M_{1,2} = - sum_{j=2}^{N-1} (-1)^{j-1} a_j (A_j - A_{j-1}) / (h_1 sum_j a_j^2).
// For N = 2 there is no jump to minimise and M_{1,2} = 0 (the chord).
// Inputs: x N >= 2 finite, strictly increasing; y N finite. Throws std::invalid_argument.
double theorem2_m12(const Eigen::VectorXd& x, const Eigen::VectorXd& y);

// seed 001 Theorem 2, the recurrence M_{i,i+1} = (2 Delta_{2,i-1} - h_{i-1} M_{i-1,i}) / h_i
// started from a given M_{1,2}. Output: N-1 values.
Eigen::VectorXd theorem2_recurrence(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double m12);

// seed 001 Theorem 2, the explicit form
//   M_{i,i+1} = (1/h_i) [2 sum_{k=2}^{i} (-1)^{i+k} (Delta_{1,k} - Delta_{1,k-1})
//                        + (-1)^{i+1} h_1 M_{1,2}].
// Same values as the recurrence (an independent path for tests). Output: N-1 values.
Eigen::VectorXd theorem2_explicit(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double m12);

// The Theorem 2 spline: M_{1,2} by the closed form, the rest by the recurrence.
MinJumpQuadratic min_jump_quadratic(const Eigen::VectorXd& x, const Eigen::VectorXd& y);

// J(S, M) = sum_{i=1}^{N-2} (M_{i,i+1} - M_{i+1,i+2})^2, the functional Theorem 2 minimises.
double jump_functional(const MinJumpQuadratic& S);

// deriv-th derivative (0, 1, 2; higher are 0) at each t. Outside [x_0, x_{N-1}] the end pieces
// are continued. Output: #t values.
Eigen::VectorXd evaluate(const MinJumpQuadratic& S, const Eigen::VectorXd& t, int deriv = 0);

} // namespace interlin
