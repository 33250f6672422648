#pragma once
// Gordon surface of a network of B-spline curves as ONE tensor-product B-spline (digest 001 §5.1
// [SUPPLEMENT], seed 001 §2.5: a surface through sections and user lines):
//   S(u, v) = sum_k beta_k(v) C_k(u) + sum_l alpha_l(u) G_l(v) - sum_k sum_l alpha_l(u) beta_k(v)
//   Q_kl
// for curves C_k at v = v_k (the sections) and G_l at u = u_l (the guides), Q_kl = C_k(u_l) =
// G_l(v_k). Each of the three terms is a tensor-product B-spline (cardinal splines times curves);
// after bringing the blending functions to the curves' degrees and all terms to common knot
// vectors (knot insertion) the sum is one control net: S(u, v_k) = C_k(u) and S(u_l, v) = G_l(v)
// for every u and v.

#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/bspline_surface.h"

#include <vector>

namespace interlin {

// Inputs:
//   sections   K >= 2 clamped 3-D curves C_k(u), one degree p and one domain [u0, u1]
//   v          K increasing parameters of the sections
//   guides     L >= 0 clamped 3-D curves G_l(v), one degree q and domain [v(0), v(K-1)]
//              (L = 0 gives the one-family interlineation of interlinate_curves)
//   u          L increasing parameters of the guides in [u0, u1) (closed_u) or [u0, u1]
//   degree_v   blending degree along v (reduced to K-1); the surface's v degree is
//              max(q, that degree): the lower one is elevated
//   closed_u   the sections are closed (C^(p-1) across u0 = u1): alpha_l are periodic cardinal
//              splines, cubic for p >= 3 (the surface stays C2 across the guides when p > 3),
//              linear for p < 3; otherwise open cardinal splines of degree min(p, L-1)
//   tolerance  compatibility |C_k(u_l) - G_l(v_k)| <= tolerance * max(1, |Q_kl|)
//   knots_v    optional knot vector of the v blending functions (degree min(degree_v, K-1),
//              Schoenberg-Whitney for v); default knot averaging. Callers that build the guides
//              pass knots shared with them, so the union has no near-coincident knots (knots of
//              different curves closer than 1e-12 of the domain are merged in any case).
// Output: the surface; closed_u copied. Throws std::invalid_argument for incompatible curves
// (message names section k and guide l and the gap) or bad sizes.
BSplineSurface gordon_bspline(const std::vector<BSplineCurve>& sections, const Eigen::VectorXd& v,
                              const std::vector<BSplineCurve>& guides, const Eigen::VectorXd& u,
                              int degree_v, bool closed_u, double tolerance = 1e-10,
                              const Eigen::VectorXd& knots_v = Eigen::VectorXd());

} // namespace interlin
