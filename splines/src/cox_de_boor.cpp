// Cox–de Boor recursion, the reference the explicit form is tested against.
#include "interlin/splines/cox_de_boor.h"

#include "interlin/splines/knots.h"

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

VectorXd cox_de_boor_values(const VectorXd& knots, int p, Index num_ctrl, double u, Index* span) {
  return cox_de_boor_derivatives(knots, p, num_ctrl, u, 0, span).row(0).transpose();
}

MatrixXd cox_de_boor_derivatives(const VectorXd& t, int p, Index num_ctrl, double u, int nd,
                                 Index* span_out) {
  const Index k = find_span(t, p, num_ctrl, u);
  if (span_out)
    *span_out = k;
  // Triangular table: ndu(j, r) basis values of degree j (upper) and knot differences (lower).
  MatrixXd ndu(p + 1, p + 1);
  VectorXd left(p + 1), right(p + 1);
  ndu(0, 0) = 1.0;
  for (int j = 1; j <= p; ++j) {
    left(j) = u - t(k + 1 - j);
    right(j) = t(k + j) - u;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu(j, r) = right(r + 1) + left(j - r);
      const double temp = ndu(r, j - 1) / ndu(j, r);
      ndu(r, j) = saved + right(r + 1) * temp;
      saved = left(j - r) * temp;
    }
    ndu(j, j) = saved;
  }
  MatrixXd ders = MatrixXd::Zero(nd + 1, p + 1);
  for (int j = 0; j <= p; ++j)
    ders(0, j) = ndu(j, p);
  MatrixXd a(2, p + 1);
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a(0, 0) = 1.0;
    for (int d = 1; d <= nd && d <= p; ++d) {
      double D = 0.0;
      const int rk = r - d, pk = p - d;
      if (r >= d) {
        a(s2, 0) = a(s1, 0) / ndu(pk + 1, rk);
        D = a(s2, 0) * ndu(rk, pk);
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? d - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a(s2, j) = (a(s1, j) - a(s1, j - 1)) / ndu(pk + 1, rk + j);
        D += a(s2, j) * ndu(rk + j, pk);
      }
      if (r <= pk) {
        a(s2, d) = -a(s1, d - 1) / ndu(pk + 1, r);
        D += a(s2, d) * ndu(r, pk);
      }
      ders(d, r) = D;
      std::swap(s1, s2);
    }
  }
  double factor = p;
  for (int d = 1; d <= nd && d <= p; ++d) {
    ders.row(d) *= factor;
    factor *= p - d;
  }
  return ders;
}

} // namespace interlin
