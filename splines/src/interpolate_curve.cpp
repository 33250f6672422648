#include "interlin/splines/interpolate_curve.h"

#include "interlin/splines/knots.h"
#include "interlin/splines/spline_basis.h"

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

void check_sites(const MatrixXd& P, const VectorXd& u, Index expected) {
  if (u.size() != expected)
    throw std::invalid_argument("interpolation: expected " + std::to_string(expected) +
                                " parameters, got " + std::to_string(u.size()));
  if (!P.allFinite() || !u.allFinite())
    throw std::invalid_argument("interpolation: points and parameters must be finite");
  for (Index i = 1; i < u.size(); ++i)
    if (!(u(i) > u(i - 1)))
      throw std::invalid_argument("interpolation: parameters must increase strictly (index " +
                                  std::to_string(i) + ")");
}

// Solves the collocation system sum_j N_j(u_i) c_j = P_i (columns of P at once). A singular or
// ill-posed system (Schoenberg–Whitney violated) raises instead of returning garbage.
MatrixXd solve_collocation(const SplineBasis& B, const VectorXd& sites, Index wrap,
                           const MatrixXd& P) {
  std::vector<Index> r, c;
  std::vector<double> v;
  collocation_entries(B, sites, 0, wrap, r, c, v);
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    if (v[i] != 0.0)
      trip.emplace_back(r[i], c[i], v[i]);
  Eigen::SparseMatrix<double> A(P.rows(), P.rows());
  A.setFromTriplets(trip.begin(), trip.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(A);
  if (lu.info() != Eigen::Success)
    throw std::runtime_error("interpolation: collocation matrix is singular (the parameters "
                             "violate the Schoenberg-Whitney condition for the knots)");
  MatrixXd C = lu.solve(P);
  const double scale = std::max(1.0, P.cwiseAbs().maxCoeff());
  if (!C.allFinite() || (A * C - P).cwiseAbs().maxCoeff() > 1e-9 * scale)
    throw std::runtime_error("interpolation: collocation system is numerically singular");
  return C;
}

} // namespace

BSplineCurve interpolate_open(const MatrixXd& P, const VectorXd& u, int degree) {
  const Index n = P.rows();
  if (n < 2)
    throw std::invalid_argument("interpolation needs at least 2 points");
  if (degree < 1)
    throw std::invalid_argument("interpolation degree must be >= 1");
  check_sites(P, u, n);
  const int p = static_cast<int>(std::min<Index>(degree, n - 1));
  BSplineCurve c;
  c.degree = p;
  c.knots = averaged_knots(u, p);
  c.ctrl = solve_collocation(explicit_basis(c.knots, p), u, 0, P);
  return c;
}

BSplineCurve interpolate_closed(const MatrixXd& P, const VectorXd& u, int degree) {
  if (degree < 1)
    throw std::invalid_argument("interpolation degree must be >= 1");
  if (P.rows() < degree + 1)
    throw std::invalid_argument("closed interpolation of degree " + std::to_string(degree) +
                                " needs at least " + std::to_string(degree + 1) + " points");
  check_sites(P, u, P.rows() + 1);
  return interpolate_closed(P, u, degree, periodic_knots(u, degree));
}

BSplineCurve interpolate_closed(const MatrixXd& P, const VectorXd& u, int p,
                                const VectorXd& knots) {
  const Index N = P.rows();
  check_sites(P, u, N + 1);
  if (knots.size() != N + 2 * p + 1)
    throw std::invalid_argument("periodic knot vector must have #points + 2 degree + 1 entries");
  const SplineBasis B = explicit_basis(knots, p);
  // Sites wrapped into the domain [t_p, t_p + period).
  const double a = knots(p), period = knots(N + p) - knots(p);
  VectorXd sites = u.head(N);
  for (Index i = 0; i < N; ++i)
    sites(i) = a + (sites(i) - a) - period * std::floor((sites(i) - a) / period);
  const MatrixXd C = solve_collocation(B, sites, N, P);
  BSplineCurve c;
  c.degree = p;
  c.knots = knots;
  c.periodic = true;
  c.ctrl.resize(N + p, P.cols());
  c.ctrl.topRows(N) = C;
  c.ctrl.bottomRows(p) = C.topRows(p);
  return c;
}

} // namespace interlin
