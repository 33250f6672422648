// The implicit equation of the Rotor 37 blade (`interlin implicit`, models/section_body.h):
// omega with its gradient at 20 000 random points of the model's box, one thread. Baselines in
// the same run: the exact signed distance by closest-point projection onto the same boundary
// (reconstruction/implicit BodyProjection: FLANN starts + Newton, one thread) and the unsigned
// distance to the loft surface alone (reconstruction/loft project_to_surface). The ratio of the
// items_per_second is the speed-up claimed in docs/benchmarks.md ("Implicit bodies from
// sections").

#include "bench_data.h"

#include "interlin/reconstruction/implicit/body_projection.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/loft/closest_point.h"

#include <benchmark/benchmark.h>

#include <random>

namespace {

using namespace interlin;

constexpr int kPoints = 20000;

// The model as `interlin implicit data/rotor37/sections.csv` builds it (default options).
const SectionBodyModel& rotor37_body() {
  static const SectionBodyModel m = build_section_body(bench::rotor37_sections()).model;
  return m;
}

// Uniform random points of the model's box (fixed seed: every run sees the same points).
const Eigen::MatrixXd& box_points() {
  static const Eigen::MatrixXd P = [] {
    const Eigen::AlignedBox3d& box = rotor37_body().box;
    std::mt19937 rng(37);
    std::uniform_real_distribution<double> U(0, 1);
    Eigen::MatrixXd Q(kPoints, 3);
    for (int i = 0; i < kPoints; ++i)
      for (int a = 0; a < 3; ++a)
        Q(i, a) = box.min()(a) + U(rng) * box.sizes()(a);
    return Q;
  }();
  return P;
}

void BM_section_body_omega_gradient(benchmark::State& st) {
  const ImplicitFunction f = section_body_function(rotor37_body());
  const Points3 P = box_points();
  Eigen::VectorXd F(P.rows());
  Points3 G(P.rows(), 3);
  for (auto _ : st) {
    f.gradient(P, F, G);
    benchmark::DoNotOptimize(F.data());
  }
  st.SetItemsProcessed(st.iterations() * P.rows());
}
BENCHMARK(BM_section_body_omega_gradient)->Unit(benchmark::kMillisecond);

void BM_section_body_exact_distance(benchmark::State& st) {
  const SectionBodyModel& m = rotor37_body();
  const BodyProjection proj(body_patches(m.side, m.edge_u));
  const Eigen::MatrixXd& P = box_points();
  for (auto _ : st) {
    const std::vector<BodyDistance> d = proj.distances(P, 1);
    benchmark::DoNotOptimize(d.data());
  }
  st.SetItemsProcessed(st.iterations() * P.rows());
}
BENCHMARK(BM_section_body_exact_distance)->Unit(benchmark::kMillisecond);

void BM_loft_closest_point(benchmark::State& st) {
  const PiecewiseSurface S = to_piecewise(rotor37_body().side);
  const Eigen::MatrixXd& P = box_points();
  for (auto _ : st) {
    const SurfaceProjection r = project_to_surface(S, P);
    benchmark::DoNotOptimize(r.distance.data());
  }
  st.SetItemsProcessed(st.iterations() * P.rows());
}
BENCHMARK(BM_loft_closest_point)->Unit(benchmark::kMillisecond);

} // namespace
