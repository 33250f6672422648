// OpenCASCADE baseline of the loft benchmark (bench_loft.cpp): BRepOffsetAPI_ThruSections
// (isSolid = false, ruled = false, default settings) on the 7-section Rotor 37 input, each
// section a closed periodic B-spline through its points (occt_loft.h). Built only when OCCT is
// found.

#include "bench_data.h"
#include "occt_loft.h"

#include <benchmark/benchmark.h>

#include <vector>

namespace {

using namespace interlin;

std::vector<TopoDS_Wire> section_wires(const std::vector<Section>& sections) {
  std::vector<TopoDS_Wire> wires;
  for (const Section& s : sections)
    wires.push_back(bench::occt_section_wire(s.points));
  return wires;
}

// ThruSections build only: the 7 section wires are made once, outside the timed loop.
void BM_loft_occt_thrusections_7(benchmark::State& st) {
  const std::vector<TopoDS_Wire> wires = section_wires(bench::rotor37_every_second());
  for (auto _ : st) {
    TopoDS_Shape shape = bench::occt_thru_sections(wires);
    benchmark::DoNotOptimize(&shape);
  }
}
BENCHMARK(BM_loft_occt_thrusections_7)->Unit(benchmark::kMillisecond);

// Sections + ThruSections: periodic interpolation of every section (GeomAPI_Interpolate), edge
// and wire construction, then the ThruSections build: the whole job loft_sections does.
void BM_loft_occt_sections_and_thrusections_7(benchmark::State& st) {
  const std::vector<Section>& seven = bench::rotor37_every_second();
  for (auto _ : st) {
    TopoDS_Shape shape = bench::occt_thru_sections(section_wires(seven));
    benchmark::DoNotOptimize(&shape);
  }
}
BENCHMARK(BM_loft_occt_sections_and_thrusections_7)->Unit(benchmark::kMillisecond);

} // namespace
