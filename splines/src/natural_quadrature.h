#pragma once
// Quadrature of vector-valued integrands for the natural-parametrization code (seed 004 §2.4):
// the book's composite trapezoid rule and an adaptive Gauss–Legendre rule. Private to splines/.

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace interlin::detail {

// Nodes and weights of the 8-point Gauss–Legendre rule on [-1, 1] (Newton on P_8).
struct GaussLegendre8 {
  std::array<double, 8> x{}, w{};
  GaussLegendre8() {
    const int n = 8;
    for (int i = 0; i < n; ++i) {
      double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z; // Legendre recurrence up to P_n
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-17)
          break;
      }
      x[static_cast<size_t>(i)] = z;
      w[static_cast<size_t>(i)] = 2 / ((1 - z * z) * dp * dp);
    }
  }
};

inline const GaussLegendre8& gauss_legendre8() {
  static const GaussLegendre8 rule;
  return rule;
}

template <class F>
auto gauss_panel(const F& f, double a, double b) {
  const GaussLegendre8& g = gauss_legendre8();
  const double m = 0.5 * (a + b), r = 0.5 * (b - a);
  auto sum = (g.w[0] * f(m + r * g.x[0])).eval();
  for (size_t i = 1; i < 8; ++i)
    sum += g.w[i] * f(m + r * g.x[i]);
  return (r * sum).eval();
}

template <class F, class V>
V adaptive_panel(const F& f, double a, double b, const V& whole, double tol, int depth) {
  const double m = 0.5 * (a + b);
  const V left = gauss_panel(f, a, m), right = gauss_panel(f, m, b);
  const V halves = left + right;
  if (depth >= 40 || (halves - whole).cwiseAbs().maxCoeff() <= tol * std::abs(b - a))
    return halves;
  return adaptive_panel(f, a, m, left, tol, depth + 1) +
         adaptive_panel(f, m, b, right, tol, depth + 1);
}

// int_a^b f by adaptive Gauss–Legendre: first panels no longer than 1 / (1 + scale) (scale
// bounds the angular speed of the integrand), each halved until the two halves agree with the
// whole to tol * panel length.
template <class F>
auto adaptive_gauss(const F& f, double a, double b, double tol, double scale) {
  using V = decltype(gauss_panel(f, a, b));
  const double len = std::abs(b - a);
  const int n = static_cast<int>(std::min(1e5, std::ceil(len * (1.0 + scale)))) + 1;
  V sum = V::Zero();
  for (int i = 0; i < n; ++i) {
    const double p = a + (b - a) * i / n, q = a + (b - a) * (i + 1) / n;
    sum += adaptive_panel(f, p, q, gauss_panel(f, p, q), tol, 0);
  }
  return sum;
}

// Composite trapezoid rule with n panels on [a, b] (seed 004 §1.4: n = 2000).
template <class F>
auto trapezoid(const F& f, double a, double b, int n) {
  const double h = (b - a) / n;
  auto sum = (0.5 * (f(a) + f(b))).eval();
  for (int i = 1; i < n; ++i)
    sum += f(a + h * i);
  return (h * sum).eval();
}

} // namespace interlin::detail
