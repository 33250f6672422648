// Volumes of the seed models by stratified Monte Carlo (interlin::estimate_volume), the reference
// that mesh volumes converge to (digest 000 T19: impeller ~1234, T21: UAV ~7.565, +-0.5 %).
// Usage: rf_volumes [MODEL.rf CELL ...]   (default: the impeller and the UAV at two cell sizes)
#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/interflatation/rfunctions/volume_estimate.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <utility>
#include <vector>

int main(int argc, char** argv) {
  std::vector<std::pair<std::string, double>> runs;
  for (int i = 1; i + 1 < argc; i += 2)
    runs.emplace_back(argv[i], std::atof(argv[i + 1]));
  if (runs.empty()) {
    const std::string d = INTERLIN_DATA_DIR "/models/";
    runs = {{d + "impeller.rf", 0.1},
            {d + "impeller.rf", 0.05},
            {d + "uav.rf", 0.02},
            {d + "uav.rf", 0.01}};
  }
  const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::printf("model, cell, samples, volume, standard error, 4-sigma interval\n");
  for (const auto& [path, cell] : runs) {
    const auto t0 = std::chrono::steady_clock::now();
    const interlin::VolumeEstimate e =
        interlin::estimate_volume(interlin::load_model(path), cell, 1, threads);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%s, %g, %ld, %.4f, %.4f, [%.4f, %.4f]  (%.1f s)\n", path.c_str(), cell, e.samples,
                e.volume, e.standard_error, e.volume - 4 * e.standard_error,
                e.volume + 4 * e.standard_error, s);
  }
}
