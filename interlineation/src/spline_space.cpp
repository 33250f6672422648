// Collocation in a given spline space (Greville sites) and degree elevation by it.
#include "interlin/interlineation/spline_space.h"

#include "interlin/splines/knots.h"
#include "interlin/splines/spline_basis.h"

#include <Eigen/LU>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

VectorXd greville_abscissae(const VectorXd& knots, int p) {
  if (p < 1)
    throw std::invalid_argument("greville_abscissae: degree must be >= 1");
  const Index n = knots.size() - p - 1;
  check_knots(knots, p, n);
  VectorXd xi(n);
  for (Index i = 0; i < n; ++i)
    xi(i) = knots.segment(i + 1, p).mean();
  return xi;
}

BSplineCurve interpolate_in_space(const std::function<MatrixXd(const VectorXd&)>& f,
                                  const VectorXd& knots, int p) {
  const VectorXd xi = greville_abscissae(knots, p);
  const MatrixXd F = f(xi);
  if (F.rows() != xi.size() || !F.allFinite())
    throw std::invalid_argument("interpolate_in_space: f must return one finite row per site");
  return interpolate_in_space(F, xi, knots, p);
}

BSplineCurve interpolate_in_space(const MatrixXd& F, const VectorXd& xi, const VectorXd& knots,
                                  int p) {
  const Index n = xi.size();
  check_knots(knots, p, knots.size() - p - 1);
  if (n != knots.size() - p - 1 || F.rows() != n || !F.allFinite() || !xi.allFinite())
    throw std::invalid_argument("interpolate_in_space: one finite point per basis function "
                                "expected (#sites = #knots - degree - 1)");
  for (Index i = 1; i < n; ++i)
    if (!(xi(i) > xi(i - 1)))
      throw std::invalid_argument("interpolate_in_space: sites must increase strictly");
  const SplineBasis B = explicit_basis(knots, p);
  std::vector<Index> r, c;
  std::vector<double> v;
  collocation_entries(B, xi, 0, 0, r, c, v);
  MatrixXd A = MatrixXd::Zero(n, n);
  for (size_t e = 0; e < v.size(); ++e)
    A(r[e], c[e]) += v[e];
  const Eigen::PartialPivLU<MatrixXd> lu(A);
  BSplineCurve out;
  out.degree = p;
  out.knots = knots;
  out.ctrl = lu.solve(F);
  const double scale = std::max(1.0, F.cwiseAbs().maxCoeff());
  if (!out.ctrl.allFinite() || (A * out.ctrl - F).cwiseAbs().maxCoeff() > 1e-10 * scale)
    throw std::runtime_error("interpolate_in_space: collocation matrix is singular (the sites "
                             "violate the Schoenberg-Whitney condition for the knots)");
  // A valid but badly placed site/knot pattern interpolates with wild oscillation between the
  // sites (control points far outside the data's range): refuse it rather than return it.
  const Eigen::RowVectorXd mid = F.colwise().mean();
  const double spread = (F.rowwise() - mid).cwiseAbs().maxCoeff();
  if ((out.ctrl.rowwise() - mid).cwiseAbs().maxCoeff() > 1e3 * spread + 1e-9 * scale)
    throw std::runtime_error("interpolate_in_space: the sites are badly placed for the knots "
                             "(control points exceed the data's spread 1000-fold)");
  return out;
}

BSplineCurve elevate_degree(const BSplineCurve& c, int degree) {
  if (c.periodic)
    throw std::invalid_argument("elevate_degree: clamped curves only");
  const int p = c.degree;
  check_knots(c.knots, p, c.ctrl.rows());
  if (degree < p)
    throw std::invalid_argument("elevate_degree: target degree " + std::to_string(degree) +
                                " is below the curve's degree " + std::to_string(p));
  if (degree == p)
    return c;
  const Index n = c.ctrl.rows();
  const double a = c.knots(p), b = c.knots(n);
  std::vector<double> t(static_cast<size_t>(degree + 1), a);
  for (Index i = p + 1; i < n; ++i) {
    const bool first = c.knots(i) != c.knots(i - 1);
    t.push_back(c.knots(i));
    if (first)
      t.insert(t.end(), static_cast<size_t>(degree - p), c.knots(i));
  }
  t.insert(t.end(), static_cast<size_t>(degree + 1), b);
  const PiecewiseCurve pc = to_piecewise(c);
  return interpolate_in_space([&](const VectorXd& s) { return evaluate(pc, s); },
                              Eigen::Map<const VectorXd>(t.data(), static_cast<Index>(t.size())),
                              degree);
}

} // namespace interlin
