#pragma once
// Smooth fields for the interlineation tests: a field with all its partial derivatives as one
// callable, monomials, the digest's T13 function, and the error of an operator against a field.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>

namespace interlin::test {

// f and its partial derivatives as one callable: F(x, y, dx, dy) -> row of dim values.
using Field = std::function<Eigen::RowVectorXd(double, double, int, int)>;

// The d-th derivative of the monomial x^a.
inline double mono(double x, int a, int d) {
  double c = 1;
  for (int m = 0; m < d; ++m)
    c *= a - m;
  return d > a ? 0.0 : c * std::pow(x, a - d);
}

// sin(3x) cos(2y) + x^3 y^3 (digest 001 T13 function), any derivative.
inline Eigen::RowVectorXd t13(double x, double y, int dx, int dy) {
  return Eigen::RowVectorXd::Constant(1, std::pow(3.0, dx) * std::sin(3 * x + dx * M_PI / 2) *
                                                 std::pow(2.0, dy) *
                                                 std::cos(2 * y + dy * M_PI / 2) +
                                             mono(x, 3, dx) * mono(y, 3, dy));
}

// The largest |O f - f| (first components) over the m x m sample of [0, 1]^2, ends included, for
// an operator O with evaluate(O, x, y).
template <class Operator>
double max_error_on_unit_square(const Operator& O, const Field& f, int m) {
  double e = 0;
  for (double x : Eigen::VectorXd::LinSpaced(m, 0, 1))
    for (double y : Eigen::VectorXd::LinSpaced(m, 0, 1))
      e = std::max(e, std::abs(evaluate(O, x, y)(0) - f(x, y, 0, 0)(0)));
  return e;
}

} // namespace interlin::test
