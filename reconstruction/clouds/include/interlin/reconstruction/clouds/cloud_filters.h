#pragma once
// Cloud preparation through PCL: statistical outlier removal, voxel-grid downsampling and normal
// estimation (PCL's filters and features with its FLANN kd-tree). Orientation of the normals is
// orient_normals (orient_normals.h).

#include "interlin/reconstruction/clouds/point_cloud.h"

namespace interlin {

// pcl::StatisticalOutlierRemoval flags a point when its mean distance to its k nearest
// neighbours exceeds the mean of that quantity over the cloud by more than std_ratio standard
// deviations. A flagged point is removed unless it lies on the surface of its k nearest kept
// points (a quadratic height function over them misses it by at most 3 of their residual
// deviations plus a tenth of their footprint; k >= 10): on a clean scan the filter flags the
// points of the random sampling's widest gaps (75 of 20,000 on a sphere), and removing those
// opens holes. Normals, when present, follow their points.
// Inputs: c (#P >= 2 points), k >= 1 neighbours, std_ratio > 0
// Output: the kept points in input order; `removed` (optional) the number removed.
// Throws std::invalid_argument for bad parameters.
PointCloud remove_statistical_outliers(const PointCloud& c, int k, double std_ratio,
                                       Eigen::Index* removed = nullptr);

// pcl::VoxelGrid: the points in each cubic voxel of side `leaf` replaced by their centroid
// (normals averaged and renormalised; dropped when an average vanishes, which only happens for
// unoriented normals: they are then estimated again). Output order is PCL's (by voxel).
// Throws std::invalid_argument for leaf <= 0, and when the voxel count would overflow PCL's
// 32-bit voxel index (the message names the smallest leaf that fits).
PointCloud voxel_downsample(const PointCloud& c, double leaf);

// pcl::NormalEstimationOMP: the normal of each point is the eigenvector of the smallest
// eigenvalue of the covariance of its k nearest neighbours (itself included). Unoriented: the
// sign is arbitrary until orient_normals.
// Inputs: P #P by 3 (#P > k), k >= 3, threads (0: all cores)
// Output: #P by 3 unit normals.
Eigen::MatrixX3d estimate_normals(const Eigen::MatrixX3d& P, int k, int threads = 0);

// Normals whose neighbourhoods keep to one sheet. Near a sharp edge, across a narrow gap or
// beside a thin wall the k nearest neighbours straddle two sheets, and their PCA normal blends
// both (more than 20 degrees off at 6 to 20 % of the points of the bench's CAD models, k = 16).
// Each of the k nearest points q (the point i itself included) proposes the plane through p_i
// normal to q's PCA normal of 6 neighbours (estimate_normals); the plane with the most of the k
// within sheet_tolerance of it (a quarter of the local spacing + 3 sigma) selects them, and PCL's
// PCA of the selection (pcl::computePointNormal) is the normal; with fewer than 6 selected, the
// 6-neighbour normal. On a smooth sheet every neighbour is selected and the normal is
// estimate_normals's. Signs: sign_sheet_normals. docs/benchmarks.md "Normals that keep to one
// sheet".
// Inputs: P #P by 3 (#P > k), k >= 6, sigma >= 0 the noise (estimate_noise), threads (0: all)
// Output: #P by 3 unit normals, unoriented. Throws std::invalid_argument for bad inputs.
// See also: estimate_normals, sign_sheet_normals (orient_normals.h)
Eigen::MatrixX3d estimate_sheet_normals(const Eigen::MatrixX3d& P, int k, double sigma,
                                        int threads = 0);

} // namespace interlin
