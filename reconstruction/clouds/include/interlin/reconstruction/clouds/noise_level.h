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

} // namespace interlin
