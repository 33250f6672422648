#include "bench_data.h"

namespace interlin::bench {

const std::vector<Section>& rotor37_sections() {
  static const std::vector<Section> all =
      read_sections(INTERLIN_DATA_DIR "/rotor37/sections.csv").sections;
  return all;
}

const std::vector<Section>& rotor37_every_second() {
  static const std::vector<Section> seven = [] {
    std::vector<Section> out;
    const auto& all = rotor37_sections();
    for (size_t i = 0; i < all.size(); i += 2)
      out.push_back(all[i]);
    return out;
  }();
  return seven;
}

} // namespace interlin::bench
