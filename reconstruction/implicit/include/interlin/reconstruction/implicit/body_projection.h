#pragma once
// Exact signed distance to the closed boundary of a lofted body (side surface and ruled caps,
// interflatation/models/body_patches.h) by a global search: the nearest dense samples of each
// patch (FLANN, one tree per patch) start Newton's foot search, the nearest foot wins. The
// reference the section-body builder fits its far field to and checks its near field against.

#include "interlin/interflatation/models/body_patches.h"

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

namespace interlin {

class BodyProjection {
public:
  // Inputs: the patches; samples_u x samples_v samples of the side (caps: samples_u x 16),
  // samples_u >= 64, samples_v >= 32; starts = nearest samples tried per point and patch
  // (neighbouring samples, within two sample spacings, count once). Points far from the
  // boundary take their starts from a coarse 64 x 32 sampling instead.
  explicit BodyProjection(const BodyPatches& patches, int samples_u = 512, int samples_v = 128,
                          int starts = 6);
  ~BodyProjection();
  BodyProjection(const BodyProjection&) = delete;
  BodyProjection& operator=(const BodyProjection&) = delete;

  // Signed distances (positive inside) of the points P (#P by 3) with feet and gradients, on
  // `threads` threads (0: all cores). With patch = 0, 1 or 2 only that patch is searched (the
  // distance to it, signed by its own normal).
  std::vector<BodyDistance> distances(const Eigen::MatrixXd& P, int threads = 0,
                                      int patch = -1) const;

  const BodyPatches& patches() const { return patches_; }

  struct Tree; // the samples of one patch and their FLANN tree

private:
  BodyPatches patches_;
  int starts_;
  std::array<std::unique_ptr<Tree>, 3> trees_, coarse_; // fine and 64 x 32 samples
};

} // namespace interlin
