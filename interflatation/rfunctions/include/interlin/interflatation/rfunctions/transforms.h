#pragma once
// Coordinate transforms of bodies (seed 000 §2.8): each returns F evaluated at transformed
// coordinates (a substitution, see substitute()). Angles in radians; rotations move the body
// (counter-clockwise about the axis seen from its positive end).

#include "interlin/interflatation/rfunctions/expression.h"

namespace interlin::rf {

Expr translate(const Expr& F, const Expr& dx, const Expr& dy, const Expr& dz); // body moved by d
Expr rotate_x(const Expr& F, const Expr& angle);
Expr rotate_y(const Expr& F, const Expr& angle);
Expr rotate_z(const Expr& F, const Expr& angle);
// Rotation about the axis (ax, ay, az) through the origin (Rodrigues). Throws
// std::invalid_argument for a zero axis.
Expr rotate(const Expr& F, double ax, double ay, double az, const Expr& angle);
// Uniform scaling s F(x/s, y/s, z/s): keeps a normalised F normalised. Throws for constant s <= 0.
Expr scale(const Expr& F, const Expr& s);
// Scaling along the axes F(x/sx, y/sy, z/sz) (does not keep normalisation).
Expr scale_xyz(const Expr& F, const Expr& sx, const Expr& sy, const Expr& sz);

// Twist about the z axis (seed 000 §2.8, "twisted cylinder", helical coordinates):
// x <- x cos(phi) + y sin(phi), y <- -x sin(phi) + y cos(phi), phi an expression (phi = alpha z for
// a helix of constant pitch, min/max of linear laws for local twists, seed 000 Fig. 2.24).
// twist_x and twist_y: the same about x (y, z rotate) and y (z, x rotate).
Expr twist_z(const Expr& F, const Expr& phi);
Expr twist_x(const Expr& F, const Expr& phi);
Expr twist_y(const Expr& F, const Expr& phi);

// Body of revolution (seed 000 (2.46)-(2.47)) from a profile F(u, v) given in x (u) and y (v):
//   revolve_x(F)        = F(x, sqrt(y^2 + z^2))       about the x axis
//   revolve_x_smooth(F) = F(x, r) v0 F(x, -r)          smooth on the axis (2.47)
//   revolve_z(F)        = F(sqrt(x^2 + y^2), z)       about the z axis (u radial, v along z)
//   revolve_z_smooth(F) = F(r, z) v0 F(-r, z)
Expr revolve_x(const Expr& F);
Expr revolve_x_smooth(const Expr& F);
Expr revolve_z(const Expr& F);
Expr revolve_z_smooth(const Expr& F);

// Similar sections along z (seed 000 §2.8): F(k x, k y, z) / k with k = k(z), k(0) = 1.
Expr similar_z(const Expr& F, const Expr& k);
// Cone over the section F(x, y) in the plane z = 0 with apex (x0, y0, z0) (seed 000 §2.8):
// x <- x0 - z0 (x - x0) / (z - z0), y <- y0 - z0 (y - y0) / (z - z0); z unchanged.
Expr cone_map(const Expr& F, const Expr& x0, const Expr& y0, const Expr& z0);
// Lofting helper (seed 000 (2.48), parameters varying with z): a + (b - a) t.
Expr lerp(const Expr& a, const Expr& b, const Expr& t);

} // namespace interlin::rf
