// The winding number of an oriented cloud (winding_number.h).
#include "winding_number.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace interlin::detail {

namespace {

// A cluster counts as one dipole beyond this multiple of its radius (Barill et al. use 2: the
// first-order term's relative error is then below (1/2)^2).
constexpr double kFarRatio = 2.0;
// Points per cluster on average: clusters of a surface in a grid of G^3 cells number about G^2.
constexpr double kClusterPoints = 16;

} // namespace

Eigen::VectorXd point_areas(const Eigen::MatrixX3d& P, const Eigen::MatrixXi& knn) {
  Eigen::VectorXd a(P.rows());
  const int k = static_cast<int>(knn.cols());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double r2 = k > 0 ? (P.row(knn(i, k - 1)) - P.row(i)).squaredNorm() : 0;
    a(i) = M_PI * r2 / std::max(k, 1);
  }
  return a;
}

WindingNumber::WindingNumber(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& N,
                             const Eigen::VectorXd& area) {
  const Eigen::Vector3d lo = P.colwise().minCoeff(), hi = P.colwise().maxCoeff();
  const double side = std::max((hi - lo).maxCoeff(), 1e-300);
  const int G = std::clamp(int(std::sqrt(double(P.rows()) / kClusterPoints)), 1, 256);
  const double h = side / G * (1 + 1e-12);
  std::map<long, std::vector<Eigen::Index>> cells;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const Eigen::Array3i c = ((P.row(i).transpose() - lo) / h).array().floor().cast<int>();
    cells[(long(c(2)) * G + c(1)) * G + c(0)].push_back(i);
  }
  P_.resize(P.rows(), 3);
  D_.resize(P.rows(), 3);
  int row = 0;
  for (const auto& [key, members] : cells) {
    Cluster c;
    c.begin = row;
    double sa = 0;
    c.centroid.setZero();
    c.dipole.setZero();
    for (Eigen::Index i : members) {
      P_.row(row) = P.row(i);
      D_.row(row) = area(i) * N.row(i);
      c.centroid += area(i) * P.row(i).transpose();
      c.dipole += D_.row(row).transpose();
      sa += area(i);
      ++row;
    }
    c.end = row;
    c.centroid =
        sa > 0
            ? Eigen::Vector3d(c.centroid / sa)
            : Eigen::Vector3d(P_.middleRows(c.begin, c.end - c.begin).colwise().mean().transpose());
    for (int r = c.begin; r < c.end; ++r)
      c.radius = std::max(c.radius, (P_.row(r).transpose() - c.centroid).norm());
    clusters_.push_back(c);
  }
}

double WindingNumber::operator()(const Eigen::Vector3d& q) const {
  double w = 0;
  auto term = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
    const Eigen::Vector3d r = p - q;
    const double l2 = r.squaredNorm();
    if (l2 > 0)
      w += d.dot(r) / (l2 * std::sqrt(l2));
  };
  for (const Cluster& c : clusters_) {
    if ((c.centroid - q).squaredNorm() > std::pow(kFarRatio * c.radius, 2)) {
      term(c.centroid, c.dipole);
      continue;
    }
    for (int r = c.begin; r < c.end; ++r)
      term(P_.row(r).transpose(), D_.row(r).transpose());
  }
  return w / (4 * M_PI);
}

} // namespace interlin::detail
