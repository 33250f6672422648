// Implicit surface extraction (docs/benchmarks.md, "Implicit surface extraction").
// 1. Marching cubes on one sampled grid: interlin's marching_cubes against VTK's
//    vtkFlyingEdges3D and vtkMarchingCubes on the same values (vtk_contour.cpp), 1 and 2 threads.
// 2. Seed 002's valve table (digest 002 §7.2): the whole implicit_mesh pipeline (sampling the
//    valve model in sub-boxes, marching cubes, merge) against grid points and sub-box count.
#include "vtk_contour.h"

#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/marching_cubes.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <vector>

namespace {

using namespace interlin;

std::string model_path(const std::string& name) {
  return std::string(INTERLIN_DATA_DIR) + "/models/" + name;
}

ImplicitFunction closed_form(double (*fn)(double, double, double), const Eigen::AlignedBox3d& box) {
  ImplicitFunction f;
  f.value = [fn](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      F(i) = fn(P(i, 0), P(i, 1), P(i, 2));
  };
  f.box = box;
  return f;
}

double torus(double x, double y, double z) {
  const double q = std::sqrt(x * x + y * y) - 1.0;
  return 0.35 * 0.35 - q * q - z * z;
}

double gyroid(double x, double y, double z) {
  return std::sin(x) * std::cos(y) + std::sin(y) * std::cos(z) + std::sin(z) * std::cos(x);
}

struct Dataset {
  RegularGrid grid;
  Eigen::VectorXd S;
};

// The sampled grids, built once: the impeller model (seed 000) with 256 cells along its longest
// side, a torus (smooth, sparse surface) and a gyroid (surface in every cell row: the dense
// case). Each box is shifted by a generic fraction of a cell so that no node value is exactly 0
// (VTK counts 0 as inside, interlin as outside), and both extractors see the same crossings.
const Dataset& dataset(const std::string& name) {
  static std::map<std::string, Dataset> cache;
  auto it = cache.find(name);
  if (it != cache.end())
    return it->second;
  ImplicitFunction f;
  int cells = 0;
  if (name == "impeller") {
    f = load_model(model_path("impeller.rf"));
    cells = 256;
  } else if (name == "torus") {
    f = closed_form(torus, {Eigen::Vector3d(-1.4, -1.4, -0.4), Eigen::Vector3d(1.4, 1.4, 0.4)});
    cells = 320;
  } else {
    f = closed_form(gyroid, {Eigen::Vector3d::Constant(-12), Eigen::Vector3d::Constant(12)});
    cells = 200;
  }
  Dataset d;
  d.grid = grid_with_resolution(f.box, cells);
  d.grid.origin += Eigen::Vector3d(0.31, 0.17, 0.23) * d.grid.spacing(0);
  sample_grid(f, d.grid, d.S, 0);
  return cache.emplace(name, std::move(d)).first->second;
}

// CPU seconds of the whole process (all threads), user + system.
double process_cpu() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Counters: the grid, the output, and the process CPU time per iteration (all threads: with two
// workers it equals the wall time when they ran one after the other, half of it when both had a
// core).
void counters(benchmark::State& st, const Dataset& d, long vertices, long triangles, double cpu0) {
  st.counters["nodes"] = double(d.grid.size());
  st.counters["vertices"] = double(vertices);
  st.counters["triangles"] = double(triangles);
  st.counters["process_cpu_ms"] = 1e3 * (process_cpu() - cpu0) / double(st.iterations());
}

// interlin marching_cubes (vertices, triangles, merged slabs) on `threads` threads.
void BM_extract_interlin(benchmark::State& st, const std::string& name, int threads) {
  const Dataset& d = dataset(name);
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  const double cpu0 = process_cpu();
  for (auto _ : st) {
    marching_cubes(d.grid, d.S, V, F, nullptr, threads);
    benchmark::DoNotOptimize(V.data());
  }
  counters(st, d, V.rows(), F.rows(), cpu0);
}

void BM_extract_vtk(benchmark::State& st, const std::string& name, int threads, bool flying) {
  const Dataset& d = dataset(name);
  if (!bench::VtkContour::use_threads(threads)) {
    st.SkipWithError("VTK SMP backend not available");
    return;
  }
  const int dims[3] = {d.grid.nodes(0), d.grid.nodes(1), d.grid.nodes(2)};
  bench::VtkContour vtk(d.S.data(), dims, d.grid.origin.data(), d.grid.spacing.data(), flying);
  long points = 0, triangles = 0;
  const double cpu0 = process_cpu();
  for (auto _ : st)
    vtk.run(points, triangles);
  counters(st, d, points, triangles, cpu0);
}

void BM_extract_vtk_flying_edges(benchmark::State& st, const std::string& name, int threads) {
  BM_extract_vtk(st, name, threads, true);
}
void BM_extract_vtk_marching_cubes(benchmark::State& st, const std::string& name) {
  BM_extract_vtk(st, name, 1, false);
}

#define EXTRACT(name)                                                                              \
  BENCHMARK_CAPTURE(BM_extract_interlin, name##_1thread, #name, 1)                                 \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->UseRealTime();                                                                             \
  BENCHMARK_CAPTURE(BM_extract_interlin, name##_2threads, #name, 2)                                \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->UseRealTime();                                                                             \
  BENCHMARK_CAPTURE(BM_extract_vtk_flying_edges, name##_1thread, #name, 1)                         \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->UseRealTime();                                                                             \
  BENCHMARK_CAPTURE(BM_extract_vtk_flying_edges, name##_2threads, #name, 2)                        \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->UseRealTime();                                                                             \
  BENCHMARK_CAPTURE(BM_extract_vtk_marching_cubes, name, #name)                                    \
      ->Unit(benchmark::kMillisecond)                                                              \
      ->UseRealTime()
EXTRACT(impeller);
EXTRACT(torus);
EXTRACT(gyroid);

// The machine's free parallelism in the same run: each of `threads` threads does the same fixed
// arithmetic; with as many free cores as threads the time equals the 1-thread time, with one
// free core it doubles. (The build machine is shared; see docs/benchmarks.md.)
void BM_spin_threads(benchmark::State& st) {
  const int threads = int(st.range(0));
  auto work = [] {
    double s = 0;
    for (long i = 0; i < 20000000; ++i)
      s += double(i) * 1e-9;
    benchmark::DoNotOptimize(s);
  };
  for (auto _ : st) {
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back(work);
    for (std::thread& t : pool)
      t.join();
  }
}
BENCHMARK(BM_spin_threads)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Seed 002 Table 1: the valve (data/models/valve.rf) sampled with about `points` grid points in
// k x k x k sub-boxes, each triangulated, the pieces merged (no projection, like the paper's
// "support points + isosurface"); all cores.
void BM_valve_table(benchmark::State& st) {
  static const ImplicitFunction valve = load_model(model_path("valve.rf"));
  const double points = double(st.range(0));
  const int k = int(st.range(1));
  ImplicitMeshOptions o;
  o.cell = std::cbrt(valve.box.volume() / points);
  o.subboxes.setConstant(k);
  o.project = st.range(2) != 0;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  ImplicitMeshInfo info;
  const double cpu0 = process_cpu();
  for (auto _ : st) {
    implicit_mesh(valve, o, V, F, &info);
    benchmark::DoNotOptimize(V.data());
  }
  st.counters["process_cpu_ms"] = 1e3 * (process_cpu() - cpu0) / double(st.iterations());
  st.counters["nodes"] = double(info.grid.size());
  st.counters["subboxes"] = double(k * k * k);
  st.counters["triangles"] = double(F.rows());
  st.counters["extract_s"] = info.seconds_extract;
  st.counters["project_s"] = info.seconds_project;
}
BENCHMARK(BM_valve_table)
    ->ArgsProduct({{125000, 2000000, 15500000}, {2, 3, 4, 5}, {0}})
    ->Args({2000000, 3, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

} // namespace
