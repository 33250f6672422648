// Normalised primitives: seed 000 (2.30)-(2.31) and §2.8, seed 002 §3.2.
#include "interlin/interflatation/rfunctions/primitives.h"

#include "interlin/interflatation/rfunctions/normalization.h"
#include "interlin/interflatation/rfunctions/r_operations.h"

#include "checks.h"

#include <cmath>
#include <stdexcept>

namespace interlin::rf {

using detail::require_positive;

Expr strip(const Expr& u, const Expr& b) {
  require_positive(b, "strip", "the half-width b");
  return (b * b - u * u) / (2 * b);
}

Expr strip_smooth(const Expr& u, const Expr& b) {
  require_positive(b, "strip_smooth", "the half-width b");
  return (b * b - u * u) / sqrt(3 * b * b + u * u);
}

Expr layer(const Expr& u, const Expr& lo, const Expr& hi) {
  require_positive(hi - lo, "layer", "hi - lo");
  return (u - lo) * (hi - u) / (hi - lo); // seed 000 §2.6, seed 002 §3.2
}

Expr halfplane(const Expr& u, const Expr& v, const Expr& a, const Expr& b, const Expr& c) {
  require_positive(hypot(a, b), "halfplane", "|(a, b)|");
  return (a * u + b * v + c) / hypot(a, b);
}

Expr circle(const Expr& u, const Expr& v, const Expr& R) {
  require_positive(R, "circle", "the radius R");
  return (R * R - u * u - v * v) / (2 * R);
}

Expr circle_smooth(const Expr& u, const Expr& v, const Expr& R) {
  require_positive(R, "circle_smooth", "the radius R");
  const Expr r2 = u * u + v * v;
  return (R * R - r2) / sqrt(3 * R * R + r2);
}

Expr rectangle(const Expr& u, const Expr& v, const Expr& a, const Expr& b) {
  return and0(strip(u, a), strip(v, b));
}

Expr ellipse(const Expr& u, const Expr& v, const Expr& a, const Expr& b) {
  require_positive(a, "ellipse", "the semi-axis a");
  require_positive(b, "ellipse", "the semi-axis b");
  return normalize(1 - u * u / (a * a) - v * v / (b * b));
}

Expr segment(const Expr& u, const Expr& v, double x1, double y1, double x2, double y2) {
  const double l2 = (x2 - x1) * (x2 - x1) + (y2 - y1) * (y2 - y1);
  if (!(l2 > 0) || !std::isfinite(l2))
    throw std::invalid_argument("segment: the end points must be distinct and finite");
  const double l = std::sqrt(l2);
  // seed 000 §2.6: f1 = 2 l (signed distance to the line), f2 = 2 l (coordinate along it, centred)
  const Expr f1 = 2 * ((u - x1) * (y2 - y1) - (v - y1) * (x2 - x1));
  const Expr f2 = (2 * u - x1 - x2) * (x2 - x1) + (2 * v - y1 - y2) * (y2 - y1);
  const Expr g = abs(f2) - l2;
  const Expr h = g + abs(g);
  return sqrt(f1 * f1 + h * h / 4) / (2 * l);
}

Expr halfspace(const Expr& x, const Expr& y, const Expr& z, const Expr& a, const Expr& b,
               const Expr& c, const Expr& d) {
  const Expr n = sqrt(a * a + b * b + c * c);
  require_positive(n, "halfspace", "|(a, b, c)|");
  return (a * x + b * y + c * z + d) / n;
}

Expr sphere(const Expr& x, const Expr& y, const Expr& z, const Expr& R) {
  require_positive(R, "sphere", "the radius R");
  return (R * R - x * x - y * y - z * z) / (2 * R);
}

Expr cuboid(const Expr& x, const Expr& y, const Expr& z, const Expr& a, const Expr& b,
            const Expr& c) {
  return and0(and0(strip(x, a), strip(y, b)), strip(z, c));
}

Expr cylinder(const Expr& x, const Expr& y, const Expr& z, const Expr& R, const Expr& h) {
  return and0(circle(x, y, R), strip(z, h));
}

Expr cone(const Expr& x, const Expr& y, const Expr& z, const Expr& R, const Expr& H) {
  require_positive(R, "cone", "the base radius R");
  require_positive(H, "cone", "the height H");
  const Expr lateral = ((H - z) * R - hypot(x, y) * H) / hypot(R, H);
  return and0(lateral, layer(z, 0.0, H));
}

Expr torus(const Expr& x, const Expr& y, const Expr& z, const Expr& R, const Expr& r) {
  require_positive(R, "torus", "the centre-line radius R");
  require_positive(r, "torus", "the tube radius r");
  const Expr d = hypot(x, y) - R;
  return (r * r - d * d - z * z) / (2 * r);
}

Expr ellipsoid(const Expr& x, const Expr& y, const Expr& z, const Expr& a, const Expr& b,
               const Expr& c) {
  require_positive(a, "ellipsoid", "the semi-axis a");
  require_positive(b, "ellipsoid", "the semi-axis b");
  require_positive(c, "ellipsoid", "the semi-axis c");
  return normalize(1 - x * x / (a * a) - y * y / (b * b) - z * z / (c * c));
}

} // namespace interlin::rf
