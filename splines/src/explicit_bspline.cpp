// seed 001, Theorem 1 (digest 001 §2.1, §2.1.3): explicit B-splines on nonuniform knots.
#include "interlin/splines/explicit_bspline.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

double factorial(int k) {
  double f = 1;
  for (int i = 2; i <= k; ++i)
    f *= i;
  return f;
}

using MatrixXl = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;

// Taylor data D^(q)(b + h) of the polynomial whose Taylor data at b is a, in place
// (digest §2.1.3 update): D^(q) <- sum_i D^(q+i) h^i / i!. Ascending q reads only entries not
// yet overwritten.
template <class Vec, class Scalar>
void shift_taylor(Vec& a, Scalar h) {
  const size_t n1 = static_cast<size_t>(a.size());
  for (size_t q = 0; q < n1; ++q) {
    Scalar sum = 0, hp = 1, fact = 1;
    for (size_t i = 0; q + i < n1; ++i) {
      sum += a[q + i] * hp / fact;
      hp *= h;
      fact *= static_cast<Scalar>(i + 1);
    }
    a[q] = sum;
  }
}

void check_local_knots(const VectorXd& X, int n) {
  if (n < 0)
    throw std::invalid_argument("B-spline degree must be >= 0");
  if (X.size() != n + 2)
    throw std::invalid_argument("a degree-" + std::to_string(n) + " B-spline needs " +
                                std::to_string(n + 2) + " knots, got " + std::to_string(X.size()));
  for (Index i = 0; i < X.size(); ++i) {
    if (!std::isfinite(X(i)))
      throw std::invalid_argument("knots must be finite");
    if (i > 0 && X(i) < X(i - 1))
      throw std::invalid_argument("knots must be non-decreasing");
  }
  if (!(X(0) < X(n + 1)))
    throw std::invalid_argument("B-spline support [X_0, X_{n+1}] is empty");
}

// Coefficients a^(q) of N^(q) in the degree-(n-q) B-splines N_{j,n-q}(X_j..X_{j+n-q+1}),
// q = 0..n, by the derivative recurrence (no cancellation: a^(q) alternates in sign).
// Row q holds a^(q)_0..a^(q)_q.
MatrixXl derivative_coefficients(const VectorXd& X, int n) {
  MatrixXl a = MatrixXl::Zero(n + 1, n + 2);
  a(0, 0) = 1;
  for (int q = 0; q < n; ++q) {
    const int p = n - q;
    for (int j = 0; j <= q + 1; ++j) {
      const long double den = static_cast<long double>(X(j + p)) - X(j);
      if (den > 0) // otherwise N_{j,p-1} is the zero function
        a(q + 1, j) = p * (a(q, j) - (j >= 1 ? a(q, j - 1) : 0.0L)) / den;
    }
  }
  return a;
}

void require_simple(const VectorXd& X, int n, const char* who) {
  check_local_knots(X, n);
  if (n < 1)
    throw std::invalid_argument(std::string(who) + " needs degree >= 1");
  for (Index i = 1; i < X.size(); ++i)
    if (!(X(i) > X(i - 1)))
      throw std::invalid_argument(std::string(who) + " needs simple knots");
}

} // namespace

ExplicitBSpline explicit_bspline(const VectorXd& X, int n) {
  check_local_knots(X, n);
  std::vector<double> b; // distinct breakpoints b_0 < ... < b_s
  for (Index i = 0; i < X.size(); ++i)
    if (b.empty() || X(i) > b.back())
      b.push_back(X(i));
  const Index s = static_cast<Index>(b.size()) - 1;
  for (double v : b)
    if (std::count(X.data(), X.data() + X.size(), v) > n + 1)
      throw std::invalid_argument("knot multiplicity exceeds degree + 1");
  const MatrixXl a = derivative_coefficients(X, n);
  // Jump of N^(q) at b: the degree-p = n-q B-spline N_{j,p} is discontinuous only where its own
  // knots X_j..X_{j+p+1} hold b with multiplicity p+1: it switches on (starts with value 1) when
  // b = X_j = X_{j+p} < X_{j+p+1}, and off when X_j < X_{j+1} = X_{j+p+1} = b.
  const auto jump = [&](int q, double v) {
    const int p = n - q;
    long double J = 0;
    for (int j = 0; j <= q; ++j) {
      if (X(j) == v && X(j + p) == v && X(j + p + 1) > v)
        J += a(q, j);
      if (X(j) < v && X(j + 1) == v && X(j + p + 1) == v)
        J -= a(q, j);
    }
    return J;
  };
  ExplicitBSpline N;
  N.degree = n;
  N.breaks = Eigen::Map<const VectorXd>(b.data(), s + 1);
  N.taylor.resize(s, n + 1);
  // (2): integrate from X_0, where every derivative starts at 0, adding the jumps at the knots.
  // Extended precision: the forward integration carries absolute errors from short spans into
  // long ones (growth ~ (span ratio)^n); 64-bit mantissas keep that below double round-off for
  // the ratios met in practice (docs/formulas.md has the measured table).
  std::vector<long double> D(static_cast<size_t>(n) + 1, 0.0L);
  for (Index t = 0; t < s; ++t) {
    for (int q = 0; q <= n; ++q) {
      D[static_cast<size_t>(q)] += jump(q, b[t]);
      N.taylor(t, q) = static_cast<double>(D[static_cast<size_t>(q)]);
    }
    shift_taylor(D, static_cast<long double>(b[t + 1]) - b[t]);
  }
  return N;
}

double closure_residual(const ExplicitBSpline& N, const VectorXd& X) {
  const int n = N.degree;
  const Index s = N.breaks.size() - 1;
  const auto m_last = std::count(X.data(), X.data() + X.size(), X(X.size() - 1));
  VectorXd end = N.taylor.row(s - 1).transpose();
  shift_taylor(end, N.breaks(s) - N.breaks(s - 1));
  double r = 0;
  for (int q = 0; q <= n - m_last; ++q)
    r = std::max(r, std::abs(end(q)) / std::max(1e-300, N.taylor.col(q).cwiseAbs().maxCoeff()));
  return r;
}

double evaluate(const ExplicitBSpline& N, double x, int deriv) {
  const Index s = N.breaks.size() - 1;
  if (deriv < 0)
    throw std::invalid_argument("derivative order must be >= 0");
  if (deriv > N.degree || x < N.breaks(0) || x >= N.breaks(s))
    return 0.0;
  Index j = std::upper_bound(N.breaks.data(), N.breaks.data() + s + 1, x) - N.breaks.data() - 1;
  const double h = x - N.breaks(j);
  // Horner on sum_{q>=deriv} D^(q) h^(q-deriv)/(q-deriv)!.
  double r = 0;
  for (int q = N.degree; q >= deriv; --q)
    r = r * h / (q - deriv + 1) + N.taylor(j, q);
  return r;
}

VectorXd theorem1_y(const VectorXd& X, int n) {
  require_simple(X, n, "theorem1_y");
  // N^(n-1) = sum_j a_j N_{j,1}: the hat N_{j,1} peaks at X_{j+1}, so y_k = a_{k-1}.
  return derivative_coefficients(X, n).row(n - 1).head(n).transpose().cast<double>();
}

VectorXd theorem1_y_solve(const VectorXd& X, int n) {
  require_simple(X, n, "theorem1_y_solve");
  // D^(q)(X_k), q = 0..n-1, as linear functions of y = (y_1..y_n): propagate the seed's Taylor
  // update (digest §2.1.3) with slope (y_k - y_{k-1})/h_k on span k and y_0 = y_{n+1} = 0.
  MatrixXd D = MatrixXd::Zero(n, n); // row q, column: coefficient of y_{col+1}
  for (int k = 1; k <= n + 1; ++k) {
    const double h = X(k) - X(k - 1);
    VectorXd slope = VectorXd::Zero(n); // (y_k - y_{k-1})/h as a row over y
    if (k <= n)
      slope(k - 1) += 1 / h;
    if (k >= 2)
      slope(k - 2) -= 1 / h;
    MatrixXd next = MatrixXd::Zero(n, n);
    for (int q = 0; q < n; ++q) {
      double hp = 1, fact = 1;
      for (int i = 0; q + i < n; ++i) {
        next.row(q) += D.row(q + i) * hp / fact;
        hp *= h;
        fact *= i + 1;
      }
      next.row(q) += slope.transpose() * hp / fact; // the n-th derivative term h^(n-q)/(n-q)!
    }
    D = next;
  }
  // (3): D^(q)(X_{n+1}) = 0 for q = 0..n-2 (q = n-1 is y_{n+1} = 0, built in). y_1 = 1.
  VectorXd y(n);
  y(0) = 1;
  if (n > 1) {
    const MatrixXd A = D.topRows(n - 1).rightCols(n - 1);
    y.tail(n - 1) = A.fullPivLu().solve(-D.topRows(n - 1).col(0));
  }
  double y1 = factorial(n);
  for (int j = 2; j <= n; ++j)
    y1 /= X(j) - X(0);
  return y * y1;
}

VectorXd theorem1_y_closed_form(const VectorXd& X, int n) {
  require_simple(X, n, "theorem1_y_closed_form");
  VectorXd y(n);
  const double sign = (n - 1) % 2 == 0 ? 1.0 : -1.0;
  for (int k = 1; k <= n; ++k) {
    double sum = 0;
    for (int j = k + 1; j <= n + 1; ++j) {
      double w = 1;
      for (int i = 0; i <= n + 1; ++i)
        if (i != j)
          w *= X(j) - X(i);
      sum += (X(j) - X(k)) / w;
    }
    y(k - 1) = sign * factorial(n) * (X(n + 1) - X(0)) * sum;
  }
  return y;
}

} // namespace interlin
