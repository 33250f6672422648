#pragma once
// Normalisation (seed 000 §2.6, seed 002 §3.2): functions whose gradient has unit length on the
// boundary, so that w approximates the signed distance near it; pieces of curves; walls of a
// given thickness.

#include "interlin/interflatation/rfunctions/expression.h"

namespace interlin::rf {

// |grad w| as an expression.
Expr gradient_norm(const Expr& w);

// Seed 000 (2.26), seed 002 §3.2: w / sqrt(w^2 + |grad w|^2). Same sign as w, |grad| = 1 where
// w = 0 (with grad w != 0); 0 where w and grad w both vanish. The gradient is formed by graph
// differentiation, so the result is itself exactly differentiable.
Expr normalize(const Expr& w);

// Seed 000 (2.27): w / |grad w| (0 where grad w = 0).
Expr normalize_by_gradient(const Expr& w);

// Piece of a curve, seed 000 (2.34) / seed 002 §5.1: with f = 0 a normalised curve and
// phi >= 0 a normalised region selecting the piece,
//   w = sqrt(f^2 + ((sqrt(phi^2 + f^4) - phi) / 2)^2)
// is >= 0, 0 exactly on the piece, about |f| along it and about the distance to the end points
// near them. Not the Euclidean distance far from the piece (seed 000 T13).
Expr piece(const Expr& f, const Expr& phi);

// Walls of thickness delta around the boundary of a normalised body w (seed 000 §2.6):
//   wall(w, d)       = d - |w|           the layer |w| <= d, total thickness 2 d (Soyuz-Apollo
//   form) inner_wall(w, d) = w (d - w) / d     the inner shell 0 <= w <= d, normalised on both
//   faces
// Throws std::invalid_argument for a constant d <= 0.
Expr wall(const Expr& w, const Expr& d);
Expr inner_wall(const Expr& w, const Expr& d);

} // namespace interlin::rf
