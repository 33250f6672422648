#include "interlin/reconstruction/loft/holdout.h"

#include "interlin/reconstruction/loft/closest_point.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

std::vector<size_t> withheld_every(size_t count, int K) {
  if (K < 2)
    throw std::invalid_argument("hold-out step must be >= 2, got " + std::to_string(K));
  std::vector<size_t> out;
  for (size_t i = 0; i + 1 < count; ++i)
    if (i % static_cast<size_t>(K) != 0)
      out.push_back(i);
  return out;
}

HoldoutResult holdout_study(const std::vector<Section>& sections,
                            const std::vector<size_t>& withheld, const LoftOptions& o) {
  return holdout_study(sections, withheld,
                       [&](const std::vector<Section>& keep) { return loft_sections(keep, o); });
}

HoldoutResult holdout_study(const std::vector<Section>& sections,
                            const std::vector<size_t>& withheld,
                            const std::function<LoftResult(const std::vector<Section>&)>& loft) {
  HoldoutResult h;
  std::vector<Section> keep;
  for (size_t i = 0; i < sections.size(); ++i) {
    const bool out = std::find(withheld.begin(), withheld.end(), i) != withheld.end();
    if (out && (i == 0 || i + 1 == sections.size()))
      throw std::invalid_argument("the first and the last section cannot be withheld (section " +
                                  sections[i].id + ")");
    (out ? h.test : h.train).push_back(i);
    if (!out)
      keep.push_back(sections[i]);
  }
  for (size_t i : withheld)
    if (i >= sections.size())
      throw std::invalid_argument("no section with index " + std::to_string(i) + " (there are " +
                                  std::to_string(sections.size()) + ")");
  if (h.test.empty())
    throw std::invalid_argument("no section withheld");
  h.loft = loft(keep);
  const PiecewiseSurface S = to_piecewise(h.loft.surface);
  double sum2 = 0;
  long count = 0;
  for (size_t i : h.test) {
    const SurfaceProjection p = project_to_surface(S, sections[i].points);
    h.distance.push_back(p.distance);
    h.max = std::max(h.max, p.distance.maxCoeff());
    sum2 += p.distance.squaredNorm();
    count += p.distance.size();
  }
  h.rms = count > 0 ? std::sqrt(sum2 / static_cast<double>(count)) : 0.0;
  return h;
}

} // namespace interlin
