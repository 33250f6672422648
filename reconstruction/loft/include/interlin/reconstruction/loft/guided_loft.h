#pragma once
// Blade surface from sections AND spanwise guide lines (seed 001 §2.5: a surface through
// sections z = z_k and user-prescribed lines on it; digest 001 §5.1 [SUPPLEMENT] Gordon surface):
// one tensor-product B-spline that passes exactly through every section curve and every guide
// curve. The library makes the two families compatible: each guide's crossing with each section
// is found, inserted into the section when it falls between its points, and pinned to one common
// parameter u_l around all sections; each guide is parameterised so that it meets section k at
// the section's span parameter v_k.

#include "interlin/reconstruction/io/guide_csv.h"
#include "interlin/reconstruction/loft/loft.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace interlin {

struct GuidedLoftOptions {
  LoftOptions loft;              // the sections' options (degree, span degree, start, ...)
  double guide_tolerance = 1e-3; // a guide must pass within this x bbox diagonal of every section
};

// One guide after fitting.
//   id               the guide's id
//   u                its parameter around the sections (the same at every crossing)
//   points, v        the interpolated points in span order and their span parameters: the K
//                    crossings (v = section_v(k)) and the guide's own points between them
//   crossing         K rows of `points` holding the crossings, in section order
//   source           per row of `points`: index of the input point it stands for (a crossing
//                    replaces an input point lying on the section), -1 for an inserted crossing
//   input_row        per input point: the row of `points` standing for it (itself, or the
//                    crossing that replaced it)
//   input_deviation  per input point: |S(u, v) - input point| at the parameter of its row (a
//                    replaced point: the distance to its crossing, at most the tolerance)
//   deviation        per row of `points`: |S(u, v) - point| (round-off)
//   curve_deviation  max |S(u, v) - G(v)| over 64 samples per span of the guide curve G
//   reversed         the input ran from the last section to the first
struct GuideFit {
  std::string id;
  double u = 0;
  Eigen::MatrixXd points;
  Eigen::VectorXd v;
  std::vector<Eigen::Index> crossing, source, input_row;
  Eigen::VectorXd input_deviation, deviation;
  double curve_deviation = 0;
  bool reversed = false;
};

// Result: loft.surface is the Gordon surface (closed around, clamped); loft.sections hold the
// prepared sections with the inserted crossings (source -1); loft.deviation covers every
// prepared point; loft.max_deviation is the maximum over the sections, the guides' points and
// curves (the exactness guarantee 1e-9 x bbox diagonal holds for all of them).
struct GuidedLoftResult {
  LoftResult loft;
  std::vector<GuideFit> guides;
  double max_guide_deviation = 0; // over GuideFit::deviation and curve_deviation
  double max_input_deviation = 0; // over GuideFit::input_deviation (the guides' own points)
};

// Inputs: K >= 2 closed sections (as for loft_sections), the guides (>= 1; each an open polyline
// that crosses every section once, within guide_tolerance x bbox diagonal, from the first
// section to the last in either direction, and no two guides crossing a section at one point).
// Throws InputError "GUIDES:LINE: ..." for guides that break these rules, std::invalid_argument
// for bad options or sections, std::runtime_error if the exactness guarantee were violated.
GuidedLoftResult guided_loft(const std::vector<Section>& sections, const GuideSet& guides,
                             const GuidedLoftOptions& options = {});

} // namespace interlin
