#pragma once
// Shared by loft_sections and guided_loft (private header): closed section curves on one knot
// vector with landmark rows at common parameters, the distances between them that chord-length
// span parameters need, the deviation of a surface from the section points and its guarantee,
// and the snapping of close parameters.

#include "interlin/reconstruction/loft/loft.h"
#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace interlin::detail {

// The inputs every loft needs: K >= 2 sections, degrees >= 1 (span degree >= 1 or
// kAutoSpanDegree), each section with at least max(4, degree + 1) points. Throws
// std::invalid_argument naming the section.
void check_loft_inputs(const std::vector<Section>& sections, const LoftOptions& o);

// The rows that sit at one common parameter around the sections of a loft without guides: the
// opposite edge when the start is an aligned edge (align leading_edge / trailing_edge), else
// none. Output: per section, its landmark rows.
std::vector<std::vector<Eigen::Index>> edge_landmarks(const std::vector<PreparedSection>& sections,
                                                      StartAlign align);

// Result of section_curves.
//   curves     K clamped curves on [0, 1], one knot vector, curves[k](point_u[k](i)) = P_i
//   point_u    per section #P + 1 parameters (the last, 1, closes the loop)
//   landmark_u per landmark m, its common parameter
//   used       the correspondence used
struct SectionCurves {
  std::vector<BSplineCurve> curves;
  std::vector<Eigen::VectorXd> point_u;
  std::vector<double> landmark_u;
  Correspondence used = Correspondence::index;
};

// Inputs:
//   sections   prepared sections
//   landmarks  per section the rows (increasing, > 0) that must sit at one common parameter in
//              every section: landmark m of each section at the mean of their chord fractions
//   o          degree, correspondence, section exponent
// Throws std::invalid_argument (index correspondence impossible).
SectionCurves section_curves(const std::vector<PreparedSection>& sections,
                             const std::vector<std::vector<Eigen::Index>>& landmarks,
                             const LoftOptions& o);

// K-1 mean distances between neighbouring curves (one knot vector), at 256 common parameters:
// the chord lengths of the span parameters (span_parameters.h). Throws std::invalid_argument
// "sections A and B coincide" for a zero distance (names from `sections`).
Eigen::VectorXd neighbour_distances(const std::vector<BSplineCurve>& curves,
                                    const std::vector<PreparedSection>& sections);

// The interlineation check at every input point: r.deviation[k](i) = |S(u_i, v_k) - P_i| for r's
// surface, parameters and prepared sections (row curve at v_k, then the u basis of S), and
// r.max_deviation the largest (r.deviation empty and r.max_deviation 0 before). lo/hi receive
// the points' bounding box.
void section_deviation(LoftResult& r, Eigen::Vector3d& lo, Eigen::Vector3d& hi);

// The exactness guarantee: throws std::runtime_error "<what> by <max deviation> (more than 1e-9 x
// bounding-box diagonal); refusing to continue" unless r.max_deviation <= 1e-9 r.bbox_diagonal.
void require_exact(const LoftResult& r, const std::string& what);

// Values closer than tol(first) in different vectors of u are made equal, the first (smallest)
// value winning, so that a knot union does not create spans many orders of magnitude shorter
// than their neighbours; values of one vector are never merged with each other. Only entries
// [ends, size - ends) of each vector take part.
void snap_values(std::vector<Eigen::VectorXd>& u, Eigen::Index ends,
                 const std::function<double(double)>& tol);

} // namespace interlin::detail
