#pragma once
// The spanwise model of loft_sections and guided_loft, in one place (private header): candidate
// models, their leave-one-out errors, the choice, and the parameters v_k it gives.

#include "section_curves.h"

#include "interlin/reconstruction/loft/span_model.h"

#include <Eigen/Core>
#include <vector>

namespace interlin::detail {

// The candidates for the options, in order of preference: parameters o.span, or (automatic)
// station when the stack has stations, then chord, then uniform; degree o.span_degree, or
// (automatic) 3, 5 and #sections - 1 (at most kMaxAutoSpanDegree), each reduced to
// #sections - 1, duplicates dropped. Throws std::invalid_argument for span = station on a stack
// without stations, naming the measured spread.
std::vector<SpanCandidate> span_candidates(const SectionStations& stations, Eigen::Index K,
                                           const LoftOptions& o);

// Leave-one-out errors of every candidate, in place: each interior section j withheld in turn,
// the others interlineated with the candidate's degree at the candidate's parameters of the
// whole stack (without v_j: parameters come from the stack's geometry, so each fold tests the
// model the loft uses, also for spacings that are not additive like centripetal and uniform),
// the distance of each point of j to that surface by Newton's method (project_from) from its
// own parameters (u_i, v_j) and from samples of the band between j's neighbours (only that band
// of the fold is converted to explicit form; of a section with more than 256 points every
// step-th is measured).
// Inputs: the prepared sections (K >= 3), their section curves, the K-1 distances between
// neighbouring curves and the stations.
void cross_validate(const std::vector<PreparedSection>& sections, const SectionCurves& curves,
                    const Eigen::VectorXd& distance, const SectionStations& stations,
                    std::vector<SpanCandidate>& candidates);

// The model of a loft: stations, candidates, their leave-one-out errors (K >= 3 and
// o.span_holdout) and the choice (the lowest span_model_score; ties to the earlier candidate;
// without errors the first).
SpanModel choose_span_model(const std::vector<PreparedSection>& sections,
                            const SectionCurves& curves, const LoftOptions& o);

// The span parameters v_k of the model for section curves on one knot vector.
Eigen::VectorXd model_span_parameters(const SpanModel& m, const std::vector<BSplineCurve>& curves,
                                      const std::vector<PreparedSection>& sections);

} // namespace interlin::detail
