#pragma once
// Blade-section loft: closed section curves -> one B-spline surface that reproduces every input
// section curve exactly (interlineation on the lines v = v_k, seed 001 §2.5).

#include "interlin/reconstruction/loft/section_prep.h"
#include "interlin/reconstruction/loft/span_model.h"
#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>
#include <string>
#include <vector>

namespace interlin {

// How points of different sections are made to correspond (meet at one surface parameter u).
//   index       point i of every section at one parameter (the mean of the sections' own
//               chord-length parameters): one shared knot vector of #P knots. Needs equal counts.
//   arc_length  each section keeps its own parameters (arc-length fraction from the start; with
//               an aligned edge also from the opposite edge, which then sits at one u for all
//               sections); the section curves are brought onto one knot vector by knot insertion.
//   automatic   index when the counts (and the opposite-edge rows) agree, else arc_length.
enum class Correspondence { automatic, index, arc_length };

// Along the span: the spacing of the section parameters v_k (span_parameters.h) and the degree
// of the blending, each fixed or chosen by leave-one-out cross-validation (span_model.h; the
// default: both chosen).
struct LoftOptions {
  int degree = 3; // around the sections (u)
  // Along the span (v): kAutoSpanDegree (chosen among 3, 5 and #sections - 1), or a fixed
  // degree; either way reduced to #sections - 1 when needed.
  int span_degree = kAutoSpanDegree;
  SpanParameters span = SpanParameters::automatic;
  // Cross-validate the spanwise model (#sections - 2 folds per candidate): choose among the
  // candidates and report the leave-one-out error. false: no folds; the model is the first
  // candidate in order of preference (span automatic: station when the stack has stations, else
  // chord; span_degree automatic: the highest, so give a degree), its errors NaN. For callers
  // that neither report nor need the error and loft many sections (sectioned scans).
  bool span_holdout = true;
  StartAlign align = StartAlign::first;
  Correspondence match = Correspondence::automatic;
  double section_exponent = 1.0; // section parameters: 1 chord length, 0.5 centripetal
};

// Result of loft_sections.
//   surface         clamped in u and v, closed_u; u in [0,1] around, v in [0,1] along the span
//   section_v       K parameters v_k of the input sections
//   point_u         per section, the parameter u of each prepared point
//   sections        the prepared (oriented, aligned) sections
//   used            the correspondence actually used
//   deviation       per section, |S(u_i, v_k) - P_i| of each prepared point
//   max_deviation, bbox_diagonal   summary; max_deviation <= 1e-9 * bbox_diagonal is guaranteed
//   notes           what preparation changed (reversed sections, alignment)
//   span            the spanwise model used (parameters, degree, leave-one-out error)
struct LoftResult {
  BSplineSurface surface;
  Eigen::VectorXd section_v;
  std::vector<Eigen::VectorXd> point_u;
  std::vector<PreparedSection> sections;
  Correspondence used = Correspondence::index;
  std::vector<Eigen::VectorXd> deviation;
  double max_deviation = 0, bbox_diagonal = 0;
  std::vector<std::string> notes;
  SpanModel span;
};

// Lofts K >= 2 closed sections (each >= degree + 1 points). Throws std::invalid_argument for bad
// options (span = station for a stack without stations), too few points or coinciding sections,
// InputError-free: section files are validated by read_sections.
// Throws std::runtime_error if the exactness guarantee were violated (never silently).
LoftResult loft_sections(const std::vector<Section>& sections, const LoftOptions& options = {});

} // namespace interlin
