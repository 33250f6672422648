#pragma once
// Normalised primitives (seed 000 (2.30)-(2.31), seed 002 §3.2): each is >= 0 inside, 0 on its
// boundary with |grad| = 1 there, so R-operations of them stay normalised (seed 000 §2.6,
// "normalisation is inherited"). Coordinates are explicit arguments, so a primitive is placed by
// shifting or transforming them (circle(x - 2, y, 1)). Sizes are half-widths and radii.
// Every function throws std::invalid_argument when a size is a constant <= 0; sizes may also be
// expressions (lofting: a radius that varies with z).

#include "interlin/interflatation/rfunctions/expression.h"

namespace interlin::rf {

// 2D (functions of two coordinates; in space they are infinite cylinders)
Expr strip(const Expr& u, const Expr& b); // |u| <= b: (b^2 - u^2) / (2b)
Expr strip_smooth(const Expr& u,
                  const Expr& b); // (b^2 - u^2) / sqrt(3 b^2 + u^2), -> -|u| as b -> 0
Expr layer(const Expr& u, const Expr& lo,
           const Expr& hi); // lo <= u <= hi: (u - lo)(hi - u)/(hi - lo)
Expr halfplane(const Expr& u, const Expr& v, const Expr& a, const Expr& b,
               const Expr& c);                            // a u + b v + c >= 0, divided by |(a, b)|
Expr circle(const Expr& u, const Expr& v, const Expr& R); // (R^2 - u^2 - v^2) / (2R)
Expr circle_smooth(const Expr& u, const Expr& v, const Expr& R); // / sqrt(3R^2 + u^2 + v^2)
Expr rectangle(const Expr& u, const Expr& v, const Expr& a, const Expr& b); // strip ^0 strip
Expr ellipse(const Expr& u, const Expr& v, const Expr& a,
             const Expr& b); // normalize(1 - u^2/a^2 - v^2/b^2)
// Normal function of the segment (x1,y1)-(x2,y2), seed 000 §2.6 [R]: the distance to it (>= 0,
// zero on the segment) written as (1/(2l)) sqrt(f1^2 + ((|f2| - l^2) + ||f2| - l^2|)^2 / 4).
Expr segment(const Expr& u, const Expr& v, double x1, double y1, double x2, double y2);

// 3D
Expr halfspace(const Expr& x, const Expr& y, const Expr& z, const Expr& a, const Expr& b,
               const Expr& c, const Expr& d); // a x + b y + c z + d >= 0, divided by |(a, b, c)|
Expr sphere(const Expr& x, const Expr& y, const Expr& z, const Expr& R); // (R^2 - r^2) / (2R)
Expr cuboid(const Expr& x, const Expr& y, const Expr& z, const Expr& a, const Expr& b,
            const Expr& c); // |x| <= a, |y| <= b, |z| <= c: strips joined by ^0
// Cylinder about the z axis: radius R, |z| <= h.
Expr cylinder(const Expr& x, const Expr& y, const Expr& z, const Expr& R, const Expr& h);
// Cone about the z axis: base radius R at z = 0, apex at z = H; the lateral face as the signed
// distance to its generator line ((H - z) R - rho H) / sqrt(R^2 + H^2), ^0 the layer 0 <= z <= H.
Expr cone(const Expr& x, const Expr& y, const Expr& z, const Expr& R, const Expr& H);
// Torus about the z axis: centre-line radius R, tube radius r: (r^2 - (rho - R)^2 - z^2) / (2r).
Expr torus(const Expr& x, const Expr& y, const Expr& z, const Expr& R, const Expr& r);
Expr ellipsoid(const Expr& x, const Expr& y, const Expr& z, const Expr& a, const Expr& b,
               const Expr& c); // normalize(1 - x^2/a^2 - y^2/b^2 - z^2/c^2)

} // namespace interlin::rf
