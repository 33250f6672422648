// R-operations, seed 000 §2.2 (formulas (2.1)-(2.9), (2.32)).
#include "interlin/interflatation/rfunctions/r_operations.h"

#include "checks.h"
#include "node.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace interlin::rf {

using detail::make;
using detail::Op;

Expr and0(const Expr& a, const Expr& b) {
  return Expr(make(Op::and0, a.node(), b.node()));
}
Expr or0(const Expr& a, const Expr& b) {
  return Expr(make(Op::or0, a.node(), b.node()));
}
Expr sub0(const Expr& a, const Expr& b) {
  return and0(a, -b);
}
Expr negation(const Expr& a) {
  return -a;
}

namespace {

void check_alpha(const Expr& alpha, const char* function) {
  if (alpha.is_constant()) {
    const double v = alpha.constant_value();
    if (!(v > -1 && v <= 1)) {
      std::ostringstream s;
      s << function << ": alpha must be in (-1, 1], got " << v;
      throw std::invalid_argument(s.str());
    }
  }
}

// seed 000 (2.2): sqrt(a^2 + b^2 - 2 alpha a b) as hypot(a - alpha b, sqrt(1 - alpha^2) b)
Expr alpha_root(const Expr& a, const Expr& b, const Expr& alpha) {
  return hypot(a - alpha * b, sqrt(1 - alpha * alpha) * b);
}

} // namespace

Expr and_alpha(const Expr& a, const Expr& b, const Expr& alpha) {
  check_alpha(alpha, "and_alpha");
  return (a + b - alpha_root(a, b, alpha)) / (1 + alpha);
}
Expr or_alpha(const Expr& a, const Expr& b, const Expr& alpha) {
  check_alpha(alpha, "or_alpha");
  return (a + b + alpha_root(a, b, alpha)) / (1 + alpha);
}
Expr alpha_variable(const Expr& a, const Expr& b) {
  return 2 / (1 + a * a + b * b) - 1; // seed 000 (2.32)
}
Expr and_alpha_variable(const Expr& a, const Expr& b) {
  return and_alpha(a, b, alpha_variable(a, b));
}
Expr or_alpha_variable(const Expr& a, const Expr& b) {
  return or_alpha(a, b, alpha_variable(a, b));
}

Expr and1(const Expr& a, const Expr& b) {
  return min(a, b);
}
Expr or1(const Expr& a, const Expr& b) {
  return max(a, b);
}

namespace {

void check_m(double m, const char* function) {
  if (!(m >= 0) || !std::isfinite(m)) {
    std::ostringstream s;
    s << function << ": m must be a finite number >= 0, got " << m;
    throw std::invalid_argument(s.str());
  }
}

} // namespace

Expr and0m(const Expr& a, const Expr& b, double m) {
  check_m(m, "and0m");
  return and0(a, b) * pow(hypot(a, b), m); // seed 000 (2.5)
}
Expr or0m(const Expr& a, const Expr& b, double m) {
  check_m(m, "or0m");
  return or0(a, b) * pow(hypot(a, b), m);
}

namespace {

Expr p_norm(const Expr& a, const Expr& b, double p, const char* function) {
  if (!(p > 1) || !std::isfinite(p)) {
    std::ostringstream s;
    s << function << ": p must be a finite number > 1, got " << p;
    throw std::invalid_argument(s.str());
  }
  return pow(pow(abs(a), p) + pow(abs(b), p), 1 / p);
}

} // namespace

Expr andp(const Expr& a, const Expr& b, double p) {
  return a + b - p_norm(a, b, p, "andp"); // seed 000 (2.6)
}
Expr orp(const Expr& a, const Expr& b, double p) {
  return a + b + p_norm(a, b, p, "orp");
}

namespace {

// seed 000 (2.7): SR = (rho - r + |rho - r|)^2 / (8 rho) = max(rho - r, 0)^2 / (2 rho)
Expr fillet_term(const Expr& a, const Expr& b, const Expr& rho, const char* function) {
  detail::require_positive(rho, function, "rho");
  const Expr t = max(rho - hypot(a, b), 0.0);
  return t * t / (2 * rho);
}

} // namespace

Expr and_fillet(const Expr& a, const Expr& b, const Expr& rho) {
  return and0(a, b) - fillet_term(a, b, rho, "and_fillet");
}
Expr or_fillet(const Expr& a, const Expr& b, const Expr& rho) {
  return or0(a, b) + fillet_term(a, b, rho, "or_fillet");
}

Expr equiv(const Expr& a, const Expr& b) {
  return a * b; // seed 000 (2.9), "the simplest formula"
}
Expr equiv_eps(const Expr& a, const Expr& b, double eps, int n) {
  if (!(eps > 0) || !std::isfinite(eps) || n < 1) {
    std::ostringstream s;
    s << "equiv_eps: need eps > 0 and n >= 1, got eps = " << eps << ", n = " << n;
    throw std::invalid_argument(s.str());
  }
  const double two_n = 2.0 * n;
  return a * b / pow(eps + pow(a, two_n) + pow(b, two_n), 1 / two_n);
}

} // namespace interlin::rf
