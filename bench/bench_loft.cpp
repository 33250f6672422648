// Loft fit on the 7-section Rotor 37 input (sections 0, 2, ..., 12; 198 points each), the input
// already in memory. The OpenCASCADE baseline of the same fit is in bench_occt.cpp (same binary,
// same run), so docs/benchmarks.md quotes the ratio of medians from one run.

#include "bench_data.h"

#include "interlin/reconstruction/loft/loft.h"

#include <benchmark/benchmark.h>

namespace {

using namespace interlin;

// Whole loft_sections call with default options: section preparation (orientation, alignment),
// parameters, interlineation of the section curves, and the built-in exactness check (every
// input point evaluated on the surface).
void BM_loft_interlin_7(benchmark::State& st) {
  const std::vector<Section>& seven = bench::rotor37_every_second();
  for (auto _ : st) {
    LoftResult r = loft_sections(seven);
    benchmark::DoNotOptimize(r.surface.ctrl.data());
  }
  st.counters["sections"] = static_cast<double>(seven.size());
}
BENCHMARK(BM_loft_interlin_7)->Unit(benchmark::kMillisecond);

} // namespace
