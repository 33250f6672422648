// Mesh sampling and export at ~200k triangles: the loft of all 13 Rotor 37 sections sampled on
// a 1000 x ~100 grid (surface_mesh), written with write_mesh to /tmp as .stl, .ply and .obj.
// Baseline in the same run: one plain fwrite of the binary-STL byte count (the I/O floor).

#include "bench_data.h"

#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace interlin;

struct MeshFixture {
  PiecewiseSurface surface;
  SurfaceMeshOptions options;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

const MeshFixture& mesh_fixture() {
  static const MeshFixture fx = [] {
    MeshFixture f;
    const LoftResult loft = loft_sections(bench::rotor37_sections());
    f.surface = to_piecewise(loft.surface);
    f.options.nu = 1000;
    f.options.nv = 100;
    f.options.required_v.assign(loft.section_v.data(),
                                loft.section_v.data() + loft.section_v.size());
    surface_mesh(f.surface, f.options, f.V, f.F);
    return f;
  }();
  return fx;
}

// Binary STL size: 80-byte header, 4-byte count, 50 bytes per triangle.
long stl_bytes(const Eigen::MatrixXi& F) {
  return 84 + 50 * static_cast<long>(F.rows());
}

// surface_mesh alone: u-sample distribution, grid evaluation of the piecewise surface and
// triangulation (no file).
void BM_surface_mesh_200k(benchmark::State& st) {
  const MeshFixture& fx = mesh_fixture();
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  for (auto _ : st) {
    surface_mesh(fx.surface, fx.options, V, F);
    benchmark::DoNotOptimize(V.data());
  }
  st.counters["vertices"] = static_cast<double>(V.rows());
  st.counters["triangles"] = static_cast<double>(F.rows());
}
BENCHMARK(BM_surface_mesh_200k)->Unit(benchmark::kMillisecond);

// write_mesh of the fixed mesh (STL: OpenMesh writer; PLY, OBJ: interlin, double precision;
// atomic temp file + rename).
void BM_write_mesh(benchmark::State& st, const std::string& ext) {
  const MeshFixture& fx = mesh_fixture();
  const std::string path = "/tmp/interlin_bench_mesh" + ext;
  for (auto _ : st)
    write_mesh(path, fx.V, fx.F);
  st.counters["triangles"] = static_cast<double>(fx.F.rows());
  st.counters["file_MB"] = static_cast<double>(std::filesystem::file_size(path)) * 1e-6;
  std::filesystem::remove(path);
}
// Wall-clock time (UseRealTime) for everything that writes a file: the kernel's share counts.
BENCHMARK_CAPTURE(BM_write_mesh, stl, std::string(".stl"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_write_mesh, ply, std::string(".ply"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_write_mesh, obj, std::string(".obj"))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The I/O floor: fopen, one fwrite of a ready buffer with the binary-STL byte count, fclose.
void BM_fwrite_floor_stl_bytes(benchmark::State& st) {
  const MeshFixture& fx = mesh_fixture();
  const std::vector<char> buffer(static_cast<size_t>(stl_bytes(fx.F)), 1);
  const char* path = "/tmp/interlin_bench_floor.bin";
  for (auto _ : st) {
    std::FILE* f = std::fopen(path, "wb");
    if (!f || std::fwrite(buffer.data(), 1, buffer.size(), f) != buffer.size())
      throw std::runtime_error("cannot write /tmp/interlin_bench_floor.bin");
    std::fclose(f);
  }
  st.counters["file_MB"] = static_cast<double>(buffer.size()) * 1e-6;
  std::remove(path);
}
BENCHMARK(BM_fwrite_floor_stl_bytes)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
