#pragma once
// Rotor 37 blade sections for the benchmarks, read once (data/rotor37/sections.csv: 13 closed
// sections of 198 points).

#include "interlin/reconstruction/io/section_csv.h"

#include <vector>

namespace interlin::bench {

// All 13 sections, in file order.
const std::vector<Section>& rotor37_sections();

// Sections 0, 2, ..., 12: the 7-section loft input of the hold-out study.
const std::vector<Section>& rotor37_every_second();

} // namespace interlin::bench
