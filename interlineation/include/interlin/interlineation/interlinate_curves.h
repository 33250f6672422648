#pragma once
// seed 001 §2.5 (blade surface from sections) and digest §5.1 [SUPPLEMENT]: spline-blended
// interlineation on one family of lines v = v_k,
//   O f(u, v) = sum_k f(u, v_k) L_k(v),   L_k(v_l) = delta_kl,
// with L_k the cardinal splines of degree q on the parameters v_k. O reproduces every trace
// f(., v_k) exactly (the interlineation property). When the traces are B-spline curves on one
// knot vector, O f is the tensor-product B-spline whose control-net columns interpolate the
// curves' control points: exactness holds for every u, not only at data points.

#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/bspline_surface.h"

#include <vector>

namespace interlin {

// Inputs:
//   curves   K >= 2 clamped curves in 3-D, one degree and one knot vector (see make_compatible)
//   v        K increasing parameters of the lines v = v_k (v(0) = 0, v(K-1) = 1 by convention)
//   degree_v degree of the blending splines, reduced to K-1 when there are fewer sections
//   closed_u the curves are closed (flag copied to the surface)
// Output: S with S(u, v_k) = curves[k](u) for all u (to round-off of one linear solve).
// Throws std::invalid_argument for incompatible curves or non-increasing v.
BSplineSurface interlinate_curves(const std::vector<BSplineCurve>& curves, const Eigen::VectorXd& v,
                                  int degree_v, bool closed_u);

} // namespace interlin
