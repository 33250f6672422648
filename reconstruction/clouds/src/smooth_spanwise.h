#pragma once
// Spanwise smoothing of fitted sections: one tensor-product least-squares surface through all
// slices' points instead of one curve per slice, so that each section borrows strength from its
// neighbours where the body varies smoothly along the span; Mallows' C_p decides between the two.
// See also: fit_sliced_scan (its SliceFitOptions::smooth_span).

#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>
#include <vector>

namespace interlin::detail {

// Result.
//   curves        K closed cubics, the surface's isocurves at the stations (periodic on [0, 1],
//                 one knot vector, leading edge at 0), or the input curves when the sections
//                 fitted one by one win
//   u             K parameter vectors: each point's foot on its curve
//   span_control  the surface's control points along the span (0: the sections kept)
struct SpanwiseSections {
  std::vector<BSplineCurve> curves;
  std::vector<Eigen::VectorXd> u;
  Eigen::Index span_control = 0;
};

// S(u, v) = sum_ab B_a(u) N_b(v) Q_ab (a tensor-product least-squares surface through all slices'
// points, as seed 001 ch. 3 fits one curve by least squares), B periodic cubic, N clamped cubic at
// the scaled stations (approximation_knots):
//   - parameters: each point's foot on its section's fit, mapped piecewise linearly so that the
//     fit's edges (its extreme points along its chord) sit at 0 and at one common parameter;
//   - knots around: where the sections turn (turning_weights averaged on the common parameter,
//     capped by the points they hold);
//   - Q by least squares at those parameters, then at the points' feet on the isocurves
//     S(., v_k) (parameter correction; the pass of least RSS is kept);
//   - counts: spanwise 4 ... K (from the sections' median count around), then more around, by
//     least C_p = RSS + 2 s2 kDofPerControl #a #b with RSS at the feet; a net whose isocurve
//     strays from its slice's points (farther from the two points around it than they are
//     apart, plus 4 sigma) is no candidate;
// and the net wins only if its C_p is below the sections' own
// sum_k (RSS_k + 2 s2 kDofPerControl control_k).
// Inputs: P K point sets (#P_k by dim), u K parameter vectors (#P_k, in [0, 1)) on curves (K
// closed fits, periodic on [0, 1], starting at the leading edge), v K increasing stations scaled
// to [0, 1], s2 the noise variance, threads for the per-slice steps (results identical).
SpanwiseSections smooth_spanwise(const std::vector<Eigen::MatrixXd>& P,
                                 const std::vector<Eigen::VectorXd>& u,
                                 const std::vector<BSplineCurve>& curves, const Eigen::VectorXd& v,
                                 double s2, int threads);

} // namespace interlin::detail
