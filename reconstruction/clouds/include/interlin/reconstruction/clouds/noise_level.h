#pragma once
// The noise of a scan, estimated from the points alone.

#include <Eigen/Core>

namespace interlin {

// Standard deviation of the scan noise normal to the surface. At up to `samples` points spread
// over the cloud, a quadratic height function is fitted by least squares to the k nearest
// neighbours in their principal frame; its residual variance with the degrees of freedom
// removed, sum r^2 / (k - 6), estimates sigma^2 where the surface is smooth on the scale of the
// neighbourhood. The median over the samples ignores neighbourhoods that straddle edges or thin
// walls (there the quadric does not fit).
// Inputs: P #P by 3 (#P > k), k >= 10 neighbours, samples >= 1
// Output: sigma >= 0 (about the quadric's approximation error, O(h^3), for noise-free points).
double estimate_noise(const Eigen::MatrixX3d& P, int k = 24, int samples = 2000);

// The part of estimate_noise's sigma that does not depend on the neighbourhood's size: the scan
// noise, without the quadric's approximation error. The residual variance at k neighbours is
// about sigma_n^2 + a k^3 (a missing cubic term gives distances ~ r^3 over a radius r ~ sqrt(k)),
// so from k = 12 and 24: sigma_n^2 = (8 sigma_12^2 - sigma_24^2) / 7, floored at 0. Noisy scans
// give sigma_n ~ sigma_24; noise-free models, whose sigma_24 is shape (edges, thin walls), ~ 0.
// Inputs: P #P by 3 (#P > 24), samples >= 1
double estimate_scan_noise(const Eigen::MatrixX3d& P, int samples = 2000);

// Scan noise (estimate_scan_noise) below this many point spacings: a clean cloud, sampled from a
// model or a mesh (the bench's CAD models read 0, simulated and real scans 0.17 to 0.5).
constexpr double kCleanScanNoise = 0.002;

// The median point spacing: over up to `samples` points spread over the cloud, d sqrt(pi / k),
// d the distance to the k-th nearest neighbour (the radius of a disc of k points of spacing s is
// s sqrt(k / pi)).
// Inputs: P #P by 3 (#P > k), k >= 1, samples >= 1
// Output: s >= 0. Throws std::invalid_argument for bad inputs.
double median_point_spacing(const Eigen::MatrixX3d& P, int k = 16, int samples = 2000);

// Whether the cloud is clean: estimate_scan_noise below kCleanScanNoise median_point_spacing.
// Inputs: P #P by 3 (#P > 24)
bool is_clean_scan(const Eigen::MatrixX3d& P);

// The number of nearest neighbours for PCA normals (estimate_normals) at noise sigma. For k
// points of spacing s in a disc of radius r = s sqrt(k / pi) with height noise sigma, the fitted
// plane's slope has standard error sigma / sqrt(sum x^2) = 2 sigma / (r sqrt(k)) =
// 2 sqrt(pi) sigma / (s k); k is chosen so that this is kNormalTilt = 0.1 rad:
// k = 2 sqrt(pi) sigma / (0.1 s), clamped to [k_min, k_max]. s is median_point_spacing(P, k_min,
// samples). A fixed k
// lets the neighbourhood shrink below the noise on dense scans: the noisy blade (sigma 0.02 cm)
// at 300,000 points had no normal within 30 degrees of its neighbours' and 8.9 % of them inward
// at k = 16 (docs/benchmarks.md, "Normals at the noise's scale"). 0.1 rad was chosen on that
// blade at 30,000 to 300,000 points, with estimate_noise's sigma, which reads low on dense scans
// (0.0149 for 0.02 at 300,000 points): 0.08 made the 30,000-point scan worse.
// Inputs: P #P by 3 (#P > k_min), sigma >= 0 (estimate_noise), 3 <= k_min <= k_max
// Output: k; k_min when sigma is 0. Throws std::invalid_argument for bad inputs.
int normal_neighbours_for_noise(const Eigen::MatrixX3d& P, double sigma, int k_min = 16,
                                int k_max = 64, int samples = 2000);

} // namespace interlin
