#pragma once
// Hold-out study: loft every K-th section, measure how far the withheld sections are from the
// surface (exact point-to-surface distances). The spanwise accuracy of a loft in one number.

#include "interlin/reconstruction/loft/loft.h"

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace interlin {

// Inputs:
//   sections  all sections (>= 3)
//   withheld  indices of the sections to leave out (neither the first nor the last: the study
//             measures interpolation, not extrapolation; at least 2 sections must remain)
//   options   loft options
// Outputs:
//   train, test   indices into `sections`
//   distance      per test section, the distance of each of its points to the surface
//   max, rms      over all test points
//   loft          the loft of the training sections
struct HoldoutResult {
  std::vector<size_t> train, test;
  std::vector<Eigen::VectorXd> distance;
  double max = 0, rms = 0;
  LoftResult loft;
};

HoldoutResult holdout_study(const std::vector<Section>& sections,
                            const std::vector<size_t>& withheld, const LoftOptions& options = {});

// The same study with any lofting method (e.g. the guided loft): `loft` maps the training
// sections to a LoftResult.
HoldoutResult holdout_study(const std::vector<Section>& sections,
                            const std::vector<size_t>& withheld,
                            const std::function<LoftResult(const std::vector<Section>&)>& loft);

// The sections withheld when every K-th is kept (0, K, 2K, ... and always the last one); K >= 2.
std::vector<size_t> withheld_every(size_t count, int K);

} // namespace interlin
