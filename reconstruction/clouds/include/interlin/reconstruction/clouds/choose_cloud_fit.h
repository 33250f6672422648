#pragma once
// Which implicit a sparse unstructured cloud gets: the partition of unity of local fits
// (cloud_implicit.h) or the Hermite RBF interpolant (hermite_rbf.h), chosen by k-fold hold-out
// on the cloud itself. Neither wins everywhere: on smooth bodies of a few hundred points the
// interpolant is 10 to 600 times closer to the truth, on a capped blade of 200 to 300 points the
// local fits are 1.3 to 1.4 times closer (docs/benchmarks.md, "Sparse clouds: the Hermite RBF").

#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/point_cloud.h"

#include <Eigen/Core>

namespace interlin {

// Clouds up to this many points are offered the Hermite RBF by the automatic choice (its fit
// takes about 0.3 s at 400 points, and grows as the cube of the count).
constexpr Eigen::Index kHermiteRbfAutoPoints = 500;

// The automatic fit's rule (`interlin implicit --fit auto`, Python fit="auto", the bench's
// default row): the hold-out decides for clouds of at most kHermiteRbfAutoPoints points whose
// normals were measured (came with the file), not estimated from the points; the interpolant
// reproduces every normal, and estimated ones misled the hold-out on 3 of 8 sparse clouds.
inline bool hermite_rbf_offered(const PointCloud& c, bool normals_measured) {
  return normals_measured && c.points.rows() <= kHermiteRbfAutoPoints;
}

// holdout_pu, holdout_hrbf: the mean first-order distance |F| / |grad F| of each held-out point
// to the function fitted to the other folds (NaN where a fold's fit failed)
struct CloudFitChoice {
  bool hermite = false;
  double holdout_pu = 0, holdout_hrbf = 0;
};

// Five-fold hold-out of both fits on the cloud c (oriented normals; fit: the partition of unity's
// options); hermite when the Hermite RBF's mean hold-out distance is the smaller. Folds are fixed
// by a seeded shuffle (deterministic). Throws std::invalid_argument for a cloud of more than
// kHermiteRbfAutoPoints points or without normals.
CloudFitChoice choose_cloud_fit(const PointCloud& c, CloudFitOptions fit = {});

} // namespace interlin
