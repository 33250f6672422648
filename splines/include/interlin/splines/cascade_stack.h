#pragma once
// Stacking cascade profiles (seed 004 §4.1) along the span: one profile per radius, each built
// from its own 13 parameters (a span law: chord via the axial width, stagger, thickness, ...
// against radius), placed in the plane z = radius and aligned on a stacking line. The output is
// the input of the loft (a multi-section file).

#include "interlin/splines/cascade_profile.h"

#include <Eigen/Core>
#include <vector>

namespace interlin {

// One span station: the profile parameters at this radius.
struct SpanStation {
  double radius = 0;
  CascadeParameters parameters;
};

// Stacking line: each profile is translated in its plane so that this point is at x = y = 0.
//   centroid       area centroid of the closed profile (the usual stacking axis)
//   leading_edge   leading-edge circle centre O1
//   trailing_edge  trailing-edge circle centre O2
//   none           the profiles keep the cascade frame of cascade_profile
enum class StackAlign { centroid, leading_edge, trailing_edge, none };

// Area centroid of a closed polygon V (#V by 2, not repeated at the end). Throws
// std::invalid_argument for a polygon of zero area.
Eigen::Vector2d polygon_centroid(const Eigen::MatrixXd& V);

// Inputs: stations with strictly increasing radii (>= 1 station), alignment, profile options.
// Output: one #P by 3 matrix (x, y, z = radius) per station, all with the same #P (the options
// fix the point count), so that point i of every section is the same feature; `profiles`
// (optional) receives the profiles in their cascade frames.
// Throws std::invalid_argument (naming the station) for bad radii or parameters.
std::vector<Eigen::MatrixXd>
stack_cascade_profiles(const std::vector<SpanStation>& stations, StackAlign align,
                       const CascadeOptions& options = {},
                       std::vector<CascadeProfile>* profiles = nullptr);

} // namespace interlin
