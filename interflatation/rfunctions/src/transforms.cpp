// Coordinate transforms: seed 000 §2.8 ((2.46)-(2.48), twisted cylinder, similar sections, cone).
#include "interlin/interflatation/rfunctions/transforms.h"

#include "interlin/interflatation/rfunctions/r_operations.h"

#include "checks.h"

#include <cmath>
#include <stdexcept>

namespace interlin::rf {

namespace {

const Expr X = Expr::x(), Y = Expr::y(), Z = Expr::z();

} // namespace

Expr translate(const Expr& F, const Expr& dx, const Expr& dy, const Expr& dz) {
  return substitute(F, X - dx, Y - dy, Z - dz);
}

// A body rotated by +angle is the old body at the point rotated by -angle.
Expr rotate_x(const Expr& F, const Expr& angle) {
  const Expr c = cos(angle), s = sin(angle);
  return substitute(F, X, c * Y + s * Z, c * Z - s * Y);
}
Expr rotate_y(const Expr& F, const Expr& angle) {
  const Expr c = cos(angle), s = sin(angle);
  return substitute(F, c * X - s * Z, Y, s * X + c * Z);
}
Expr rotate_z(const Expr& F, const Expr& angle) {
  const Expr c = cos(angle), s = sin(angle);
  return substitute(F, c * X + s * Y, c * Y - s * X, Z);
}

Expr rotate(const Expr& F, double ax, double ay, double az, const Expr& angle) {
  const double n = std::sqrt(ax * ax + ay * ay + az * az);
  if (!(n > 0) || !std::isfinite(n))
    throw std::invalid_argument("rotate: the axis must be a finite nonzero vector");
  ax /= n, ay /= n, az /= n;
  // Rodrigues for the angle -angle: p cos + (p x k) sin + k (k.p)(1 - cos)
  const Expr c = cos(angle), s = sin(angle);
  const Expr kp = ax * X + ay * Y + az * Z;
  const Expr t = kp * (1 - c);
  return substitute(F, c * X + s * (Y * az - Z * ay) + ax * t,
                    c * Y + s * (Z * ax - X * az) + ay * t, c * Z + s * (X * ay - Y * ax) + az * t);
}

Expr scale(const Expr& F, const Expr& s) {
  detail::require_positive(s, "scale", "the factor s");
  return s * substitute(F, X / s, Y / s, Z / s);
}

Expr scale_xyz(const Expr& F, const Expr& sx, const Expr& sy, const Expr& sz) {
  detail::require_positive(sx, "scale_xyz", "sx");
  detail::require_positive(sy, "scale_xyz", "sy");
  detail::require_positive(sz, "scale_xyz", "sz");
  return substitute(F, X / sx, Y / sy, Z / sz);
}

// A twist is the rotation by an angle that varies with the point.
Expr twist_z(const Expr& F, const Expr& phi) {
  return rotate_z(F, phi);
}
Expr twist_x(const Expr& F, const Expr& phi) {
  return rotate_x(F, phi);
}
Expr twist_y(const Expr& F, const Expr& phi) {
  return rotate_y(F, phi);
}

Expr revolve_x(const Expr& F) {
  return substitute(F, X, hypot(Y, Z), 0.0); // seed 000 (2.46)
}
Expr revolve_x_smooth(const Expr& F) {
  const Expr r = hypot(Y, Z);
  return or0(substitute(F, X, r, 0.0), substitute(F, X, -r, 0.0)); // (2.47)
}
Expr revolve_z(const Expr& F) {
  return substitute(F, hypot(X, Y), Z, 0.0);
}
Expr revolve_z_smooth(const Expr& F) {
  const Expr r = hypot(X, Y);
  return or0(substitute(F, r, Z, 0.0), substitute(F, -r, Z, 0.0));
}

Expr similar_z(const Expr& F, const Expr& k) {
  return substitute(F, k * X, k * Y, Z) / k;
}

Expr cone_map(const Expr& F, const Expr& x0, const Expr& y0, const Expr& z0) {
  const Expr t = z0 / (Z - z0);
  return substitute(F, x0 - t * (X - x0), y0 - t * (Y - y0), Z);
}

Expr lerp(const Expr& a, const Expr& b, const Expr& t) {
  return a + (b - a) * t;
}

} // namespace interlin::rf
