#pragma once
// Helpers of the R-function tests: compile an expression and evaluate it at single points.

#include "interlin/interflatation/rfunctions/expression.h"

#include <Eigen/Core>

namespace interlin::test {

// F(p) through the compiled batch program (the path every user of the library takes).
inline double value_at(const ImplicitFunction& f, double x, double y, double z = 0) {
  Points3 P(1, 3);
  P << x, y, z;
  Eigen::VectorXd F(1);
  f.value(P, F);
  return F(0);
}

inline Eigen::Vector3d gradient_at(const ImplicitFunction& f, double x, double y, double z = 0) {
  Points3 P(1, 3);
  P << x, y, z;
  Eigen::VectorXd F(1);
  Points3 G(1, 3);
  f.gradient(P, F, G);
  return G.row(0).transpose();
}

inline ImplicitFunction compiled(const rf::Expr& e) {
  return rf::compile(e, Eigen::AlignedBox3d(Eigen::Vector3d(-1, -1, -1), Eigen::Vector3d(1, 1, 1)));
}

inline double value_at(const rf::Expr& e, double x, double y, double z = 0) {
  return value_at(compiled(e), x, y, z);
}

inline Eigen::Vector3d gradient_at(const rf::Expr& e, double x, double y, double z = 0) {
  return gradient_at(compiled(e), x, y, z);
}

// Central difference of f at p along each axis, step h.
inline Eigen::Vector3d central_difference(const ImplicitFunction& f, const Eigen::Vector3d& p,
                                          double h) {
  Eigen::Vector3d g;
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector3d a = p, b = p;
    a(c) += h;
    b(c) -= h;
    g(c) = (value_at(f, a.x(), a.y(), a.z()) - value_at(f, b.x(), b.y(), b.z())) / (2 * h);
  }
  return g;
}

} // namespace interlin::test
