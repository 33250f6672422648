#include "interlin/reconstruction/clouds/noise_level.h"

#include "height_quadric.h"
#include "nearest_neighbours.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

double estimate_noise(const Eigen::MatrixX3d& P, int k, int samples) {
  if (k < 10 || samples < 1)
    throw std::invalid_argument("noise estimate: need k >= 10 and samples >= 1");
  if (P.rows() <= k)
    throw std::invalid_argument("noise estimate: need more than k points");
  const detail::NeighbourIndex index(P);
  const Eigen::Index n = P.rows();
  const Eigen::Index m = std::min<Eigen::Index>(n, samples);
  std::vector<double> var(static_cast<size_t>(m), -1);
  detail::parallel_for(static_cast<long>(m), detail::resolve_threads(0), [&](long s, int) {
    const Eigen::Index i = s * n / m; // evenly spread over the file order
    std::vector<int> idx;
    std::vector<double> d2;
    index.knn(P.row(i).transpose(), k, idx, d2);
    Eigen::MatrixX3d Q(static_cast<Eigen::Index>(idx.size()), 3);
    for (size_t j = 0; j < idx.size(); ++j)
      Q.row(static_cast<Eigen::Index>(j)) = P.row(idx[j]);
    var[static_cast<size_t>(s)] = detail::fit_height_quadric(Q).variance;
  });
  var.erase(std::remove_if(var.begin(), var.end(), [](double v) { return v < 0; }), var.end());
  if (var.empty())
    return 0;
  std::nth_element(var.begin(), var.begin() + var.size() / 2, var.end());
  return std::sqrt(var[var.size() / 2]);
}

double estimate_scan_noise(const Eigen::MatrixX3d& P, int samples) {
  // k and 2k neighbours: the cubic term's variance grows by 2^3 between them
  constexpr int kSmall = 12, kLarge = 24;
  const double s1 = estimate_noise(P, kSmall, samples), s2 = estimate_noise(P, kLarge, samples);
  return std::sqrt(std::max(0.0, (8 * s1 * s1 - s2 * s2) / 7));
}

double median_point_spacing(const Eigen::MatrixX3d& P, int k, int samples) {
  if (k < 1 || samples < 1)
    throw std::invalid_argument("point spacing: need k >= 1 and samples >= 1");
  if (P.rows() <= k)
    throw std::invalid_argument("point spacing: need more than k points");
  const detail::NeighbourIndex index(P);
  const Eigen::Index n = P.rows(), m = std::min<Eigen::Index>(n, samples);
  std::vector<double> spacing(static_cast<size_t>(m));
  detail::parallel_for(static_cast<long>(m), detail::resolve_threads(0), [&](long s, int) {
    std::vector<int> idx;
    std::vector<double> d2;
    index.knn(P.row(s * n / m).transpose(), k + 1, idx, d2); // itself first
    spacing[static_cast<size_t>(s)] = std::sqrt(d2.back() * M_PI / k);
  });
  std::nth_element(spacing.begin(), spacing.begin() + m / 2, spacing.end());
  return spacing[static_cast<size_t>(m / 2)];
}

bool is_clean_scan(const Eigen::MatrixX3d& P) {
  return estimate_scan_noise(P) < kCleanScanNoise * median_point_spacing(P);
}

int normal_neighbours_for_noise(const Eigen::MatrixX3d& P, double sigma, int k_min, int k_max,
                                int samples) {
  constexpr double kNormalTilt = 0.1; // rad, about 5.7 degrees
  if (k_min < 3 || k_max < k_min || samples < 1 || !(sigma >= 0))
    throw std::invalid_argument("normal neighbours: need 3 <= k_min <= k_max, sigma >= 0");
  if (P.rows() <= k_min)
    throw std::invalid_argument("normal neighbours: need more than k_min points");
  if (sigma == 0)
    return k_min;
  const double s = median_point_spacing(P, k_min, samples);
  if (!(s > 0))
    return k_min;
  const double k = 2 * std::sqrt(M_PI) * sigma / (s * kNormalTilt);
  return int(std::clamp(std::ceil(k), double(k_min), double(k_max)));
}

} // namespace interlin
