#pragma once
// Sectioned scans -> fitted sections -> loft: each slice's profile is ordered (order_profile),
// fitted by a closed least-squares cubic (seed 001 ch. 3: "the coefficients are found by least
// squares"; splines/approximate_curve) whose number of control points is chosen from the noise,
// and the fitted curves themselves are lofted (seed 001 §2.5, interlinate_curves): the surface
// contains every fitted section curve, at every parameter. See also: detect_slices,
// loft_sections, build_section_body (its LoftResult overload takes SlicedFit::loft).

#include "interlin/reconstruction/clouds/slices.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace interlin {

struct SliceFitOptions {
  double noise = 0; // sigma of the scan noise; 0: the family's spread (noise normal to the slices)
  // Samples per fitted section (FittedSection::section), evenly spaced by arc length (0: 8 x
  // the curve's control points, >= 400).
  int samples = 0;
  int threads = 0; // sections fitted in parallel; 0: all hardware threads (results identical)
  // Smooth along the span: the sections become isocurves of one least-squares surface through
  // all slices' points where Mallows' C_p prefers it to the sections fitted one by one.
  bool smooth_span = true;
  std::function<void(const std::string&)> progress; // one line per step
};

// One fitted section.
//   station    the slice's station; points: how many scan points it had
//   curve      the fitted closed cubic in 3D, clamped on [0, 1], starting at the leading edge
//              (u = 0), every trailing edge at (about) one common u; planar: in the slice's
//              plane; radial: fitted to the points moved radially onto the slice's cylinder
//   section    the curve's samples (#samples by 3), evenly spaced by arc length; u their
//              parameters
//   control    control points used; rms, max: the slice's points' distances to the curve (at
//              their feet)
struct FittedSection {
  double station = 0;
  Eigen::Index points = 0;
  BSplineCurve curve;
  Eigen::MatrixXd section;
  Eigen::VectorXd u;
  int control = 0;
  double rms = 0, max = 0;
};

// Result.
//   noise        sigma used (given, or the family's spread)
//   loft         S(u, v_k) = sections[k].curve(u) for all u (v_k the stations, scaled to [0, 1]);
//                its sections / point_u / deviation are the samples', its span model the fixed
//                station cubic (no cross-validation: loo_* NaN)
//   section_gap  max |S(u, v_k) - C_k(u)| halfway between the samples: round-off
//   span_control  0: each section fitted to its slice alone; else the sections are the
//                isocurves of one tensor-product surface with that many control points along
//                the span (SliceFitOptions::smooth_span)
struct SlicedFit {
  SliceFamily family;
  double noise = 0;
  std::vector<FittedSection> sections;
  LoftResult loft;
  double section_gap = 0;
  Eigen::Index span_control = 0;
};

// Each slice: its points projected onto the slice's plane or cylinder, order_profile, one
// winding and the start at the leading edge for all slices (prepare_sections on a moving
// average of the ordered points), then closed cubic least squares (approximate_curve, knots on
// multiples of 2^-16 so that the curves' knot union has no near-coincident knots) in two passes
// from a pilot fit (32 control points at the chord length of the moving average):
//   - each point's parameter is its foot's arc-length fraction on the last fit (so that the
//     residuals are distances normal to the curve, without the points' tangential noise);
//   - the knots are spread by arc length plus turning angle of the last fit (crowding at the
//     noses);
//   - the control points (8 ... #points / 4) minimise Mallows' C_p with the known noise,
//     RSS + 8 sigma^2 x control points (in the second pass each candidate is refitted once at
//     its own feet).
// The parameters are then mapped piecewise linearly so that every trailing edge sits at one
// parameter, and refitted there. With smooth_span, the sections are then replaced by the
// isocurves at the stations of one tensor-product least-squares surface through all slices'
// points when that has the lower C_p (smooth_spanwise: the noise of each section averages with
// its neighbours' where the body varies smoothly along the span; measured in docs/benchmarks.md,
// "Sectioned scans: smoothing along the span"). The curves are brought onto one knot vector
// (make_compatible) and interlinated cubically along the span at the slices' stations.
// Inputs: P #P by 3, a family from detect_slices (kind planar or radial, >= 2 slices).
// Throws std::invalid_argument for a family of another kind or fewer than 2 slices,
// std::runtime_error if the loft missed a fitted section by more than 1e-9 of the diagonal.
SlicedFit fit_sliced_scan(const Eigen::MatrixX3d& P, const SliceFamily& family,
                          const SliceFitOptions& options = {});

// The fitted sections' samples (FittedSection::section) as Sections with id "1", "2", ... in
// station order, and loft options like fit_sliced_scan's (leading edges aligned, arc-length
// correspondence, spanwise cubic at the stations without cross-validation): a loft of the
// samples through loft_sections, which interpolates them but departs from the fitted curves
// between them (by up to 0.6 sigma on the Rotor 37 scans, docs/benchmarks.md); for comparisons
// with other loft options.
std::vector<Section> fitted_sections(const std::vector<FittedSection>& fitted);
LoftOptions sliced_scan_loft_options();

} // namespace interlin
