// Hermite RBF interpolation of an oriented cloud (Macêdo, Gois, Velho 2011, §3): hermite_rbf.h.

#include "interlin/reconstruction/clouds/hermite_rbf.h"

#include "nearest_neighbours.h"
#include "winding_number.h"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;

namespace {

// The Gram matrix of the functionals f -> f(p_i) and f -> d f / d x_c (p_i) applied to both
// arguments of phi(x - y) = |x - y|^3 (Macêdo et al., eq. 7): rows and columns ordered as the
// #P values, then the #P x-derivatives, y, z. With d = p_i - p_j, r = |d|:
//   value-value r^3, value-derivative -3 r d_e, derivative-value 3 r d_c,
//   derivative-derivative -3 (r delta_ce + d_c d_e / r) (0 at r = 0).
MatrixXd gram_matrix(const Eigen::MatrixX3d& P) {
  const Index n = P.rows();
  MatrixXd M(4 * n, 4 * n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i) {
      const Vector3d d = (P.row(i) - P.row(j)).transpose();
      const double r = d.norm();
      M(i, j) = r * r * r;
      for (int c = 0; c < 3; ++c) {
        M(i, n + c * n + j) = -3 * r * d(c);
        M(n + c * n + i, j) = 3 * r * d(c);
        for (int e = 0; e < 3; ++e)
          M(n + c * n + i, n + e * n + j) =
              r > 0 ? -3 * (r * (c == e ? 1.0 : 0.0) + d(c) * d(e) / r) : 0.0;
      }
    }
  return M;
}

// The linear polynomials' conditions: the functionals applied to 1, x, y, z (4 #P by 4).
MatrixXd polynomial_block(const Eigen::MatrixX3d& P) {
  const Index n = P.rows();
  MatrixXd B = MatrixXd::Zero(4 * n, 4);
  B.topLeftCorner(n, 1).setOnes();
  B.topRightCorner(n, 3) = P;
  for (int c = 0; c < 3; ++c)
    B.block(n + c * n, 1 + c, n, 1).setOnes();
  return B;
}

// Solves [M B; B^T 0] [lambda; gamma] = [rhs; 0] on the null space of B^T: with B = Q [R; 0],
// lambda = Q [0; y], (Q^T M Q)_22 y = (Q^T rhs)_2 (Cholesky: positive definite there), then
// R gamma = (Q^T rhs)_1 - (Q^T M Q)_12 y. M is overwritten.
void solve_saddle(MatrixXd& M, const MatrixXd& B, const Eigen::VectorXd& rhs,
                  Eigen::VectorXd& lambda, Eigen::Vector4d& gamma) {
  const Index m = M.rows(), k = B.cols();
  const Eigen::HouseholderQR<MatrixXd> qr(B);
  const auto Q = qr.householderQ();
  M.applyOnTheLeft(Q.transpose());
  M.applyOnTheRight(Q);
  Eigen::VectorXd t = rhs;
  t.applyOnTheLeft(Q.transpose());
  Eigen::Ref<MatrixXd> M22 = M.bottomRightCorner(m - k, m - k);
  const Eigen::LLT<Eigen::Ref<MatrixXd>> llt(M22); // in place: M12 stays
  if (llt.info() != Eigen::Success)
    throw std::invalid_argument("hermite rbf: the interpolation system is not positive definite");
  const Eigen::VectorXd y = llt.solve(t.tail(m - k));
  gamma = qr.matrixQR().topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(
      t.head(k) - M.topRightCorner(k, m - k) * y);
  lambda = Eigen::VectorXd::Zero(m);
  lambda.tail(m - k) = y;
  lambda.applyOnTheLeft(Q);
}

// Fh at a normalised point xh: sum_j r_j (a_j r_j^2 - 3 b_j . d_j) + g . xh + c with
// d_j = xh - p_j, r_j = |d_j| (a phi - b . grad phi, grad phi(d) = 3 r d), over the contiguous
// columns of the column-major centre and b matrices.
double value_at(const HermiteRbf& m, const Vector3d& xh) {
  const double *px = m.points.col(0).data(), *py = m.points.col(1).data(),
               *pz = m.points.col(2).data(), *bx = m.b.col(0).data(), *by = m.b.col(1).data(),
               *bz = m.b.col(2).data(), *a = m.a.data();
  double f = 0;
  for (Index j = 0; j < m.points.rows(); ++j) {
    const double dx = xh(0) - px[j], dy = xh(1) - py[j], dz = xh(2) - pz[j];
    const double r2 = dx * dx + dy * dy + dz * dz;
    f += std::sqrt(r2) * (a[j] * r2 - 3 * (bx[j] * dx + by[j] * dy + bz[j] * dz));
  }
  return f + m.g.dot(xh) + m.c;
}

// Per-batch work arrays of value_gradient_at (one per centre).
struct Work {
  Eigen::ArrayXd dx, dy, dz, r, s;
};

// Fh and its gradient g + sum_j 3 (s_j d_j - r_j b_j), s_j = a_j r_j - b_j . d_j / r_j: the
// terms a grad phi - H(phi) b with H(phi)(d) = 3 (r I + d d^T / r) (0 at r = 0, where d = 0).
double value_gradient_at(const HermiteRbf& m, const Vector3d& xh, Work& w, Vector3d& grad) {
  w.dx = xh(0) - m.points.col(0).array();
  w.dy = xh(1) - m.points.col(1).array();
  w.dz = xh(2) - m.points.col(2).array();
  w.r = (w.dx.square() + w.dy.square() + w.dz.square()).sqrt();
  const auto bd = m.b.col(0).array() * w.dx + m.b.col(1).array() * w.dy + m.b.col(2).array() * w.dz;
  const double f = (w.r * (m.a.array() * w.r.square() - 3 * bd)).sum();
  w.s = m.a.array() * w.r - bd / w.r.max(1e-300);
  grad = 3 * Vector3d((w.s * w.dx - w.r * m.b.col(0).array()).sum(),
                      (w.s * w.dy - w.r * m.b.col(1).array()).sum(),
                      (w.s * w.dz - w.r * m.b.col(2).array()).sum()) +
         m.g;
  return f + m.g.dot(xh) + m.c;
}

} // namespace

HermiteRbf fit_hermite_rbf(const PointCloud& cloud, HermiteRbfInfo* info_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const Index n = cloud.points.rows();
  if (!cloud.has_normals())
    throw std::invalid_argument("hermite rbf: the cloud needs oriented normals");
  if (n < 4 || n > kHermiteRbfMaxPoints)
    throw std::invalid_argument("hermite rbf: needs 4 to " + std::to_string(kHermiteRbfMaxPoints) +
                                " points, not " + std::to_string(n));
  const Vector3d lo = cloud.points.colwise().minCoeff(), hi = cloud.points.colwise().maxCoeff();
  const double diag = (hi - lo).norm();
  const detail::NeighbourIndex index(cloud.points);
  const Eigen::MatrixXi knn =
      index.knn_all(int(std::min<Index>(detail::kAreaNeighbours, n - 1)), 1);
  for (Index i = 0; i < n; ++i)
    if ((cloud.points.row(i) - cloud.points.row(knn(i, 0))).norm() <= 1e-9 * diag)
      throw std::invalid_argument("hermite rbf: points " + std::to_string(i) + " and " +
                                  std::to_string(knn(i, 0)) + " coincide");
  const Eigen::VectorXd area = detail::point_areas(cloud.points, knn);
  HermiteRbfInfo info;
  info.flipped = detail::normals_inward(cloud.points, cloud.normals, area);

  HermiteRbf m;
  m.centre = 0.5 * (lo + hi);
  m.scale = 0.5 * diag; // the points within the unit ball: kernel values of order 1
  m.points = (cloud.points.rowwise() - m.centre.transpose()) / m.scale;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(4 * n); // F(p_i) = 0, grad F(p_i) = -n_i
  for (int c = 0; c < 3; ++c)
    rhs.segment(n + c * n, n) = (info.flipped ? 1.0 : -1.0) * cloud.normals.col(c);
  MatrixXd M = gram_matrix(m.points);
  Eigen::VectorXd lambda;
  Eigen::Vector4d gamma;
  solve_saddle(M, polynomial_block(m.points), rhs, lambda, gamma);
  m.a = lambda.head(n);
  m.b.resize(n, 3);
  for (int c = 0; c < 3; ++c)
    m.b.col(c) = lambda.segment(n + c * n, n);
  m.c = gamma(0);
  m.g = gamma.tail(3);
  constexpr double kBoxMargin = 0.05; // as fit_cloud_implicit's box
  m.box = Eigen::AlignedBox3d(lo.array() - kBoxMargin * diag, hi.array() + kBoxMargin * diag);
  m.spacing = info.spacing = detail::median_spacing(area);
  info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (info_out)
    *info_out = info;
  return m;
}

ImplicitFunction hermite_rbf_function(std::shared_ptr<const HermiteRbf> model) {
  ImplicitFunction f;
  f.box = model->box;
  f.sample_spacing = model->spacing;
  f.value = [model](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F) {
    for (Index i = 0; i < P.rows(); ++i)
      F(i) = model->scale * value_at(*model, (P.row(i).transpose() - model->centre) / model->scale);
  };
  f.gradient = [model](const Eigen::Ref<const Points3>& P, Eigen::Ref<Eigen::VectorXd> F,
                       Eigen::Ref<Points3> G) {
    Work w;
    for (Index i = 0; i < P.rows(); ++i) {
      Vector3d g;
      F(i) = model->scale *
             value_gradient_at(*model, (P.row(i).transpose() - model->centre) / model->scale, w, g);
      G.row(i) = g.transpose(); // d/dx (scale Fh((x - centre) / scale)) = grad Fh
    }
  };
  return f;
}

} // namespace interlin
