#pragma once
// Internal: value and partial derivatives of every elementary operation. One inline definition
// per operation serves the batch value kernel, the dual-number kernel and the constant folder.
//
// Convention at singular points (an R0 corner, sqrt or hypot at 0, atan2 at the origin,
// ratio(n, 0)): the singular factor of a derivative is taken as 0, so derivatives stay finite.

#include "node.h"

#include <cmath>
#include <limits>

namespace interlin::rf::detail {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline double ratio(double n, double d) {
  return d != 0 ? n / d : 0.0;
}

inline double sign_of(double a) {
  return static_cast<double>((a > 0) - (a < 0));
}

inline bool is_finite(double v) {
  return std::abs(v) <= std::numeric_limits<double>::max();
}

// R0 (seed 000 (2.1)) where a + b -+ sqrt(a^2 + b^2) is not finite: infinite or undefined
// operands and overflow of the squares. An undefined (NaN) operand is an empty set (-inf), so a
// singular sub-body does not poison a union. s = -1 conjunction, +1 disjunction.
double r0_nonfinite(double a, double b, double s);

// The operations with a value kernel, as X-macro lists for the switches that dispatch them:
// INTERLIN_RF_VALUE_OPS(CASE) expands CASE(add) CASE(sub) ... CASE(or0), the operations an
// expression holds; INTERLIN_RF_IMMEDIATE_OPS(CASE) the immediate forms of compiled programs.
#define INTERLIN_RF_VALUE_OPS(CASE)                                                                \
  CASE(add)                                                                                        \
  CASE(sub)                                                                                        \
  CASE(mul)                                                                                        \
  CASE(div)                                                                                        \
  CASE(neg)                                                                                        \
  CASE(pow_k)                                                                                      \
  CASE(pow)                                                                                        \
  CASE(sqrt)                                                                                       \
  CASE(abs)                                                                                        \
  CASE(sign)                                                                                       \
  CASE(sin)                                                                                        \
  CASE(cos)                                                                                        \
  CASE(tan)                                                                                        \
  CASE(asin)                                                                                       \
  CASE(acos)                                                                                       \
  CASE(atan)                                                                                       \
  CASE(atan2)                                                                                      \
  CASE(exp)                                                                                        \
  CASE(log)                                                                                        \
  CASE(min)                                                                                        \
  CASE(max)                                                                                        \
  CASE(hypot)                                                                                      \
  CASE(ratio)                                                                                      \
  CASE(and0)                                                                                       \
  CASE(or0)
#define INTERLIN_RF_IMMEDIATE_OPS(CASE)                                                            \
  CASE(add_k)                                                                                      \
  CASE(mul_k)                                                                                      \
  CASE(k_sub)                                                                                      \
  CASE(k_div)                                                                                      \
  CASE(div_k)                                                                                      \
  CASE(square)

struct Partials {
  double a = 0, b = 0;
};

template <Op O>
inline double value(double a, double b, double k) {
  if constexpr (O == Op::add)
    return a + b;
  else if constexpr (O == Op::sub)
    return a - b;
  else if constexpr (O == Op::mul)
    return a * b;
  else if constexpr (O == Op::div)
    return a / b;
  else if constexpr (O == Op::neg)
    return -a;
  else if constexpr (O == Op::pow_k)
    return std::pow(a, k);
  else if constexpr (O == Op::pow)
    return std::pow(a, b);
  else if constexpr (O == Op::sqrt)
    return std::sqrt(a);
  else if constexpr (O == Op::abs)
    return std::abs(a);
  else if constexpr (O == Op::sign)
    return sign_of(a);
  else if constexpr (O == Op::sin)
    return std::sin(a);
  else if constexpr (O == Op::cos)
    return std::cos(a);
  else if constexpr (O == Op::tan)
    return std::tan(a);
  else if constexpr (O == Op::asin)
    return std::asin(a);
  else if constexpr (O == Op::acos)
    return std::acos(a);
  else if constexpr (O == Op::atan)
    return std::atan(a);
  else if constexpr (O == Op::atan2)
    return std::atan2(a, b);
  else if constexpr (O == Op::exp)
    return std::exp(a);
  else if constexpr (O == Op::log)
    return std::log(a);
  else if constexpr (O == Op::min) // R1 conjunction; NaN is an empty set
    return (a != a || b != b) ? -kInf : (a < b ? a : b);
  else if constexpr (O == Op::max) // R1 disjunction
    return a != a ? b : (b != b ? a : (a < b ? b : a));
  else if constexpr (O == Op::hypot)
    return std::sqrt(a * a + b * b);
  else if constexpr (O == Op::ratio)
    return ratio(a, b);
  else if constexpr (O == Op::and0 || O == Op::or0) {
    // seed 000 (2.1) without cancellation: where a + b and the root have opposite roles,
    // a + b -+ h = 2ab / (a + b +- h) (an operand 1e30 times the other keeps the small one)
    const double h = std::sqrt(a * a + b * b), s = a + b;
    if constexpr (O == Op::and0)
      return s > 0 ? 2 * a * b / (s + h) : s - h;
    else
      return s < 0 ? 2 * a * b / (s - h) : s + h;
  } else if constexpr (O == Op::add_k)
    return a + k;
  else if constexpr (O == Op::mul_k)
    return a * k;
  else if constexpr (O == Op::k_sub)
    return k - a;
  else if constexpr (O == Op::k_div)
    return k / a;
  else if constexpr (O == Op::div_k)
    return a / k;
  else if constexpr (O == Op::square)
    return a * a;
  else
    static_assert(O == Op::add, "no value kernel for this operation");
}

// Partial derivatives with respect to the operands, given the operands and the value v.
template <Op O>
inline Partials partials(double a, double b, double v, double k) {
  if constexpr (O == Op::add)
    return {1, 1};
  else if constexpr (O == Op::sub)
    return {1, -1};
  else if constexpr (O == Op::mul)
    return {b, a};
  else if constexpr (O == Op::div)
    return {1 / b, -v / b};
  else if constexpr (O == Op::neg)
    return {-1, 0};
  else if constexpr (O == Op::pow_k) // k a^k / a: 0 at a = 0
    return {k * ratio(v, a), 0};
  else if constexpr (O == Op::pow)
    return {b * ratio(v, a), v == 0 ? 0.0 : v * std::log(a)};
  else if constexpr (O == Op::sqrt)
    return {ratio(0.5, v), 0};
  else if constexpr (O == Op::abs)
    return {sign_of(a), 0};
  else if constexpr (O == Op::sign)
    return {0, 0};
  else if constexpr (O == Op::sin)
    return {std::cos(a), 0};
  else if constexpr (O == Op::cos)
    return {-std::sin(a), 0};
  else if constexpr (O == Op::tan)
    return {1 + v * v, 0};
  else if constexpr (O == Op::asin)
    return {1 / std::sqrt(1 - a * a), 0};
  else if constexpr (O == Op::acos)
    return {-1 / std::sqrt(1 - a * a), 0};
  else if constexpr (O == Op::atan)
    return {1 / (1 + a * a), 0};
  else if constexpr (O == Op::atan2) {
    const double r2 = a * a + b * b;
    return {ratio(b, r2), ratio(-a, r2)};
  } else if constexpr (O == Op::exp)
    return {v, 0};
  else if constexpr (O == Op::log)
    return {1 / a, 0};
  else if constexpr (O == Op::min || O == Op::max) {
    // the operand that is the value; the mean where they tie
    if (a == b)
      return {0.5, 0.5};
    return (O == Op::min) == (a < b) ? Partials{1, 0} : Partials{0, 1};
  } else if constexpr (O == Op::hypot)
    return {ratio(a, v), ratio(b, v)};
  else if constexpr (O == Op::ratio)
    return {ratio(1, b), ratio(-v, b)};
  else if constexpr (O == Op::and0 || O == Op::or0) {
    // seed 000 §2.3: d(a ^0 b)/da = 1 - a/r = 1 - cos(phi)
    const double s = O == Op::and0 ? -1.0 : 1.0, r = std::sqrt(a * a + b * b);
    if (!is_finite(a) || !is_finite(b)) // the finite operand (or neither) carries the value
      return {is_finite(a) ? 1.0 : 0.0, is_finite(b) ? 1.0 : 0.0};
    return {1 + s * ratio(a, r), 1 + s * ratio(b, r)};
  } else if constexpr (O == Op::add_k)
    return {1, 0};
  else if constexpr (O == Op::mul_k)
    return {k, 0};
  else if constexpr (O == Op::k_sub)
    return {-1, 0};
  else if constexpr (O == Op::k_div)
    return {-v / a, 0};
  else if constexpr (O == Op::div_k)
    return {1 / k, 0};
  else if constexpr (O == Op::square)
    return {2 * a, 0};
  else
    static_assert(O == Op::add, "no partials for this operation");
}

// The value with the R0 fix-up for infinite, undefined and overflowing operands.
template <Op O>
inline double checked_value(double a, double b, double k) {
  const double v = value<O>(a, b, k);
  if constexpr (O == Op::and0 || O == Op::or0)
    if (!is_finite(v))
      return r0_nonfinite(a, b, O == Op::and0 ? -1.0 : 1.0);
  return v;
}

// Runtime dispatch for the constant folder: the value of `op` at constant operands.
double fold_value(Op op, double a, double b, double k);

} // namespace interlin::rf::detail
