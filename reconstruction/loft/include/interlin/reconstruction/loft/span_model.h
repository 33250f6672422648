#pragma once
// The spanwise model of a loft: how the section lines v = v_k are spaced (span_parameters.h) and
// the degree of the blending along the span, with its leave-one-out error: each interior section
// withheld in turn from the loft of the others, the exact distance of its points to that surface.
// loft_sections and guided_loft choose it in one place (LoftOptions::span, span_degree).

#include "interlin/reconstruction/loft/span_parameters.h"

#include <limits>
#include <vector>

namespace interlin {

// LoftOptions::span_degree value: choose the degree by cross-validation.
inline constexpr int kAutoSpanDegree = 0;

// The highest degree the automatic choice tries: the CLI's largest --span-degree. With up to
// 10 sections the candidate "#sections - 1" is the one polynomial through all of them.
inline constexpr int kMaxAutoSpanDegree = 9;

// One model and its leave-one-out error.
//   parameters  station, chord, centripetal or uniform
//   degree      the degree on the whole stack (a fold with fewer sections: min(degree, #-1))
//   loo_max, loo_rms   over the points of every withheld section (at most 256 of each: every
//               step-th of a denser one; NaN for fewer than 3 sections, no interior section to
//               withhold, or without cross-validation)
struct SpanCandidate {
  SpanParameters parameters = SpanParameters::chord;
  int degree = 3;
  double loo_max = std::numeric_limits<double>::quiet_NaN();
  double loo_rms = std::numeric_limits<double>::quiet_NaN();
};

// The model a loft used.
//   used        the surface's parameters and degree, with their leave-one-out error
//   chosen      picked by cross-validation among `candidates` (false: fixed by the options, or
//               the first candidate without cross-validation, LoftOptions::span_holdout)
//   candidates  every model tried, in order of preference (ties go to the earlier)
//   stations    the stack's stations (span_parameters.h)
//   folds       the number of sections withheld in turn (#sections - 2; 0 without
//               cross-validation)
struct SpanModel {
  SpanCandidate used;
  bool chosen = false;
  std::vector<SpanCandidate> candidates;
  SectionStations stations;
  int folds = 0;
};

// The cross-validation score that the automatic choice minimises (lower is better).
double span_model_score(const SpanCandidate& c);

} // namespace interlin
