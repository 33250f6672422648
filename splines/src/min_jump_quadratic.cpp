// seed 001, Theorem 2 (digest 001 §2.3): interpolating quadratic spline with minimal jumps of S''.
#include "interlin/splines/min_jump_quadratic.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::VectorXd;

namespace {

void check_nodes(const VectorXd& x, const VectorXd& y) {
  if (x.size() < 2)
    throw std::invalid_argument("Theorem 2 spline needs at least 2 nodes, got " +
                                std::to_string(x.size()));
  if (y.size() != x.size())
    throw std::invalid_argument("Theorem 2 spline: " + std::to_string(x.size()) + " nodes but " +
                                std::to_string(y.size()) + " values");
  if (!x.allFinite() || !y.allFinite())
    throw std::invalid_argument("Theorem 2 spline: nodes and values must be finite");
  for (Index i = 1; i < x.size(); ++i)
    if (!(x(i) > x(i - 1)))
      throw std::invalid_argument("Theorem 2 spline: nodes must increase strictly (node " +
                                  std::to_string(i) + ")");
}

// h_i and Delta_{1,i} (0-based: h(i) = x(i+1) - x(i)).
void differences(const VectorXd& x, const VectorXd& y, VectorXd& h, VectorXd& d1) {
  const Index n = x.size() - 1;
  h = x.tail(n) - x.head(n);
  d1 = (y.tail(n) - y.head(n)).cwiseQuotient(h);
}

} // namespace

double theorem2_m12(const VectorXd& x, const VectorXd& y) {
  check_nodes(x, y);
  const Index N = x.size();
  if (N == 2)
    return 0.0;
  VectorXd h, d1;
  differences(x, y, h, d1);
  // 1-based seed indices j = 2..N-1 map to 0-based piece j-1; A(j-1) holds A_j.
  VectorXd A = VectorXd::Zero(N - 1);
  double num = 0, a = 0, alt = 0; // alt = sum_{k=2}^{j} (-1)^{j-k} Delta_{2,k-1}
  for (Index j = 2; j <= N - 1; ++j) {
    const double d2 = d1(j - 1) - d1(j - 2); // Delta_{2,j-1}
    alt = d2 - alt;
    A(j - 1) = 2.0 / h(j - 1) * alt;
    const double aj = 1.0 / h(j - 2) + 1.0 / h(j - 1);
    const double sign = (j - 1) % 2 == 0 ? 1.0 : -1.0; // (-1)^{j-1}
    num += sign * aj * (A(j - 1) - A(j - 2));
    a += aj * aj;
  }
  return -num / (h(0) * a);
}

VectorXd theorem2_recurrence(const VectorXd& x, const VectorXd& y, double m12) {
  check_nodes(x, y);
  VectorXd h, d1;
  differences(x, y, h, d1);
  VectorXd M(h.size());
  M(0) = m12;
  for (Index i = 1; i < M.size(); ++i)
    M(i) = (2.0 * (d1(i) - d1(i - 1)) - h(i - 1) * M(i - 1)) / h(i);
  return M;
}

VectorXd theorem2_explicit(const VectorXd& x, const VectorXd& y, double m12) {
  check_nodes(x, y);
  VectorXd h, d1;
  differences(x, y, h, d1);
  VectorXd M(h.size());
  for (Index i = 1; i <= M.size(); ++i) { // seed index i: M_{i,i+1} = M(i-1)
    double sum = 0;
    for (Index k = 2; k <= i; ++k)
      sum += ((i + k) % 2 == 0 ? 1.0 : -1.0) * (d1(k - 1) - d1(k - 2));
    const double sign = (i + 1) % 2 == 0 ? 1.0 : -1.0;
    M(i - 1) = (2.0 * sum + sign * h(0) * m12) / h(i - 1);
  }
  return M;
}

MinJumpQuadratic min_jump_quadratic(const VectorXd& x, const VectorXd& y) {
  MinJumpQuadratic S;
  S.x = x;
  S.y = y;
  S.M = theorem2_recurrence(x, y, theorem2_m12(x, y));
  return S;
}

double jump_functional(const MinJumpQuadratic& S) {
  const Index n = S.M.size();
  return n < 2 ? 0.0 : (S.M.tail(n - 1) - S.M.head(n - 1)).squaredNorm();
}

VectorXd evaluate(const MinJumpQuadratic& S, const VectorXd& t, int deriv) {
  if (deriv < 0)
    throw std::invalid_argument("derivative order must be >= 0");
  if (S.x.size() < 2 || S.y.size() != S.x.size() || S.M.size() != S.x.size() - 1)
    throw std::invalid_argument("Theorem 2 spline: inconsistent sizes");
  VectorXd out(t.size());
  const Index last = S.M.size() - 1;
  for (Index k = 0; k < t.size(); ++k) {
    const double u = t(k);
    const Index i = std::clamp<Index>(
        std::upper_bound(S.x.data(), S.x.data() + S.x.size(), u) - S.x.data() - 1, 0, last);
    const double x0 = S.x(i), x1 = S.x(i + 1), h = x1 - x0, M = S.M(i);
    const double slope = (S.y(i + 1) - S.y(i)) / h;
    switch (deriv) {
    case 0:
      out(k) = ((x1 - u) * S.y(i) + (u - x0) * S.y(i + 1)) / h + 0.5 * M * (u - x0) * (u - x1);
      break;
    case 1:
      out(k) = slope + 0.5 * M * (2.0 * u - x0 - x1);
      break;
    case 2:
      out(k) = M;
      break;
    default:
      out(k) = 0.0;
    }
  }
  return out;
}

} // namespace interlin
