// The partition of unity or the Hermite RBF by five-fold hold-out (choose_cloud_fit.h).
#include "interlin/reconstruction/clouds/choose_cloud_fit.h"

#include "interlin/reconstruction/clouds/hermite_rbf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

namespace interlin {

namespace {

constexpr int kFolds = 5;

// Sum of |F| / |grad F| over the rows `test` of P.
double distance_sum(const ImplicitFunction& F, const Eigen::MatrixX3d& P) {
  Eigen::VectorXd v(P.rows());
  Points3 G(P.rows(), 3);
  F.gradient(P, v, G);
  return (v.cwiseAbs().array() / G.rowwise().norm().array().max(1e-300)).sum();
}

} // namespace

CloudFitChoice choose_cloud_fit(const PointCloud& c, CloudFitOptions fit) {
  fit.progress = nullptr; // the folds' fits are not the job's progress
  const Eigen::Index n = c.points.rows();
  if (n > kHermiteRbfAutoPoints || !c.has_normals())
    throw std::invalid_argument("choose_cloud_fit: needs oriented normals and at most " +
                                std::to_string(kHermiteRbfAutoPoints) + " points");
  std::vector<Eigen::Index> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), Eigen::Index{0});
  std::shuffle(order.begin(), order.end(), std::mt19937(1));
  double pu = 0, rbf = 0;
  for (int fold = 0; fold < kFolds; ++fold) {
    std::vector<Eigen::Index> train, test;
    for (Eigen::Index k = 0; k < n; ++k)
      (k % kFolds == fold ? test : train).push_back(order[static_cast<size_t>(k)]);
    PointCloud t;
    t.points = c.points(train, Eigen::all);
    t.normals = c.normals(train, Eigen::all);
    const Eigen::MatrixX3d Q = c.points(test, Eigen::all);
    try {
      pu += distance_sum(cloud_implicit_function(
                             std::make_shared<const CloudImplicit>(fit_cloud_implicit(t, fit))),
                         Q);
    } catch (const std::invalid_argument&) {
      pu = std::numeric_limits<double>::quiet_NaN();
    }
    try {
      rbf += distance_sum(
          hermite_rbf_function(std::make_shared<const HermiteRbf>(fit_hermite_rbf(t))), Q);
    } catch (const std::invalid_argument&) {
      rbf = std::numeric_limits<double>::quiet_NaN();
    }
  }
  CloudFitChoice r;
  r.holdout_pu = pu / double(n);
  r.holdout_hrbf = rbf / double(n);
  r.hermite = std::isnan(r.holdout_pu) ? !std::isnan(r.holdout_hrbf)
                                       : r.holdout_hrbf < r.holdout_pu; // NaN compares false
  return r;
}

} // namespace interlin
