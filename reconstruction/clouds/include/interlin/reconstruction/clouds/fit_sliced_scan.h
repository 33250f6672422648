#pragma once
// Sectioned scans -> fitted sections -> loft: each slice's profile is ordered (order_profile),
// fitted by a closed least-squares cubic (seed 001 ch. 3: "the coefficients are found by least
// squares"; splines/approximate_curve) whose number of control points is chosen from the noise,
// and the fitted sections are lofted (seed 001 §2.5, reconstruction/loft): the surface contains
// every fitted section curve. See also: detect_slices, loft_sections.

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
  // Points per fitted section handed to the loft, evenly spaced by arc length (0: 8 x the
  // curve's control points, >= 400):
  // the loft's section curve interpolates them, so it equals the fitted curve at those points
  // and differs from it in between by the reported section_gap.
  int samples = 0;
  std::function<void(const std::string&)> progress; // one line per step
};

// One fitted section.
//   station    the slice's station; points: how many scan points it had
//   curve      the closed cubic in the slice's 2D coordinates (planar: two in-plane axes;
//              radial: arc length r * angle and the axial coordinate)
//   section    the curve's samples in 3D (#samples by 3), the loft's input; u their parameters
//   control    control points used; rms, max: |C(u_i) - P_i| over the slice's points
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
//   section_gap  the largest distance from the fitted curves (between their samples) to the loft
struct SlicedFit {
  SliceFamily family;
  double noise = 0;
  std::vector<FittedSection> sections;
  LoftResult loft;
  double section_gap = 0;
};

// Each slice: order_profile, parameters from a moving average of the ordered points (chord
// length of the smoothed polyline, insensitive to the noise), then approximate_curve (closed,
// cubic) with 8, 16, 32, ... up to #points / 4 control points until the rms residual is at most
// 1.5 sigma (the discrepancy principle: the in-plane residual of isotropic noise is sqrt(2)
// sigma). The loft
// aligns the sections at their leading edges (arc-length correspondence) and is cubic along the
// span at the slices' stations (sliced_scan_loft_options).
// Inputs: P #P by 3, a family from detect_slices (kind planar or radial, >= 2 slices).
// Throws std::invalid_argument for a family of another kind or fewer than 2 slices.
SlicedFit fit_sliced_scan(const Eigen::MatrixX3d& P, const SliceFamily& family,
                          const SliceFitOptions& options = {});

// The loft's input: each fitted section's samples (FittedSection::section) as a Section with id
// "1", "2", ... in station order, and the options fit_sliced_scan lofts them with (sections
// aligned at their leading edges, arc-length correspondence; spanwise cubic at the stations, or
// chord spacing where the loft finds none, without cross-validation: LoftOptions::span_holdout
// false, so the loft's span.used.loo_* are NaN). Another loft of these (e.g. the
// implicit body of build_section_body) is the same surface.
std::vector<Section> fitted_sections(const std::vector<FittedSection>& fitted);
LoftOptions sliced_scan_loft_options();

} // namespace interlin
