// Stratified Monte Carlo volume of {F > 0}: two uniform points per cell of a regular grid.
#include "interlin/interflatation/rfunctions/volume_estimate.h"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace interlin {

VolumeEstimate estimate_volume(const ImplicitFunction& f, double cell, unsigned seed, int threads) {
  if (f.box.isEmpty() || !(cell > 0) || threads < 1)
    throw std::invalid_argument("estimate_volume: need a non-empty box, cell > 0 and threads >= 1");
  const Eigen::Vector3d size = f.box.sizes();
  Eigen::Vector3i n;
  for (int c = 0; c < 3; ++c)
    n(c) = static_cast<int>(std::ceil(size(c) / cell));
  if (static_cast<double>(n.x()) * n.y() * n.z() > 2147483647.0)
    throw std::invalid_argument("estimate_volume: more than 2^31 cells; use a larger cell");
  const Eigen::Vector3d h = size.cwiseQuotient(n.cast<double>());
  const double cv = h.prod();
  // one layer (fixed k) at a time, per thread: inside counts and the variance sum
  std::vector<double> inside(n.z(), 0.0), var(n.z(), 0.0);
  auto work = [&](int t) {
    const Eigen::Index m = static_cast<Eigen::Index>(n.x()) * n.y();
    Points3 P(2 * m, 3);
    Eigen::VectorXd F(2 * m);
    for (int k = t; k < n.z(); k += threads) {
      std::mt19937_64 rng(seed * 1000003ULL + static_cast<unsigned long long>(k));
      std::uniform_real_distribution<double> u(0, 1);
      for (int j = 0, r = 0; j < n.y(); ++j)
        for (int i = 0; i < n.x(); ++i)
          for (int s = 0; s < 2; ++s, ++r)
            P.row(r) << f.box.min().x() + (i + u(rng)) * h.x(),
                f.box.min().y() + (j + u(rng)) * h.y(), f.box.min().z() + (k + u(rng)) * h.z();
      f.value(P, F);
      double in = 0, v = 0;
      for (Eigen::Index c = 0; c < m; ++c) {
        const double a = F(2 * c) > 0, b = F(2 * c + 1) > 0;
        in += a + b;
        v += (a - b) * (a - b);
      }
      inside[k] = in;
      var[k] = v;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
    pool.emplace_back(work, t);
  work(0);
  for (std::thread& th : pool)
    th.join();
  VolumeEstimate e;
  double in = 0, v = 0;
  for (int k = 0; k < n.z(); ++k)
    in += inside[k], v += var[k];
  e.volume = cv * in / 2;
  e.standard_error = cv * std::sqrt(v / 4);
  e.samples = 2L * n.x() * n.y() * n.z();
  return e;
}

} // namespace interlin
