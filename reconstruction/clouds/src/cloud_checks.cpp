#include "interlin/reconstruction/clouds/cloud_checks.h"

#include "interlin/reconstruction/io/input_error.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <numeric>
#include <sstream>

namespace interlin {

using Eigen::Index;

namespace {

// Rows of P without exact repeats, first occurrences in input order.
std::vector<Index> distinct_rows(const Eigen::MatrixX3d& P) {
  std::vector<Index> order(static_cast<size_t>(P.rows()));
  std::iota(order.begin(), order.end(), Index{0});
  auto less = [&](Index a, Index b) {
    for (int c = 0; c < 3; ++c)
      if (P(a, c) != P(b, c))
        return P(a, c) < P(b, c);
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<Index> keep;
  for (size_t i = 0; i < order.size(); ++i)
    if (i == 0 || P.row(order[i]) != P.row(order[i - 1]))
      keep.push_back(order[i]);
  std::sort(keep.begin(), keep.end());
  return keep;
}

std::string str(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

} // namespace

PointCloud check_cloud(const std::string& path, const PointCloud& c,
                       std::vector<std::string>* notes) {
  const std::vector<Index> keep = distinct_rows(c.points);
  PointCloud d;
  d.points.resize(static_cast<Index>(keep.size()), 3);
  d.normals.resize(c.has_normals() ? static_cast<Index>(keep.size()) : 0, 3);
  for (size_t i = 0; i < keep.size(); ++i) {
    d.points.row(static_cast<Index>(i)) = c.points.row(keep[i]);
    if (c.has_normals())
      d.normals.row(static_cast<Index>(i)) = c.normals.row(keep[i]);
  }
  const Index removed = c.points.rows() - d.points.rows();
  if (removed > 0 && notes)
    notes->push_back(path + ": " + std::to_string(removed) + " repeated point(s) removed");
  const Index n = d.points.rows();
  const std::string repeated =
      removed > 0 ? " (after removing " + std::to_string(removed) + " repeated point(s))" : "";
  if (n < kMinCloudPoints)
    throw_input_error(path, 0,
                      "only " + std::to_string(n) + " distinct point(s)" + repeated +
                          ": fitting a surface needs at least " + std::to_string(kMinCloudPoints));
  // Extents along the principal axes: sqrt of the covariance eigenvalues (ascending).
  const Eigen::RowVector3d mean = d.points.colwise().mean();
  const Eigen::MatrixX3d X = d.points.rowwise() - mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(X.transpose() * X / double(n));
  const Eigen::Vector3d ext = es.eigenvalues().cwiseMax(0).cwiseSqrt();
  // kFlat: relative thinness below which a cloud is degenerate (float32 round-off is ~6e-8)
  constexpr double kFlat = 1e-6;
  if (ext(2) == 0)
    throw_input_error(path, 0, "all " + std::to_string(n) + " points are identical" + repeated);
  if (ext(1) <= kFlat * ext(2))
    throw_input_error(path, 0,
                      "all " + std::to_string(n) + " points lie on one line (spread " +
                          str(ext(1)) + " across it): a line bounds no volume");
  if (ext(0) <= kFlat * ext(2))
    throw_input_error(path, 0,
                      "all " + std::to_string(n) + " points lie on one plane (spread " +
                          str(ext(0)) + " across it): a plane bounds no volume");
  return d;
}

} // namespace interlin
