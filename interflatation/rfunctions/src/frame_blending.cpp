// Blending on a frame: seed 000 §2.9 (2.49) and Appendix B (the UAV fuselage "wp").
#include "interlin/interflatation/rfunctions/frame_blending.h"

#include "interlin/interflatation/rfunctions/normalization.h"
#include "interlin/interflatation/rfunctions/r_operations.h"

#include "checks.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace interlin::rf {

Expr segment_frame(const Expr& u, const Expr& r, const Expr& a) {
  detail::require_positive(a, "segment_frame", "the half-length a");
  return piece(r, (a * a - u * u) / (2 * a)); // "fi" and "ff" of (2.49)
}

Expr blend_segment(const Expr& u, const Expr& r, const Expr& a, const Expr& a1, const Expr& a2,
                   const Expr& p1, const Expr& p2) {
  if (p1.is_constant() && p1.constant_value() == 0)
    throw std::invalid_argument("blend_segment: p1 must be nonzero");
  return -segment_frame(u, r, a) + (a1 - u) * (a2 + u) / p1 + p2;
}

Expr arc_frame(const Expr& u, const Expr& v, const Expr& R, double beta) {
  detail::require_positive(R, "arc_frame", "the radius R");
  if (!(beta > 0 && beta < std::numbers::pi))
    throw std::invalid_argument("arc_frame: beta must be in (0, pi)");
  // theta <= beta: on the clockwise side of the ray at +beta; theta >= -beta likewise
  const double s = std::sin(beta), c = std::cos(beta);
  const Expr below = s * u - c * v, above = s * u + c * v; // unit normals: normalised lines
  const Expr wedge = beta <= std::numbers::pi / 2 ? and0(below, above) : or0(below, above);
  return piece(R - hypot(u, v), wedge);
}

} // namespace interlin::rf
