// Least-squares curve approximation with smoothing (seed 001 ch. 3, digest 001 §2.2 option (b)).
#include "interlin/splines/approximate_curve.h"

#include "interlin/splines/knots.h"
#include "interlin/splines/parameterization.h"
#include "interlin/splines/spline_basis.h"

#include "natural_quadrature.h"

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// Periodic knots rounded to multiples of `grid` (ApproximationOptions::knot_grid): the
// parameters' start and period must be multiples of it, so that the domain stays where the
// parameters are and the rounded knots stay periodic.
VectorXd round_knots(const VectorXd& t, double grid, double start, double period) {
  const auto on_grid = [grid](double x) {
    return std::abs(x / grid - std::round(x / grid)) < 1e-9;
  };
  if (!on_grid(start) || !on_grid(period))
    throw std::invalid_argument(
        "curve approximation: knot_grid needs parameters from and over multiples of it");
  VectorXd r = (t / grid).array().round() * grid;
  for (Index i = 0; i + 1 < t.size(); ++i)
    if ((t(i + 1) > t(i)) != (r(i + 1) > r(i)))
      throw std::invalid_argument("curve approximation: knot_grid merges knots");
  return r;
}

// G(i, j) = int N_i'' N_j'' over the domain (columns wrapped modulo `wrap` when > 0).
MatrixXd bending_gram(const SplineBasis& B, Index ncols, Index wrap) {
  const int p = B.degree;
  MatrixXd G = MatrixXd::Zero(ncols, ncols);
  const detail::GaussLegendre8& g = detail::gauss_legendre8();
  for (Index k = p; k < B.num_ctrl; ++k) {
    const double a = B.knots(k), b = B.knots(k + 1);
    if (!(b > a))
      continue;
    for (size_t q = 0; q < 8; ++q) {
      const double x = 0.5 * (a + b) + 0.5 * (b - a) * g.x[q], w = 0.5 * (b - a) * g.w[q];
      Index span;
      const MatrixXd D = basis_derivatives(B, x, 2, &span);
      for (int r = 0; r <= p; ++r)
        for (int s = 0; s <= p; ++s) {
          Index i = span - p + r, j = span - p + s;
          if (wrap > 0)
            i %= wrap, j %= wrap;
          G(i, j) += w * D(2, r) * D(2, s);
        }
    }
  }
  return G;
}

} // namespace

double bending_energy(const BSplineCurve& c) {
  if (c.degree < 2)
    throw std::invalid_argument("bending energy needs degree >= 2");
  const SplineBasis B = explicit_basis(c.knots, c.degree);
  const MatrixXd G = bending_gram(B, c.ctrl.rows(), 0);
  return (c.ctrl.transpose() * G * c.ctrl).trace();
}

Approximation approximate_curve(const MatrixXd& P, const ApproximationOptions& o) {
  const Index N = P.rows();
  const int p = o.degree;
  if (p < 1)
    throw std::invalid_argument("curve approximation: degree must be >= 1");
  if (p >= N)
    throw std::invalid_argument("curve approximation: degree " + std::to_string(p) +
                                " needs more than " + std::to_string(p) + " points, got " +
                                std::to_string(N));
  if (!P.allFinite())
    throw std::invalid_argument("curve approximation: points must be finite");
  if (!(o.smoothing >= 0) || !std::isfinite(o.smoothing))
    throw std::invalid_argument("curve approximation: smoothing weight must be >= 0");
  if (o.smoothing > 0 && p < 2)
    throw std::invalid_argument("curve approximation: smoothing needs degree >= 2");
  if (!(o.tolerance >= 0))
    throw std::invalid_argument("curve approximation: tolerance must be >= 0");
  if (o.num_ctrl != 0 && (o.num_ctrl < p + 1 || o.num_ctrl > N))
    throw std::invalid_argument(
        "curve approximation: num_ctrl must lie in [degree + 1, #points] = [" +
        std::to_string(p + 1) + ", " + std::to_string(N) + "]");
  if (!(o.knot_grid >= 0) || !std::isfinite(o.knot_grid) || (o.knot_grid > 0 && !o.closed))
    throw std::invalid_argument("curve approximation: knot_grid must be >= 0 (closed curves only)");
  if (o.knot_weights.size() != 0 &&
      (!o.closed || o.knot_weights.size() != N || !(o.knot_weights.array() > 0).all() ||
       !o.knot_weights.allFinite()))
    throw std::invalid_argument(
        "curve approximation: knot_weights must be #points positive weights (closed curves only)");
  if (o.parameters.size() != 0 && o.parameters.size() != N + (o.closed ? 1 : 0))
    throw std::invalid_argument("curve approximation: " + std::to_string(o.parameters.size()) +
                                " parameters for " + std::to_string(N) + " points");
  const VectorXd u =
      o.parameters.size() != 0 ? o.parameters : chord_parameters(P, o.closed, o.parameter_exponent);
  double L = 0;
  for (Index i = 0; i + 1 < N; ++i)
    L += (P.row(i + 1) - P.row(i)).norm();
  if (o.closed)
    L += (P.row(0) - P.row(N - 1)).norm();

  Index n = o.num_ctrl > 0 ? o.num_ctrl : std::min<Index>(N, std::max(p + 1, 8));
  Approximation best;
  for (;;) {
    BSplineCurve c;
    c.degree = p;
    c.periodic = o.closed;
    c.knots =
        o.closed ? periodic_quantile_knots(u, p, n, o.knot_weights) : approximation_knots(u, p, n);
    if (o.knot_grid > 0)
      c.knots = round_knots(c.knots, o.knot_grid, u(0), u(N) - u(0));
    const SplineBasis B = explicit_basis(c.knots, p);
    const VectorXd sites = o.closed ? VectorXd(u.head(N)) : u;
    std::vector<Index> rows, cols;
    std::vector<double> vals;
    collocation_entries(B, sites, 0, o.closed ? n : 0, rows, cols, vals);
    // A is banded (degree + 1 entries per row): sparse products form the normal equations in
    // O(N p^2) instead of the dense O(N n^2), which dominated the section fits.
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(vals.size());
    for (size_t k = 0; k < vals.size(); ++k)
      entries.emplace_back(rows[k], cols[k], vals[k]);
    Eigen::SparseMatrix<double> A(N, n);
    A.setFromTriplets(entries.begin(), entries.end());
    MatrixXd M = MatrixXd(A.transpose() * A);
    if (o.smoothing > 0)
      M += o.smoothing * double(N) / (L * L) * bending_gram(B, n, o.closed ? n : 0);
    const MatrixXd AtP = A.transpose() * P;
    const Eigen::LDLT<MatrixXd> ldlt(M);
    const MatrixXd C = ldlt.solve(AtP);
    const double scale = std::max(1.0, AtP.cwiseAbs().maxCoeff());
    if (ldlt.info() != Eigen::Success || !C.allFinite() ||
        (M * C - AtP).cwiseAbs().maxCoeff() > 1e-8 * scale)
      throw std::runtime_error("curve approximation: singular normal equations with " +
                               std::to_string(n) +
                               " control points (add smoothing or use "
                               "fewer control points)");
    if (o.closed) {
      c.ctrl.resize(n + p, P.cols());
      c.ctrl.topRows(n) = C;
      c.ctrl.bottomRows(p) = C.topRows(p);
    } else {
      c.ctrl = C;
    }
    const VectorXd d = (A * C - P).rowwise().norm(); // the curve at the sites is A C
    Approximation r;
    r.curve = c;
    r.u = sites;
    r.max_deviation = d.maxCoeff(&r.worst_point);
    r.rms_deviation = std::sqrt(d.squaredNorm() / double(N));
    r.met_tolerance = o.tolerance <= 0 || r.max_deviation <= o.tolerance;
    best = r;
    if (r.met_tolerance || n == N)
      return best;
    n = std::min<Index>(N, 2 * n);
  }
}

} // namespace interlin
