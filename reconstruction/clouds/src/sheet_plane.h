#pragma once
// Private to reconstruction/clouds: which neighbours share a point's sheet (estimate_sheet_normals,
// sign_sheet_normals).

#include <cmath>

namespace interlin::detail {

// The neighbours of the proposed planes' normals (estimate_normals of this many points).
constexpr int kSheetProposal = 6;

// A neighbour lies on point i's sheet when within this distance of its plane: a quarter of the
// local spacing (s = d6 sqrt(pi / 6), d6 the distance to the 6-th nearest point, itself the
// first) plus 3 noise sigmas. Across a gap of 1.5 spacings or more, or beyond an edge, the other
// sheet's points lie farther off the plane.
inline double sheet_tolerance(double d6, double sigma) {
  constexpr double kSheetSpacings = 0.25, kSheetSigmas = 3;
  return kSheetSpacings * d6 * std::sqrt(M_PI / kSheetProposal) + kSheetSigmas * sigma;
}

} // namespace interlin::detail
