#pragma once
// R-operations (seed 000 §2.2, seed 002 §3.1): conjunction (intersection), disjunction (union) and
// negation (complement) of bodies {w >= 0}, as expressions. Each keeps the sign rule of its
// Boolean counterpart; they differ in smoothness and in how they treat normalised operands.

#include "interlin/interflatation/rfunctions/expression.h"

namespace interlin::rf {

// R0 (seed 000 (2.1)): a ^0 b = a + b - sqrt(a^2 + b^2), a v0 b = a + b + sqrt(a^2 + b^2).
// C-infinity except where a = b = 0; the operations of RFPreview's rfAND / rfOR. An undefined
// operand (NaN) counts as an empty set; infinite operands give the limits (a ^0 +inf = a).
Expr and0(const Expr& a, const Expr& b);
Expr or0(const Expr& a, const Expr& b);
// a without b: a ^0 (-b)  (seed 003 §3.1, "diff").
Expr sub0(const Expr& a, const Expr& b);
// Negation: -a (seed 000 §2.2).
Expr negation(const Expr& a);

// R-alpha (seed 000 (2.2)): (a + b -+ sqrt(a^2 + b^2 - 2 alpha a b)) / (1 + alpha), for
// -1 < alpha <= 1; alpha may be any expression (variable alpha). alpha = 0 gives R0, alpha = 1
// R1. The radicand is evaluated as (a - alpha b)^2 + (1 - alpha^2) b^2, never negative.
// Throws std::invalid_argument for a constant alpha outside (-1, 1].
Expr and_alpha(const Expr& a, const Expr& b, const Expr& alpha);
Expr or_alpha(const Expr& a, const Expr& b, const Expr& alpha);
// The variable alpha of seed 000 (2.32): 2 / (1 + a^2 + b^2) - 1, equal to 1 exactly where
// a = b = 0, so normalised operands meeting smoothly keep |grad| = 1 at the junction.
Expr alpha_variable(const Expr& a, const Expr& b);
Expr and_alpha_variable(const Expr& a, const Expr& b);
Expr or_alpha_variable(const Expr& a, const Expr& b);

// R1 (seed 000 (2.4)): min and max. Not differentiable where a = b.
Expr and1(const Expr& a, const Expr& b);
Expr or1(const Expr& a, const Expr& b);

// R0^m (seed 000 (2.5)): (a + b -+ sqrt(a^2 + b^2)) (a^2 + b^2)^(m/2), derivatives up to order
// m continuous at a = b = 0. Throws std::invalid_argument for m < 0.
Expr and0m(const Expr& a, const Expr& b, double m);
Expr or0m(const Expr& a, const Expr& b, double m);

// Rp (seed 000 (2.6)): a + b -+ (|a|^p + |b|^p)^(1/p), p > 1 (p = 2 is R0). Throws
// std::invalid_argument for p <= 1.
Expr andp(const Expr& a, const Expr& b, double p);
Expr orp(const Expr& a, const Expr& b, double p);

// R-rho, rounding of the corner with radius rho (seed 000 (2.7)):
// a ^0 b - SR and a v0 b + SR, SR = (rho - r + |rho - r|)^2 / (8 rho), r = sqrt(a^2 + b^2).
// For perpendicular normalised half-planes the corner becomes a circular arc of radius rho.
// Throws std::invalid_argument for a constant rho <= 0.
Expr and_fillet(const Expr& a, const Expr& b, const Expr& rho);
Expr or_fillet(const Expr& a, const Expr& b, const Expr& rho);

// Equivalence (seed 000 (2.9)): a ~ b = a b, and the smoothed family
// a ~ b = a b / (eps + a^(2n) + b^(2n))^(1/(2n)), eps > 0, n >= 1 (associative).
Expr equiv(const Expr& a, const Expr& b);
Expr equiv_eps(const Expr& a, const Expr& b, double eps, int n);

} // namespace interlin::rf
