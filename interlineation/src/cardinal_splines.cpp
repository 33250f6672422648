// Cardinal splines: open (interpolation of the identity) and periodic (cyclic spline system).
#include "interlin/interlineation/cardinal_splines.h"

#include "interlin/interlineation/spline_space.h"
#include "interlin/splines/interpolate_curve.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

void check_nodes(const VectorXd& x) {
  if (x.size() < 1 || !x.allFinite())
    throw std::invalid_argument("cardinal splines need at least one finite node");
  for (Index i = 1; i < x.size(); ++i)
    if (!(x(i) > x(i - 1)))
      throw std::invalid_argument("cardinal spline nodes must increase strictly (node " +
                                  std::to_string(i) + ")");
}

// alpha_0 = 1 on [a, b]: one linear segment with both control values 1.
BSplineCurve constant_one(double a, double b) {
  BSplineCurve c;
  c.degree = 1;
  c.knots.resize(4);
  c.knots << a, a, b, b;
  c.ctrl = MatrixXd::Ones(2, 1);
  return c;
}

CardinalSplines finish(CardinalSplines c) {
  c.basis = explicit_basis(c.curve.knots, c.curve.degree);
  return c;
}

} // namespace

CardinalSplines cardinal_splines(const VectorXd& nodes, int degree) {
  check_nodes(nodes);
  if (degree < 1)
    throw std::invalid_argument("cardinal spline degree must be >= 1");
  CardinalSplines c;
  c.nodes = nodes;
  const Index n = nodes.size();
  if (n == 1)
    throw std::invalid_argument("an open cardinal family needs at least 2 nodes");
  c.curve = interpolate_open(MatrixXd::Identity(n, n), nodes, degree);
  return finish(c);
}

CardinalSplines periodic_cardinal_splines(const VectorXd& nodes, double begin, double period,
                                          int degree) {
  check_nodes(nodes);
  if (!(period > 0) || !std::isfinite(begin) || !std::isfinite(period))
    throw std::invalid_argument("periodic cardinal splines need a finite positive period");
  if (degree != 1 && degree != 3)
    throw std::invalid_argument("periodic cardinal splines have degree 1 or 3, got " +
                                std::to_string(degree));
  const Index n = nodes.size();
  if (nodes(0) < begin || nodes(n - 1) >= begin + period)
    throw std::invalid_argument("periodic cardinal spline nodes must lie in [begin, begin + "
                                "period)");
  CardinalSplines c;
  c.nodes = nodes;
  c.periodic = true;
  c.begin = begin;
  c.period = period;
  if (n == 1) {
    c.curve = constant_one(begin, begin + period);
    return finish(c);
  }
  // h_i = x_{i+1} - x_i with x_n = x_0 + period.
  VectorXd h(n);
  for (Index i = 0; i < n; ++i)
    h(i) = (i + 1 < n ? nodes(i + 1) : nodes(0) + period) - nodes(i);
  // Second derivatives M (n by n, column l for alpha_l): zero for hats, the cyclic system for
  // cubics (rows i = 0..n-1, neighbours i-1 and i+1 taken modulo n).
  MatrixXd M = MatrixXd::Zero(n, n);
  if (degree == 3) {
    MatrixXd A = MatrixXd::Zero(n, n), R = MatrixXd::Zero(n, n);
    for (Index i = 0; i < n; ++i) {
      const Index im = (i + n - 1) % n, ip = (i + 1) % n;
      A(i, im) += h(im);
      A(i, i) += 2 * (h(im) + h(i));
      A(i, ip) += h(i);
      // 6 [(y_{i+1} - y_i)/h_i - (y_i - y_{i-1})/h_{i-1}] for y = e_l, all l at once.
      R(i, ip) += 6 / h(i);
      R(i, i) -= 6 / h(i) + 6 / h(im);
      R(i, im) += 6 / h(im);
    }
    M = Eigen::PartialPivLU<MatrixXd>(A).solve(R);
  }
  // Values on the interval [x_i, x_{i+1}] (the standard cubic spline form with moments M).
  const auto value = [&](double x) {
    double t = x - nodes(0);
    t -= period * std::floor(t / period);
    Index i = n - 1;
    for (Index k = 0; k + 1 < n; ++k)
      if (t < nodes(k + 1) - nodes(0)) {
        i = k;
        break;
      }
    const Index ip = (i + 1) % n;
    const double a = nodes(i) - nodes(0) + h(i) - t, b = t - (nodes(i) - nodes(0)), hi = h(i);
    Eigen::RowVectorXd y = Eigen::RowVectorXd::Zero(n);
    y(i) += a / hi;
    y(ip) += b / hi;
    y += M.row(i) * (a * a * a / hi - a * hi) / 6 + M.row(ip) * (b * b * b / hi - b * hi) / 6;
    return y;
  };
  // Knots: the period's ends and every node inside it (simple knots keep C^(degree-1)).
  std::vector<double> t(static_cast<size_t>(degree + 1), begin);
  for (Index i = 0; i < n; ++i)
    if (nodes(i) > begin)
      t.push_back(nodes(i));
  t.insert(t.end(), static_cast<size_t>(degree + 1), begin + period);
  c.curve = interpolate_in_space(
      [&](const VectorXd& s) {
        MatrixXd F(s.size(), n);
        for (Index k = 0; k < s.size(); ++k)
          F.row(k) = value(s(k));
        return F;
      },
      Eigen::Map<const VectorXd>(t.data(), static_cast<Index>(t.size())), degree);
  return finish(c);
}

MatrixXd evaluate(const CardinalSplines& c, double x, int nderiv) {
  if (c.periodic)
    x = c.begin + (x - c.begin) - c.period * std::floor((x - c.begin) / c.period);
  Index span;
  const MatrixXd N = basis_derivatives(c.basis, x, nderiv, &span);
  const int p = c.curve.degree;
  return N * c.curve.ctrl.middleRows(span - p, p + 1);
}

} // namespace interlin
