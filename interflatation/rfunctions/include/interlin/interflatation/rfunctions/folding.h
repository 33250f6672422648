#pragma once
// Folding symmetry (seed 000 §2.7): n copies of a body from one, by evaluating the copy in folded
// coordinates instead of joining n bodies with R-operations.

#include "interlin/interflatation/rfunctions/expression.h"

namespace interlin::rf {

// Translational folding functions of period h (the copies sit at x = k h):
//   mu(t, h)            = (h/pi) asin(sin(pi t / h))                   seed 000 (2.37), exact
//   mu_fourier(t, h, N) = (4h/pi^2) sum_{i=1..N} (-1)^(i+1) sin((2i-1) pi t/h) / (2i-1)^2   (2.38)
//   mu_finite(t, h, l)  = min(t, mu(t, h), l - t)                       (2.41), copies on [0, l]
// Cyclic folding functions for n copies around the z axis (copies at angles 2 pi k / n):
//   mu_cyclic(theta, n)            = (2/n) asin(sin(n theta / 2))                       (2.42)
//   mu_cyclic_fourier(theta, n, N) = (8/(pi n)) sum_{k=1..N} (-1)^(k+1) sin((2k-1) n
//   theta/2)/(2k-1)^2
// The Fourier forms are what the seeds' programs use (N = 4 in seed 000 Appendix B and seed 002
// Fig. 2); their slope at the copies is (8/pi^2) sum 1/(2k-1)^2 < 1 (0.92158 for N = 4), which
// widens the copies (seed 000 T16). Throws std::invalid_argument for h <= 0, n < 1, N < 1.
Expr mu(const Expr& t, double h);
Expr mu_fourier(const Expr& t, double h, int N);
Expr mu_finite(const Expr& t, double h, const Expr& l);
Expr mu_cyclic(const Expr& theta, double n);
Expr mu_cyclic_fourier(const Expr& theta, double n, int N);

// Bodies: F(mu(x), y, z) for a copy F symmetric about the plane x = 0 and inside |x| < h/2
// (Theorem 1); fold_x_asym for a copy without that symmetry (Theorem 2, (2.39), with R0).
Expr fold_x(const Expr& F, double h);
Expr fold_x_fourier(const Expr& F, double h, int N);
Expr fold_x_finite(const Expr& F, double h, const Expr& l);
Expr fold_x_asym(const Expr& F, double h);
// Cyclic: F(r cos mu, r sin mu, z), r = sqrt(x^2 + y^2), theta = atan2(y, x), for a copy F about
// the +x axis, symmetric about y = 0, inside the sector |theta| < pi/n (Theorem 4);
// fold_cyclic_asym for a copy without the mirror symmetry (Theorem 5, (2.43), with R0).
Expr fold_cyclic(const Expr& F, double n);
Expr fold_cyclic_fourier(const Expr& F, double n, int N);
Expr fold_cyclic_asym(const Expr& F, double n);

} // namespace interlin::rf
