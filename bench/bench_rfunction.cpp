// R-function evaluation: the semi-closed impeller of seed 000 (data/models/impeller.rf, 24
// blades by Fourier folding, 80 instructions) on a 256^3 grid of its box, one z-layer of 256^2
// points per batch. Baselines in the same run: the same grid on 2 threads (ratio = speed-up),
// a pure arithmetic loop on 1 and 2 threads (the parallelism the machine offers during the run),
// and the same points evaluated one call per point (ratio = what batching buys).

#include "interlin/interflatation/rfunctions/model.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <string>
#include <thread>
#include <vector>

namespace {

using namespace interlin;

constexpr int kN = 256; // grid points per axis

const ImplicitFunction& impeller() {
  static const ImplicitFunction f =
      load_model(std::string(INTERLIN_DATA_DIR) + "/models/impeller.rf");
  return f;
}

// The x, y columns of one z-layer of the grid over the model's box; z is filled per layer.
Points3 layer_points(const ImplicitFunction& f) {
  Points3 P(kN * kN, 3);
  const Eigen::Vector3d lo = f.box.min(), step = f.box.sizes() / (kN - 1);
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i)
      P.row(i + kN * j) << lo.x() + i * step.x(), lo.y() + j * step.y(), lo.z();
  return P;
}

double layer_z(const ImplicitFunction& f, int k) {
  return f.box.min().z() + k * f.box.sizes().z() / (kN - 1);
}

// Layers k = t, t + T, ... of the grid, batch per layer.
double evaluate_layers(const ImplicitFunction& f, int t, int T) {
  Points3 P = layer_points(f);
  Eigen::VectorXd F(P.rows());
  double sum = 0;
  for (int k = t; k < kN; k += T) {
    P.col(2).setConstant(layer_z(f, k));
    f.value(P, F);
    sum += F.sum();
  }
  return sum;
}

// The 256^3 grid, on `threads` threads (each its own layers and buffers).
void BM_rf_impeller_grid256(benchmark::State& st) {
  const ImplicitFunction& f = impeller();
  const int threads = static_cast<int>(st.range(0));
  for (auto _ : st) {
    std::vector<double> sums(threads);
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t)
      pool.emplace_back([&, t] { sums[t] = evaluate_layers(f, t, threads); });
    sums[0] = evaluate_layers(f, 0, threads);
    for (std::thread& th : pool)
      th.join();
    benchmark::DoNotOptimize(sums.data());
  }
  st.SetItemsProcessed(st.iterations() * static_cast<int64_t>(kN) * kN * kN);
}
BENCHMARK(BM_rf_impeller_grid256)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same split of work for a loop of square roots with no memory traffic: its 2-thread
// speed-up is what the machine's cores allow during the run (other processes share them).
void BM_parallel_baseline(benchmark::State& st) {
  const int threads = static_cast<int>(st.range(0));
  constexpr long kWork = 800000000; // about as long as the impeller grid on one thread
  auto spin = [&](int t) {
    double a = 0;
    for (long i = t; i < kWork; i += threads)
      a += std::sqrt(static_cast<double>(i));
    return a;
  };
  for (auto _ : st) {
    std::vector<double> sums(threads);
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t)
      pool.emplace_back([&, t] { sums[t] = spin(t); });
    sums[0] = spin(0);
    for (std::thread& th : pool)
      th.join();
    benchmark::DoNotOptimize(sums.data());
  }
}
BENCHMARK(BM_parallel_baseline)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// One layer (256^2 points at mid-height): one batch call ...
void BM_rf_impeller_layer_batch(benchmark::State& st) {
  const ImplicitFunction& f = impeller();
  Points3 P = layer_points(f);
  P.col(2).setConstant(layer_z(f, kN / 2));
  Eigen::VectorXd F(P.rows());
  for (auto _ : st) {
    f.value(P, F);
    benchmark::DoNotOptimize(F.data());
  }
  st.SetItemsProcessed(st.iterations() * P.rows());
}
BENCHMARK(BM_rf_impeller_layer_batch)->Unit(benchmark::kMillisecond)->UseRealTime();

// ... against one call per point on the same points.
void BM_rf_impeller_layer_per_point(benchmark::State& st) {
  const ImplicitFunction& f = impeller();
  Points3 P = layer_points(f);
  P.col(2).setConstant(layer_z(f, kN / 2));
  Eigen::VectorXd F(P.rows());
  for (auto _ : st) {
    for (Eigen::Index i = 0; i < P.rows(); ++i)
      f.value(P.middleRows(i, 1), F.segment(i, 1));
    benchmark::DoNotOptimize(F.data());
  }
  st.SetItemsProcessed(st.iterations() * P.rows());
}
BENCHMARK(BM_rf_impeller_layer_per_point)->Unit(benchmark::kMillisecond)->UseRealTime();

// Value and gradient (dual numbers) of the same layer, batched.
void BM_rf_impeller_layer_gradient(benchmark::State& st) {
  const ImplicitFunction& f = impeller();
  Points3 P = layer_points(f);
  P.col(2).setConstant(layer_z(f, kN / 2));
  Eigen::VectorXd F(P.rows());
  Points3 G(P.rows(), 3);
  for (auto _ : st) {
    f.gradient(P, F, G);
    benchmark::DoNotOptimize(G.data());
  }
  st.SetItemsProcessed(st.iterations() * P.rows());
}
BENCHMARK(BM_rf_impeller_layer_gradient)->Unit(benchmark::kMillisecond)->UseRealTime();

} // namespace
