#pragma once
// Shared by loft_sections and guided_loft (private header): closed section curves on one knot
// vector with landmark rows at common parameters, the span parameters, and the deviation of a
// surface from the section points.

#include "interlin/reconstruction/loft.h"
#include "interlin/splines/bspline_curve.h"

#include <Eigen/Core>
#include <vector>

namespace interlin::detail {

// Result of section_curves.
//   curves     K clamped curves on [0, 1], one knot vector, curves[k](point_u[k](i)) = P_i
//   point_u    per section #P + 1 parameters (the last, 1, closes the loop)
//   landmark_u per landmark m, its common parameter
//   section_v  K span parameters in [0, 1]
//   used       the correspondence used
struct SectionCurves {
  std::vector<BSplineCurve> curves;
  std::vector<Eigen::VectorXd> point_u;
  std::vector<double> landmark_u;
  Eigen::VectorXd section_v;
  Correspondence used = Correspondence::index;
};

// Inputs:
//   sections   prepared sections
//   landmarks  per section the rows (increasing, > 0) that must sit at one common parameter in
//              every section: landmark m of each section at the mean of their chord fractions
//   o          degree, correspondence, exponents
// Throws std::invalid_argument (index correspondence impossible, coinciding sections).
SectionCurves section_curves(const std::vector<PreparedSection>& sections,
                             const std::vector<std::vector<Eigen::Index>>& landmarks,
                             const LoftOptions& o);

// |S(u_i, v_k) - P_i| for every prepared point (row curve at v_k, then the u basis of S).
// lo/hi receive the points' bounding box.
std::vector<Eigen::VectorXd> section_deviation(const BSplineSurface& S,
                                               const Eigen::VectorXd& section_v,
                                               const std::vector<Eigen::VectorXd>& point_u,
                                               const std::vector<PreparedSection>& sections,
                                               Eigen::Vector3d& lo, Eigen::Vector3d& hi);

} // namespace interlin::detail
