// All basis functions of a knot vector in explicit per-span form (seed 001, Theorem 1).
#include "interlin/splines/spline_basis.h"

#include "interlin/splines/explicit_bspline.h"
#include "interlin/splines/knots.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

SplineBasis explicit_basis(const VectorXd& knots, int p) {
  const Index n = knots.size() - p - 1;
  check_knots(knots, p, n);
  SplineBasis B;
  B.degree = p;
  B.knots = knots;
  B.num_ctrl = n;
  B.coeffs = MatrixXd::Zero((n - p) * (p + 1), p + 1);
  VectorXd inv_fact(p + 1);
  inv_fact(0) = 1;
  for (int q = 1; q <= p; ++q)
    inv_fact(q) = inv_fact(q - 1) / q;
  for (Index i = 0; i < n; ++i) {
    const VectorXd X = knots.segment(i, p + 2);
    if (!(X(0) < X(p + 1)))
      continue; // identically zero basis function (knot of multiplicity p+2)
    const ExplicitBSpline N = explicit_bspline(X, p);
    for (Index k = std::max<Index>(i, p); k <= std::min<Index>(i + p, n - 1); ++k) {
      if (!(knots(k) < knots(k + 1)))
        continue;
      const Index j =
          std::lower_bound(N.breaks.data(), N.breaks.data() + N.breaks.size(), knots(k)) -
          N.breaks.data();
      const Index r = i - (k - p);
      // Taylor data D^(q)/q! are the power-basis coefficients of (u - t_k)^q.
      B.coeffs.row((k - p) * (p + 1) + r) = N.taylor.row(j).cwiseProduct(inv_fact.transpose());
    }
  }
  // Partition of unity, span by span: sum_r N_r = 1 means the summed coefficients are (1,0,..,0).
  // The explicit construction integrates from the left end of each support, so extreme ratios of
  // neighbouring span lengths amplify round-off (~ ratio^p); refuse instead of returning garbage.
  for (Index k = p; k < n; ++k) {
    const double h = knots(k + 1) - knots(k);
    if (!(h > 0))
      continue;
    double defect = 0, hq = 1;
    for (int q = 0; q <= p; ++q, hq *= h)
      defect = std::max(defect,
                        std::abs(B.coeffs.middleRows((k - p) * (p + 1), p + 1).col(q).sum() * hq -
                                 (q == 0 ? 1.0 : 0.0)));
    if (defect > 1e-10)
      throw std::runtime_error("explicit B-spline basis: knot spans too nonuniform near u = " +
                               std::to_string(knots(k)) + " (partition-of-unity defect " +
                               std::to_string(defect) + "); merge nearly coincident knots");
  }
  return B;
}

MatrixXd basis_derivatives(const SplineBasis& B, double u, int nderiv, Index* span_out) {
  const int p = B.degree;
  const Index k = find_span(B.knots, p, B.num_ctrl, u);
  if (span_out)
    *span_out = k;
  const double s = u - B.knots(k);
  const auto block = B.coeffs.middleRows((k - p) * (p + 1), p + 1);
  MatrixXd out = MatrixXd::Zero(nderiv + 1, p + 1);
  for (int d = 0; d <= std::min(nderiv, p); ++d) {
    for (int r = 0; r <= p; ++r) {
      // Horner on sum_{q>=d} c_q q!/(q-d)! s^(q-d).
      double v = 0;
      for (int q = p; q >= d; --q) {
        double falling = 1;
        for (int m = 0; m < d; ++m)
          falling *= q - m;
        v = v * s + block(r, q) * falling;
      }
      out(d, r) = v;
    }
  }
  return out;
}

void collocation_entries(const SplineBasis& B, const VectorXd& u, int deriv, Index wrap,
                         std::vector<Index>& rows, std::vector<Index>& cols,
                         std::vector<double>& vals) {
  const int p = B.degree;
  for (Index i = 0; i < u.size(); ++i) {
    Index k;
    const MatrixXd N = basis_derivatives(B, u(i), deriv, &k);
    for (int r = 0; r <= p; ++r) {
      const Index c = k - p + r;
      rows.push_back(i);
      cols.push_back(wrap > 0 ? c % wrap : c);
      vals.push_back(N(deriv, r));
    }
  }
}

} // namespace interlin
