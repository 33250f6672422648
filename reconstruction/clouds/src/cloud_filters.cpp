// The PCL filters and features used by the cloud job (the one translation unit that sees PCL's
// filter and feature headers; compile time matters on 2-core CI).
#include "interlin/reconstruction/clouds/cloud_filters.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include "height_quadric.h"
#include "nearest_neighbours.h"
#include "sheet_plane.h"

#include <pcl/features/normal_3d.h>
#include <pcl/features/normal_3d_omp.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin {

namespace {

// Coordinates relative to `origin` in float (PCL's point types are single precision; the offset
// keeps far-from-origin scans, e.g. blades at radius 20, at full float resolution).
pcl::PointCloud<pcl::PointNormal>::Ptr to_pcl(const PointCloud& c, const Eigen::Vector3d& origin) {
  auto out = std::make_shared<pcl::PointCloud<pcl::PointNormal>>();
  out->resize(static_cast<size_t>(c.points.rows()));
  for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
    pcl::PointNormal& p = (*out)[static_cast<size_t>(i)];
    p.x = static_cast<float>(c.points(i, 0) - origin(0));
    p.y = static_cast<float>(c.points(i, 1) - origin(1));
    p.z = static_cast<float>(c.points(i, 2) - origin(2));
    const bool n = c.has_normals();
    p.normal_x = n ? static_cast<float>(c.normals(i, 0)) : 0.f;
    p.normal_y = n ? static_cast<float>(c.normals(i, 1)) : 0.f;
    p.normal_z = n ? static_cast<float>(c.normals(i, 2)) : 0.f;
    p.curvature = 0.f;
  }
  return out;
}

Eigen::Vector3d centre(const Eigen::MatrixX3d& P) {
  return 0.5 * (P.colwise().minCoeff() + P.colwise().maxCoeff()).transpose();
}

// Whether point p lies on the surface of the points Q (k by 3, k > 6): the quadratic height
// function of Q in its principal frame (height_quadric.h) misses p by at most kSurfaceSigmas
// residual deviations of Q plus kSurfaceReach of Q's footprint (its farthest point from its
// centroid), and p's (u, v) lies within the footprint. The footprint term admits the cubic terms
// a quadric leaves on a clean scan (residual ~ 0); a flagged outlier lies a few point spacings
// (a footprint of 16 points: about 2.3) off.
bool on_quadric(const Eigen::MatrixX3d& Q, const Eigen::RowVector3d& p) {
  constexpr double kSurfaceSigmas = 3, kSurfaceReach = 0.1;
  const detail::HeightQuadric h = detail::fit_height_quadric(Q);
  const double footprint = (Q.rowwise() - h.mean).rowwise().norm().maxCoeff();
  if (h.variance < 0 || h.local(p).tail<2>().norm() > footprint)
    return false;
  return std::abs(h.offset(p)) <=
         kSurfaceSigmas * std::sqrt(h.variance) + kSurfaceReach * footprint;
}

// The flagged points that lie on the surface of their k nearest kept points (on_quadric). The
// statistical filter also flags the points of a clean scan's sparsest stretches (the random
// sampling's largest gaps); removing those widens the gaps into holes, through which the
// orientation's flood fill leaks (the 300,000-point car: 892 flagged, 19.6 % of the normals
// then inward; docs/benchmarks.md, "Outlier removal that keeps the surface").
std::vector<pcl::index_t> surface_points(const Eigen::MatrixX3d& P,
                                         const pcl::PointCloud<pcl::PointNormal>::Ptr& cloud,
                                         const pcl::Indices& kept, const pcl::Indices& flagged,
                                         int k) {
  pcl::search::KdTree<pcl::PointNormal> tree(false);
  tree.setInputCloud(cloud, std::make_shared<const pcl::Indices>(kept));
  std::vector<pcl::index_t> on_surface;
  pcl::Indices nb;
  std::vector<float> d2;
  for (pcl::index_t i : flagged)
    if (tree.nearestKSearch((*cloud)[size_t(i)], k, nb, d2) == k &&
        on_quadric(P(nb, Eigen::all), P.row(i)))
      on_surface.push_back(i);
  return on_surface;
}

} // namespace

PointCloud remove_statistical_outliers(const PointCloud& c, int k, double std_ratio,
                                       Eigen::Index* removed) {
  if (k < 1 || !(std_ratio > 0) || !std::isfinite(std_ratio))
    throw std::invalid_argument("outlier removal: need k >= 1 and std_ratio > 0");
  if (c.points.rows() <= k) {
    if (removed)
      *removed = 0;
    return c;
  }
  const Eigen::Vector3d o = centre(c.points);
  const auto cloud = to_pcl(c, o);
  pcl::StatisticalOutlierRemoval<pcl::PointNormal> sor(true);
  sor.setInputCloud(cloud);
  sor.setMeanK(k);
  sor.setStddevMulThresh(std_ratio);
  pcl::Indices kept;
  sor.filter(kept);
  const pcl::IndicesConstPtr flagged = sor.getRemovedIndices();
  constexpr int kQuadricLeast = 9; // points for on_quadric's 6 coefficients and a residual
  if (!flagged->empty() && k > kQuadricLeast && kept.size() >= size_t(k)) {
    for (pcl::index_t i : surface_points(c.points, cloud, kept, *flagged, k))
      kept.push_back(i);
    std::sort(kept.begin(), kept.end()); // input order
  }
  PointCloud out;
  out.points = c.points(kept, Eigen::all);
  if (c.has_normals())
    out.normals = c.normals(kept, Eigen::all);
  if (removed)
    *removed = c.points.rows() - out.points.rows();
  return out;
}

PointCloud voxel_downsample(const PointCloud& c, double leaf) {
  if (!(leaf > 0) || !std::isfinite(leaf))
    throw std::invalid_argument("voxel downsampling: the voxel size must be positive");
  const Eigen::Vector3d lo = c.points.colwise().minCoeff(), hi = c.points.colwise().maxCoeff();
  const Eigen::Array3d cells = ((hi - lo).array() / leaf).floor() + 1;
  // PCL indexes voxels with a 32-bit integer (it refuses larger grids with a console message).
  const double limit = double(std::numeric_limits<std::int32_t>::max());
  if (cells.prod() > limit)
    throw std::invalid_argument("voxel downsampling: voxel size " + std::to_string(leaf) +
                                " gives " + std::to_string(cells.prod()) +
                                " voxels, more than PCL's 32-bit index; use at least " +
                                std::to_string(std::cbrt((hi - lo).array().prod() / limit) * 1.01));
  const Eigen::Vector3d o = centre(c.points);
  pcl::VoxelGrid<pcl::PointNormal> grid;
  grid.setInputCloud(to_pcl(c, o));
  const float l = static_cast<float>(leaf);
  grid.setLeafSize(l, l, l);
  grid.setDownsampleAllData(true);
  pcl::PointCloud<pcl::PointNormal> f;
  grid.filter(f);
  PointCloud out;
  const Eigen::Index n = static_cast<Eigen::Index>(f.size());
  out.points.resize(n, 3);
  out.normals.resize(c.has_normals() ? n : 0, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const pcl::PointNormal& p = f[static_cast<size_t>(i)];
    out.points.row(i) = Eigen::RowVector3d(p.x, p.y, p.z) + o.transpose();
    if (c.has_normals())
      out.normals.row(i) = Eigen::RowVector3d(p.normal_x, p.normal_y, p.normal_z);
  }
  if (c.has_normals()) {
    const Eigen::VectorXd len = out.normals.rowwise().norm();
    // kVanishedNormal: averages of opposite (unoriented) normals cancel to about this length
    constexpr double kVanishedNormal = 1e-3;
    if (len.minCoeff() < kVanishedNormal)
      out.normals.resize(0, 3);
    else
      out.normals.array().colwise() /= len.array();
  }
  return out;
}

Eigen::MatrixX3d estimate_normals(const Eigen::MatrixX3d& P, int k, int threads) {
  if (k < 3)
    throw std::invalid_argument("normal estimation: need at least 3 neighbours");
  if (P.rows() <= k)
    throw std::invalid_argument("normal estimation: need more than " + std::to_string(k) +
                                " points, got " + std::to_string(P.rows()));
  PointCloud c;
  c.points = P;
  const Eigen::Vector3d o = centre(P);
  pcl::NormalEstimationOMP<pcl::PointNormal, pcl::Normal> ne(
      static_cast<unsigned>(detail::resolve_threads(threads)));
  ne.setInputCloud(to_pcl(c, o));
  ne.setSearchMethod(std::make_shared<pcl::search::KdTree<pcl::PointNormal>>());
  ne.setKSearch(k);
  pcl::PointCloud<pcl::Normal> n;
  ne.compute(n);
  Eigen::MatrixX3d N(P.rows(), 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const pcl::Normal& q = n[static_cast<size_t>(i)];
    Eigen::Vector3d v(q.normal_x, q.normal_y, q.normal_z);
    // PCL leaves NaN where the neighbourhood is degenerate (all neighbours on one line)
    N.row(i) = std::isfinite(v.squaredNorm()) && v.norm() > 0 ? v.normalized().transpose()
                                                              : Eigen::RowVector3d(0, 0, 1);
  }
  return N;
}

namespace {

// The neighbours of point i (itself first, then K's row) on the plane proposed by one of them
// with the most of them on it.
pcl::Indices sheet_neighbours(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& proposed,
                              const Eigen::MatrixXi& K, Eigen::Index i, double sigma) {
  pcl::Indices near{int(i)};
  for (Eigen::Index j = 0; j < K.cols(); ++j)
    near.push_back(K(i, j));
  const double tol =
      detail::sheet_tolerance((P.row(near[detail::kSheetProposal - 1]) - P.row(i)).norm(), sigma);
  auto on_plane = [&](int j, int through) {
    return std::abs((P.row(j) - P.row(i)).dot(proposed.row(through))) <= tol;
  };
  int best = int(i), most = 0;
  for (int q : near) {
    const int count =
        int(std::count_if(near.begin(), near.end(), [&](int j) { return on_plane(j, q); }));
    if (count > most)
      most = count, best = q;
  }
  pcl::Indices sheet;
  std::copy_if(near.begin(), near.end(), std::back_inserter(sheet),
               [&](int j) { return on_plane(j, best); });
  return sheet;
}

} // namespace

Eigen::MatrixX3d estimate_sheet_normals(const Eigen::MatrixX3d& P, int k, double sigma,
                                        int threads) {
  if (!(sigma >= 0))
    throw std::invalid_argument("sheet normals: the noise sigma must be >= 0");
  if (k < detail::kSheetProposal)
    throw std::invalid_argument("sheet normals: need at least " +
                                std::to_string(detail::kSheetProposal) + " neighbours");
  if (P.rows() <= k)
    throw std::invalid_argument("sheet normals: need more than " + std::to_string(k) +
                                " points, got " + std::to_string(P.rows()));
  const Eigen::MatrixX3d proposed = estimate_normals(P, detail::kSheetProposal, threads);
  const Eigen::MatrixXi K = detail::NeighbourIndex(P).knn_all(k - 1, threads); // itself excluded
  PointCloud c;
  c.points = P;
  const auto cloud = to_pcl(c, centre(P));
  Eigen::MatrixX3d N(P.rows(), 3);
  detail::parallel_for(long(P.rows()), detail::resolve_threads(threads), [&](long i, int) {
    const pcl::Indices sheet = sheet_neighbours(P, proposed, K, i, sigma);
    Eigen::Vector4f plane;
    float curvature;
    const bool fitted = int(sheet.size()) >= detail::kSheetProposal &&
                        pcl::computePointNormal(*cloud, sheet, plane, curvature) &&
                        plane.head<3>().allFinite() && plane.head<3>().norm() > 0;
    N.row(i) = fitted ? Eigen::RowVector3d(plane.head<3>().cast<double>().normalized())
                      : Eigen::RowVector3d(proposed.row(i));
  });
  return N;
}

} // namespace interlin
