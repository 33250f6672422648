#include "interlin/splines/bspline_curve.h"

#include "interlin/splines/knots.h"
#include "interlin/splines/spline_basis.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

double domain_begin(const BSplineCurve& c) {
  return c.knots(c.degree);
}
double domain_end(const BSplineCurve& c) {
  return c.knots(c.ctrl.rows());
}

PiecewiseCurve to_piecewise(const BSplineCurve& c) {
  const int p = c.degree;
  const Index n = c.ctrl.rows();
  check_knots(c.knots, p, n);
  if (!c.ctrl.allFinite())
    throw std::invalid_argument("control points must be finite");
  const SplineBasis B = explicit_basis(c.knots, p);
  std::vector<Index> spans;
  for (Index k = p; k < n; ++k)
    if (c.knots(k) < c.knots(k + 1))
      spans.push_back(k);
  PiecewiseCurve pc;
  pc.degree = p;
  pc.periodic = c.periodic;
  pc.breaks.resize(static_cast<Index>(spans.size()) + 1);
  pc.coeffs.resize(static_cast<Index>(spans.size()) * (p + 1), c.ctrl.cols());
  for (Index j = 0; j < static_cast<Index>(spans.size()); ++j) {
    const Index k = spans[j];
    pc.breaks(j) = c.knots(k);
    // Power coefficients of span k: sum_r N_{k-p+r} coefficients times control point k-p+r.
    pc.coeffs.middleRows(j * (p + 1), p + 1) =
        B.coeffs.middleRows((k - p) * (p + 1), p + 1).transpose() * c.ctrl.middleRows(k - p, p + 1);
  }
  pc.breaks(pc.breaks.size() - 1) = c.knots(n);
  return pc;
}

namespace {

// Span index j and local coordinate h = u - breaks(j); periodic curves wrap u first.
Index locate(const PiecewiseCurve& c, double& u) {
  const Index s = c.breaks.size() - 1;
  const double a = c.breaks(0), b = c.breaks(s);
  if (c.periodic && (u < a || u >= b))
    u = a + (u - a) - (b - a) * std::floor((u - a) / (b - a));
  if (u <= a)
    return 0;
  if (u >= b)
    return s - 1;
  return std::upper_bound(c.breaks.data(), c.breaks.data() + s + 1, u) - c.breaks.data() - 1;
}

} // namespace

MatrixXd evaluate(const PiecewiseCurve& c, const VectorXd& u, int deriv) {
  if (deriv < 0)
    throw std::invalid_argument("derivative order must be >= 0");
  const int p = c.degree;
  const Index dim = c.coeffs.cols();
  MatrixXd out = MatrixXd::Zero(u.size(), dim);
  if (deriv > p)
    return out;
  // q (q - 1) ... (q - deriv + 1): the factor of coefficient q in the deriv-th derivative
  std::vector<double> falling(size_t(p) + 1, 1.0);
  for (int q = deriv; q <= p; ++q)
    for (int m = 0; m < deriv; ++m)
      falling[size_t(q)] *= q - m;
  // Scalar Horner per coordinate: a dynamic-size row expression per step costs several times more.
  for (Index i = 0; i < u.size(); ++i) {
    double ui = u(i);
    const Index j = locate(c, ui);
    const double h = ui - c.breaks(j);
    for (Index d = 0; d < dim; ++d) {
      const double* a = &c.coeffs(j * (p + 1), d);
      double sum = 0;
      for (int q = p; q >= deriv; --q)
        sum = sum * h + falling[size_t(q)] * a[q];
      out(i, d) = sum;
    }
  }
  return out;
}

MatrixXd evaluate(const BSplineCurve& c, const VectorXd& u, int deriv) {
  return evaluate(to_piecewise(c), u, deriv);
}

} // namespace interlin
