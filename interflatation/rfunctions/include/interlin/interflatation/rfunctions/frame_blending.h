#pragma once
// Blending on a frame (seed 000 §2.9, (2.49); seed 002 §5): a body around a skeleton, built from
// the generalised-normalised distance to the skeleton minus a radius law along it.

#include "interlin/interflatation/rfunctions/expression.h"

namespace interlin::rf {

// Distance-like function of the segment -a <= u <= a of the u axis, for a point at distance
// r >= 0 from the axis: piece(r, (a^2 - u^2) / (2a)), seed 000 (2.34)/(2.49) ("ff").
// Throws std::invalid_argument for a constant a <= 0.
Expr segment_frame(const Expr& u, const Expr& r, const Expr& a);

// The blended body of seed 000 (2.49): -segment_frame(u, r, a) + (a1 - u)(a2 + u) / p1 + p2,
// a body of revolution about the u axis with radius close to (a1 - u)(a2 + u)/p1 + p2 (a1, a2:
// nose and tail, p1: fullness, p2: rounding of the ends). With u = x, r = sqrt(y^2 + z^2) it is
// the UAV fuselage of seed 000 Appendix B; with r = |y| the 2D profile of seed 002 §5.2 (which
// writes -p2). Throws std::invalid_argument for a constant p1 == 0.
Expr blend_segment(const Expr& u, const Expr& r, const Expr& a, const Expr& a1, const Expr& a2,
                   const Expr& p1, const Expr& p2);

// Distance-like function of the circular arc of radius R about the origin of the (u, v) plane
// spanning the angles -beta <= theta <= beta (0 < beta < pi): piece(R - sqrt(u^2 + v^2), phi)
// with phi the normalised wedge of those angles (R0 of the two boundary lines). Seed 000 §2.9
// builds a Joukowski-like wing on an arc frame but its formula (2.50) is lost; this is the
// digest's suggested reconstruction [R]: zero exactly on the arc, about |R - r| along it.
// Throws std::invalid_argument for a constant R <= 0 or beta outside (0, pi).
Expr arc_frame(const Expr& u, const Expr& v, const Expr& R, double beta);

} // namespace interlin::rf
