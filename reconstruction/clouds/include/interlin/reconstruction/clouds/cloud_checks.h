#pragma once
// Clouds that cannot bound a volume are refused with one clear line before any fitting.

#include "interlin/reconstruction/clouds/point_cloud.h"

#include <string>
#include <vector>

namespace interlin {

// Fewest distinct points the implicit fit accepts: every local fit needs CloudFitOptions::
// min_points (20 by default) points, and a closed surface needs more than one fit.
constexpr Eigen::Index kMinCloudPoints = 20;

// Removes repeated points (exact duplicates; the first copy and its normal are kept) and checks
// what is left. Throws InputError "PATH: ..." when fewer than kMinCloudPoints distinct points
// remain, or when all of them lie on one point, one line or one plane (extent across it at most
// 1e-6 of the largest extent: a scanned solid is never that flat, a file of coplanar points is).
// `notes` (optional) receives a line when duplicates were removed.
PointCloud check_cloud(const std::string& path, const PointCloud& c,
                       std::vector<std::string>* notes = nullptr);

} // namespace interlin
