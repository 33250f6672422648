#pragma once
// seed 001, Theorem 1: explicit B-spline of degree n on nonuniform knots X_0 <= ... <= X_{n+1},
// built per span as a Taylor polynomial (digest 001 §2.1, §2.1.3).
//
// The seed's construction: the (n-1)-th derivative is piecewise linear with values y_k at the
// knots (1); lower derivatives are integrals from X_0 (2); the support closes, (3). The seed
// leaves open how (3) is solved. Solving (3) as a linear system with y_1 fixed (theorem1_y_solve)
// is exact in rational arithmetic but ill-conditioned in floating point: with knot-span ratios of
// 1e3 the cubic loses 6 digits and degree >= 5 fails completely (measured; see docs/formulas.md).
// explicit_bspline therefore obtains the same y* from the B-spline derivative recurrence
//   N^(q+1) = sum_j a^(q+1)_j N_{j,n-q-1},  a^(q+1)_j = (n-q)(a^(q)_j - a^(q)_{j-1})/(X_{j+n-q} -
//   X_j),
// whose differences never cancel (the coefficients alternate in sign), and then integrates (2)
// span by span. Multiple knots are covered too: a derivative of order q jumps at a knot of
// multiplicity m >= n-q+1, and the jump is read off the coefficients a^(q). The conditions (3)
// then hold to round-off; closure_residual reports them.
//
#include <Eigen/Core>

namespace interlin {

// One B-spline in explicit per-span form.
//   breaks  s+1 distinct knots b_0 < ... < b_s (the support is [b_0, b_s])
//   taylor  s by n+1: taylor(j, q) = D^(q) N (b_j+), the q-th derivative at the left end of
//           span j, so that on [b_j, b_{j+1}]  N(x) = sum_q taylor(j,q) (x - b_j)^q / q!
struct ExplicitBSpline {
  int degree = 0;
  Eigen::VectorXd breaks;
  Eigen::MatrixXd taylor;
};

// Inputs:
//   X  n+2 knots, non-decreasing, X(0) < X(n+1), no knot of multiplicity > n+1
//   n  degree >= 0
// Output: the normalised B-spline N_{0,n}(x; X). Throws std::invalid_argument on bad knots.
ExplicitBSpline explicit_bspline(const Eigen::VectorXd& X, int n);

// Value (deriv = 0) or deriv-th derivative of N at x; exactly 0 outside [X_0, X_{n+1}).
double evaluate(const ExplicitBSpline& N, double x, int deriv = 0);

// seed 001 (1)-(3): the values y_k = N^(n-1)(X_k), k = 1..n, of the piecewise-linear (n-1)-th
// derivative, for simple knots and n >= 1, normalised to partition of unity (stable recurrence).
Eigen::VectorXd theorem1_y(const Eigen::VectorXd& X, int n);

// The seed's own route: y_1 = 1, the n-1 homogeneous equations (3) solved for y_2..y_n, then
// scaled to partition of unity by the closed-form y_1 = n! / prod_{j=2}^{n} (X_j - X_0).
// Simple knots only. Kept for fidelity and tests; ill-conditioned for strongly nonuniform knots.
Eigen::VectorXd theorem1_y_solve(const Eigen::VectorXd& X, int n);

// max_q |D^(q)(X_{n+1}-)| / max_x |N| over q = 0..n-m_last: how well N satisfies (3).
double closure_residual(const ExplicitBSpline& N, const Eigen::VectorXd& X);

// digest 001 §2.1.3, closed form of the same y_k (from the divided-difference representation):
//   y_k = (-1)^(n-1) n! (X_{n+1}-X_0) sum_{j=k+1}^{n+1} (X_j-X_k) / prod_{i!=j} (X_j-X_i).
// Simple knots only. An independent path used to check theorem1_y.
Eigen::VectorXd theorem1_y_closed_form(const Eigen::VectorXd& X, int n);

} // namespace interlin
