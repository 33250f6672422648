#include "interlin/splines/knots.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::VectorXd;

void check_knots(const VectorXd& knots, int degree, Index num_ctrl) {
  if (degree < 0)
    throw std::invalid_argument("B-spline degree must be >= 0, got " + std::to_string(degree));
  if (num_ctrl < degree + 1)
    throw std::invalid_argument("degree " + std::to_string(degree) + " needs at least " +
                                std::to_string(degree + 1) + " control points, got " +
                                std::to_string(num_ctrl));
  if (knots.size() != num_ctrl + degree + 1)
    throw std::invalid_argument(
        "knot vector has " + std::to_string(knots.size()) +
        " entries, expected #ctrl + degree + 1 = " + std::to_string(num_ctrl + degree + 1));
  for (Index i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots(i)))
      throw std::invalid_argument("knot " + std::to_string(i) + " is not finite");
    if (i > 0 && knots(i) < knots(i - 1))
      throw std::invalid_argument("knots must be non-decreasing: knot " + std::to_string(i) +
                                  " is smaller than knot " + std::to_string(i - 1));
  }
  if (!(knots(degree) < knots(num_ctrl)))
    throw std::invalid_argument("empty parameter domain [knots(p), knots(n)]");
}

Index find_span(const VectorXd& knots, int degree, Index num_ctrl, double u) {
  if (u >= knots(num_ctrl)) {
    // Last non-empty span of the domain.
    Index k = num_ctrl - 1;
    while (k > degree && knots(k) == knots(k + 1))
      --k;
    return k;
  }
  if (u <= knots(degree)) {
    Index k = degree;
    while (k < num_ctrl - 1 && knots(k) == knots(k + 1))
      ++k;
    return k;
  }
  // Largest k in [degree, num_ctrl-1] with knots(k) <= u.
  const auto first = knots.data() + degree, last = knots.data() + num_ctrl;
  return (std::upper_bound(first, last, u) - knots.data()) - 1;
}

VectorXd averaged_knots(const VectorXd& u, int p) {
  const Index n = u.size();
  if (p < 1 || n < p + 1)
    throw std::invalid_argument("averaged_knots: need #u >= degree + 1 >= 2");
  VectorXd t(n + p + 1);
  t.head(p + 1).setConstant(u(0));
  t.tail(p + 1).setConstant(u(n - 1));
  // Piegl & Tiller (9.8): interior knot j+p = mean of u_j .. u_{j+p-1}.
  for (Index j = 1; j < n - p; ++j)
    t(j + p) = u.segment(j, p).mean();
  return t;
}

VectorXd periodic_knots(const VectorXd& u, int p) {
  const Index N = u.size() - 1; // sites u(0..N-1), u(N) closes the loop
  if (p < 1 || N < p + 1)
    throw std::invalid_argument(
        "periodic_knots: need at least degree + 1 = " + std::to_string(p + 1) + " points");
  const double period = u(N) - u(0);
  // One period of knots tau_0 .. tau_N (tau_N = tau_0 + period).
  VectorXd tau(N + 1);
  if (p % 2 == 1) {
    tau = u;
  } else {
    // Knots at midpoints; the period starts at the midpoint before u_0 so that it contains u_0.
    tau(0) = 0.5 * (u(N - 1) - period + u(0));
    for (Index i = 1; i <= N; ++i)
      tau(i) = 0.5 * (u(i - 1) + u(i));
  }
  VectorXd t(N + 2 * p + 1);
  for (Index i = -p; i <= N + p; ++i) {
    const Index w = ((i % N) + N) % N; // index within the period
    const double shift = period * static_cast<double>((i - w) / N);
    t(i + p) = tau(w) + shift;
  }
  return t;
}

// seed 001 ch. 3 (least squares); Piegl & Tiller eq. 9.68-9.69.
VectorXd approximation_knots(const VectorXd& u, int p, Index n) {
  const Index N = u.size();
  if (n == N)
    return averaged_knots(u, p); // interpolation: knot averaging keeps the system regular
  VectorXd t(n + p + 1);
  t.head(p + 1).setConstant(u(0));
  t.tail(p + 1).setConstant(u(N - 1));
  const double d = double(N) / double(n - p);
  for (Index j = 1; j < n - p; ++j) {
    const Index i = static_cast<Index>(std::floor(j * d));
    const double a = j * d - double(i);
    t(p + j) = (1 - a) * u(i - 1) + a * u(i);
  }
  return t;
}

VectorXd periodic_quantile_knots(const VectorXd& u, int p, Index n, const VectorXd& w) {
  const Index N = u.size() - 1;
  if (n == N && w.size() == 0)
    return periodic_knots(u, p); // interpolation: sites (odd p) or midpoints (even p)
  const double period = u(N) - u(0);
  VectorXd W(N + 1); // W(i): weight of the intervals before u_i
  W(0) = 0;
  for (Index i = 0; i < N; ++i)
    W(i + 1) = W(i) + (w.size() != 0 ? w(i) : 1.0);
  VectorXd tau(n);
  for (Index j = 0, i = 0; j < n; ++j) {
    const double x = double(j) * W(N) / double(n);
    while (i + 1 < N && W(i + 1) <= x)
      ++i;
    tau(j) = u(i) + (x - W(i)) / (W(i + 1) - W(i)) * (u(i + 1) - u(i));
  }
  VectorXd t(n + 2 * p + 1);
  for (Index k = 0; k < t.size(); ++k) {
    const Index j = k - p;
    const Index q = ((j % n) + n) % n;
    t(k) = tau(q) + period * double((j - q) / n);
  }
  return t;
}

} // namespace interlin
