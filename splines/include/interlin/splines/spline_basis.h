#pragma once
// All B-splines of one knot vector in explicit per-span form (seed 001, Theorem 1; digest 001
// §2.1.3): the polynomial coefficients of every basis function on every span are computed once,
// after which values and derivatives cost one Horner pass per basis function.

#include <Eigen/Core>
#include <vector>

namespace interlin {

// Inputs of explicit_basis: knots (#ctrl + degree + 1, non-decreasing), degree >= 0.
//   coeffs  ((#ctrl - degree) * (degree+1)) by (degree+1): block k - degree holds the span
//           [knots(k), knots(k+1)), k = degree..#ctrl-1; row r of the block is the basis
//           N_{k-degree+r} and column q its coefficient of (u - knots(k))^q. Empty spans are 0.
struct SplineBasis {
  int degree = 0;
  Eigen::VectorXd knots;
  Eigen::Index num_ctrl = 0;
  Eigen::MatrixXd coeffs;
};

SplineBasis explicit_basis(const Eigen::VectorXd& knots, int degree);

// Values and derivatives of the degree+1 basis functions that are non-zero at u.
// Output: (nderiv+1) by (degree+1); row d holds the d-th derivatives of N_{span-degree+r}(u).
// `span` (optional) receives the knot-span index (see find_span).
Eigen::MatrixXd basis_derivatives(const SplineBasis& basis, double u, int nderiv,
                                  Eigen::Index* span = nullptr);

// Sparse-free collocation helper: the (#u by #ctrl) dense-row entries of the basis at sites u,
// as triplets (row, column, value) appended to the three output vectors; column indices are
// taken modulo `wrap` when wrap > 0 (periodic splines, whose last degree control points repeat
// the first ones).
void collocation_entries(const SplineBasis& basis, const Eigen::VectorXd& u, int deriv,
                         Eigen::Index wrap, std::vector<Eigen::Index>& rows,
                         std::vector<Eigen::Index>& cols, std::vector<double>& vals);

} // namespace interlin
