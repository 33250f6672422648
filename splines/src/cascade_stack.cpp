// Stacking seed 004 §4.1 cascade profiles along the span into loft sections.
#include "interlin/splines/cascade_stack.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector2d;

Vector2d polygon_centroid(const MatrixXd& V) {
  double A = 0, cx = 0, cy = 0;
  const Index n = V.rows();
  for (Index i = 0; i < n; ++i) {
    const Index j = (i + 1) % n;
    const double w = V(i, 0) * V(j, 1) - V(j, 0) * V(i, 1); // shoelace term
    A += w;
    cx += (V(i, 0) + V(j, 0)) * w;
    cy += (V(i, 1) + V(j, 1)) * w;
  }
  if (!(std::abs(A) > 0) || !std::isfinite(A))
    throw std::invalid_argument("polygon centroid: the polygon has zero area");
  return {cx / (3 * A), cy / (3 * A)};
}

std::vector<MatrixXd> stack_cascade_profiles(const std::vector<SpanStation>& stations,
                                             StackAlign align, const CascadeOptions& options,
                                             std::vector<CascadeProfile>* profiles) {
  if (stations.empty())
    throw std::invalid_argument("profile stack: no span stations");
  std::vector<MatrixXd> out;
  for (size_t k = 0; k < stations.size(); ++k) {
    const double r = stations[k].radius;
    const std::string where =
        "span station " + std::to_string(k) + " (radius " + std::to_string(r) + "): ";
    if (!std::isfinite(r))
      throw std::invalid_argument(where + "radius must be finite");
    if (k > 0 && !(r > stations[k - 1].radius))
      throw std::invalid_argument(where + "radii must increase strictly");
    CascadeProfile P;
    try {
      P = cascade_profile(stations[k].parameters, options);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + e.what());
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(where + e.what());
    }
    Vector2d origin = Vector2d::Zero();
    if (align == StackAlign::centroid)
      origin = polygon_centroid(P.points);
    else if (align == StackAlign::leading_edge)
      origin = P.O1;
    else if (align == StackAlign::trailing_edge)
      origin = P.O2;
    MatrixXd S(P.points.rows(), 3);
    S.leftCols(2) = P.points.rowwise() - origin.transpose();
    S.col(2).setConstant(r);
    out.push_back(S);
    if (profiles)
      profiles->push_back(P);
  }
  return out;
}

} // namespace interlin
