// Normalisation, pieces of curves and walls: seed 000 §2.6 ((2.26), (2.27), (2.34)).
#include "interlin/interflatation/rfunctions/normalization.h"

#include "checks.h"
#include "node.h"

namespace interlin::rf {

Expr gradient_norm(const Expr& w) {
  const Expr wx = derivative(w, 0), wy = derivative(w, 1), wz = derivative(w, 2);
  return sqrt(wx * wx + wy * wy + wz * wz);
}

namespace {

Expr safe_ratio(const Expr& n, const Expr& d) {
  return Expr(detail::make(detail::Op::ratio, n.node(), d.node()));
}

} // namespace

Expr normalize(const Expr& w) {
  const Expr wx = derivative(w, 0), wy = derivative(w, 1), wz = derivative(w, 2);
  return safe_ratio(w, sqrt(w * w + wx * wx + wy * wy + wz * wz)); // (2.26)
}

Expr normalize_by_gradient(const Expr& w) {
  return safe_ratio(w, gradient_norm(w)); // (2.27)
}

Expr piece(const Expr& f, const Expr& phi) {
  const Expr f2 = f * f;
  const Expr t = (sqrt(phi * phi + f2 * f2) - phi) / 2; // (2.34)
  return sqrt(f2 + t * t);
}

Expr wall(const Expr& w, const Expr& d) {
  detail::require_positive(d, "wall", "the half-thickness d");
  return d - abs(w);
}

Expr inner_wall(const Expr& w, const Expr& d) {
  detail::require_positive(d, "inner_wall", "the thickness d");
  return w * (d - w) / d;
}

} // namespace interlin::rf
