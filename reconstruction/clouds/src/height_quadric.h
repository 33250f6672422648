#pragma once
// Private to reconstruction/clouds: the quadratic height function of a neighbourhood in its
// principal frame, fitted by least squares (estimate_noise's residuals, the outlier filter's
// on-surface test).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace interlin::detail {

// w = h(u, v) = c0 u^2 + c1 u v + c2 v^2 + c3 u + c4 v + c5 over the points Q (k by 3, k > 6) in
// their principal frame (w along the smallest eigenvector, u along the largest), u, v and w
// divided by the scale s = sqrt(largest eigenvalue / k).
struct HeightQuadric {
  Eigen::RowVector3d mean;
  Eigen::Matrix3d frame; // columns: w, v, u
  double scale = 0;
  Eigen::Matrix<double, 6, 1> c;
  double variance = -1; // residual variance, sum r^2 / (k - 6), in Q's units; < 0: degenerate

  // The point p in the frame: (w, v, u), unscaled.
  Eigen::RowVector3d local(const Eigen::RowVector3d& p) const { return (p - mean) * frame; }
  // w - h(u, v) at p, in Q's units: its offset from the quadric along the normal.
  double offset(const Eigen::RowVector3d& p) const {
    const Eigen::RowVector3d l = local(p) / scale;
    return (l(0) - basis(l(2), l(1)).dot(c)) * scale;
  }
  static Eigen::Matrix<double, 1, 6> basis(double u, double v) {
    return {u * u, u * v, v * v, u, v, 1};
  }
};

inline HeightQuadric fit_height_quadric(const Eigen::MatrixX3d& Q) {
  HeightQuadric h;
  h.mean = Q.colwise().mean();
  const Eigen::MatrixX3d X = Q.rowwise() - h.mean;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(X.transpose() * X);
  h.frame = es.eigenvectors();
  h.scale = std::sqrt(std::max(es.eigenvalues()(2), 0.0) / double(Q.rows()));
  if (!(h.scale > 0))
    return h;
  const Eigen::MatrixX3d L = X * h.frame;
  Eigen::MatrixXd A(Q.rows(), 6);
  for (Eigen::Index i = 0; i < Q.rows(); ++i)
    A.row(i) = HeightQuadric::basis(L(i, 2) / h.scale, L(i, 1) / h.scale);
  const Eigen::VectorXd w = L.col(0) / h.scale;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  if (qr.rank() < 6)
    return h;
  h.c = qr.solve(w);
  h.variance = (A * h.c - w).squaredNorm() * h.scale * h.scale / double(Q.rows() - 6);
  return h;
}

} // namespace interlin::detail
