// Evaluation speed of the two cloud implicits on the same cloud (docs/benchmarks.md, "Sparse
// clouds: the Hermite RBF"): PCL's bunny (392 points after outlier removal, the file's normals)
// fitted by the partition of unity and by the Hermite RBF, each evaluated (value; value and
// gradient) at 1 M points uniform in its box, one thread. The RBF costs O(#points) per point.
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/hermite_rbf.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/clouds/read_point_cloud.h"

#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <string>

namespace {

using namespace interlin;

const PointCloud& bunny() {
  static const PointCloud c = [] {
    const std::string path = std::string(INTERLIN_DATA_DIR) + "/clouds/bun0.pcd";
    return prepare_cloud(path, read_point_cloud(path), {});
  }();
  return c;
}

const ImplicitFunction& model(bool hermite) {
  static const ImplicitFunction pu =
      cloud_implicit_function(std::make_shared<const CloudImplicit>(fit_cloud_implicit(bunny())));
  static const ImplicitFunction rbf =
      hermite_rbf_function(std::make_shared<const HermiteRbf>(fit_hermite_rbf(bunny())));
  return hermite ? rbf : pu;
}

Points3 points_in(const Eigen::AlignedBox3d& box, Eigen::Index n) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> U(0, 1);
  Points3 P(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a)
      P(i, a) = box.min()(a) + U(rng) * box.sizes()(a);
  return P;
}

// state.range(0): 0 partition of unity, 1 Hermite RBF; range(1): 1 with the gradient
void BM_cloud_eval(benchmark::State& state) {
  const ImplicitFunction& F = model(state.range(0) == 1);
  constexpr Eigen::Index kPoints = 1 << 20;
  const Points3 P = points_in(F.box, kPoints);
  Eigen::VectorXd v(kPoints);
  Points3 G(kPoints, 3);
  for (auto _ : state) {
    if (state.range(1) == 1)
      F.gradient(P, v, G);
    else
      F.value(P, v);
    benchmark::DoNotOptimize(v.data());
  }
  state.SetItemsProcessed(state.iterations() * kPoints);
}
BENCHMARK(BM_cloud_eval)
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->ArgNames({"hrbf", "gradient"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

} // namespace
