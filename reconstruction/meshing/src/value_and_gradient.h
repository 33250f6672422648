#pragma once
// F and grad F at a batch of points, for meshers that need the gradient of any ImplicitFunction.
#include "interlin/interflatation/implicit_function.h"

namespace interlin::detail {

// F and grad F at the rows of X: f.gradient, else central differences with step d.
inline void value_and_gradient(const ImplicitFunction& f, const Points3& X, double d,
                               Eigen::Ref<Eigen::VectorXd> F, Eigen::Ref<Points3> G) {
  if (f.gradient) {
    f.gradient(X, F, G);
    return;
  }
  f.value(X, F);
  for (int a = 0; a < 3; ++a) {
    Points3 Q = X;
    Eigen::VectorXd Fp(X.rows()), Fm(X.rows());
    Q.col(a).array() += d;
    f.value(Q, Fp);
    Q.col(a).array() -= 2 * d;
    f.value(Q, Fm);
    G.col(a) = (Fp - Fm) / (2 * d);
  }
}

} // namespace interlin::detail
