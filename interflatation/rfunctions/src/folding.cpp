// Folding symmetry: seed 000 §2.7, Theorems 1, 2, 4, 5 ((2.37)-(2.43)).
#include "interlin/interflatation/rfunctions/folding.h"

#include "interlin/interflatation/rfunctions/r_operations.h"

#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace interlin::rf {

namespace {

constexpr double pi = std::numbers::pi;
const Expr X = Expr::x(), Y = Expr::y(), Z = Expr::z();

void check(const char* function, double period, int N) {
  if (!(period > 0) || !std::isfinite(period) || N < 1) {
    std::ostringstream s;
    s << function << ": need a finite period (h or n) > 0 and N >= 1, got " << period
      << ", N = " << N;
    throw std::invalid_argument(s.str());
  }
}

// sum_{i=1..N} (-1)^(i+1) sin((2i-1) t) / (2i-1)^2: the triangle wave's Fourier series
Expr triangle_series(const Expr& t, int N) {
  Expr s = 0.0;
  for (int i = 1; i <= N; ++i) {
    const double m = 2.0 * i - 1;
    s = s + ((i % 2) ? 1.0 : -1.0) / (m * m) * sin(m * t);
  }
  return s;
}

} // namespace

Expr mu(const Expr& t, double h) {
  check("mu", h, 1);
  return h / pi * asin(sin(pi / h * t)); // (2.37)
}

Expr mu_fourier(const Expr& t, double h, int N) {
  check("mu_fourier", h, N);
  return 4 * h / (pi * pi) * triangle_series(pi / h * t, N); // (2.38)
}

Expr mu_finite(const Expr& t, double h, const Expr& l) {
  return min(min(t, mu(t, h)), l - t); // (2.41)
}

Expr mu_cyclic(const Expr& theta, double n) {
  check("mu_cyclic", n, 1);
  return 2 / n * asin(sin(n / 2 * theta)); // (2.42), the closed form
}

Expr mu_cyclic_fourier(const Expr& theta, double n, int N) {
  check("mu_cyclic_fourier", n, N);
  return 8 / (pi * n) * triangle_series(n / 2 * theta, N);
}

Expr fold_x(const Expr& F, double h) {
  return substitute(F, mu(X, h), Y, Z);
}
Expr fold_x_fourier(const Expr& F, double h, int N) {
  return substitute(F, mu_fourier(X, h, N), Y, Z);
}
Expr fold_x_finite(const Expr& F, double h, const Expr& l) {
  return substitute(F, mu_finite(X, h, l), Y, Z);
}
Expr fold_x_asym(const Expr& F, double h) {
  // (2.39): even copies from the unmirrored branch, odd copies from the branch shifted by h
  const Expr even = and0(substitute(F, mu(X, h), Y, Z), cos(pi / h * X));
  const Expr odd = and0(substitute(F, mu(X - h, h), Y, Z), cos(pi / h * (X - h)));
  return or0(even, odd);
}

namespace {

Expr fold_polar(const Expr& F, const Expr& m) {
  const Expr r = hypot(X, Y);
  return substitute(F, r * cos(m), r * sin(m), Z);
}

} // namespace

Expr fold_cyclic(const Expr& F, double n) {
  return fold_polar(F, mu_cyclic(atan2(Y, X), n)); // Theorem 4
}
Expr fold_cyclic_fourier(const Expr& F, double n, int N) {
  return fold_polar(F, mu_cyclic_fourier(atan2(Y, X), n, N));
}
Expr fold_cyclic_asym(const Expr& F, double n) {
  // (2.43): the copy on the even sectors, and the copy rotated by 2 pi / n on the odd ones
  const Expr theta = atan2(Y, X);
  const Expr shifted = theta - 2 * pi / n;
  const Expr even = and0(fold_polar(F, mu_cyclic(theta, n)), cos(n / 2 * theta));
  const Expr odd = and0(fold_polar(F, mu_cyclic(shifted, n)), cos(n / 2 * shifted));
  return or0(even, odd);
}

} // namespace interlin::rf
