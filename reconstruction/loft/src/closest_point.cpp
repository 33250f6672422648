#include "interlin/reconstruction/loft/closest_point.h"

#include <flann/flann.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

struct Foot {
  double u, v, dist;
  Vector3d x;
};

// Newton's method for min_{u,v} |S(u,v) - p|^2 / 2 with backtracking; v is kept in its domain
// (projected), u wraps for closed surfaces and is kept in its domain otherwise.
Foot newton_foot(const PiecewiseSurface& S, const Eigen::Vector4d& dom, const Vector3d& p, double u,
                 double v) {
  const auto clampu = [&](double x) {
    if (S.closed_u)
      return dom(0) + (x - dom(0)) -
             (dom(1) - dom(0)) * std::floor((x - dom(0)) / (dom(1) - dom(0)));
    return std::clamp(x, dom(0), dom(1));
  };
  const auto clampv = [&](double x) { return std::clamp(x, dom(2), dom(3)); };
  Vector3d x = evaluate(S, u, v);
  double f = 0.5 * (x - p).squaredNorm();
  for (int it = 0; it < 50; ++it) {
    const Vector3d r = x - p;
    const Vector3d Su = evaluate(S, u, v, 1, 0), Sv = evaluate(S, u, v, 0, 1);
    const Vector3d Suu = evaluate(S, u, v, 2, 0), Suv = evaluate(S, u, v, 1, 1),
                   Svv = evaluate(S, u, v, 0, 2);
    const Vector2d g(Su.dot(r), Sv.dot(r));
    Eigen::Matrix2d H;
    H << Su.dot(Su) + Suu.dot(r), Su.dot(Sv) + Suv.dot(r), Su.dot(Sv) + Suv.dot(r),
        Sv.dot(Sv) + Svv.dot(r);
    Eigen::LDLT<Eigen::Matrix2d> ldlt(H);
    Vector2d step;
    if (ldlt.info() == Eigen::Success && ldlt.isPositive() && H.determinant() > 0)
      step = -ldlt.solve(g);
    else { // Gauss–Newton: the first-order part of H is positive semi-definite
      Eigen::Matrix2d J;
      J << Su.dot(Su), Su.dot(Sv), Su.dot(Sv), Sv.dot(Sv);
      step = -J.ldlt().solve(g);
    }
    if (!step.allFinite())
      break;
    double t = 1;
    bool moved = false;
    for (int ls = 0; ls < 30; ++ls, t *= 0.5) {
      const double un = clampu(u + t * step(0)), vn = clampv(v + t * step(1));
      const Vector3d xn = evaluate(S, un, vn);
      const double fn = 0.5 * (xn - p).squaredNorm();
      // Near the minimum f changes below its own round-off: accept such steps, stop once the
      // step itself is at round-off level.
      if (fn <= f + 1e-13 * f + 1e-300) {
        const double du = std::abs(un - u), dv = std::abs(vn - v);
        u = un, v = vn, x = xn, f = fn;
        moved = du + dv > 1e-15 * (1 + std::abs(u) + std::abs(v));
        break;
      }
    }
    if (!moved)
      break;
  }
  return {u, v, std::sqrt(2 * f), x};
}

} // namespace

SurfaceProjection project_to_surface(const PiecewiseSurface& S, const MatrixXd& P, int su, int sv) {
  if (P.cols() != 3)
    throw std::invalid_argument("project_to_surface: points must be #P by 3");
  if (su < 2 || sv < 2)
    throw std::invalid_argument("project_to_surface: need at least a 2 x 2 start grid");
  const Eigen::Vector4d dom = domain(S);
  const VectorXd gu = VectorXd::LinSpaced(su, dom(0), dom(1));
  const VectorXd gv = VectorXd::LinSpaced(sv, dom(2), dom(3));
  // Row-major copy for FLANN: grid point i + su * j.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> G = evaluate_grid(S, gu, gv);
  flann::Matrix<double> data(G.data(), static_cast<size_t>(G.rows()), 3);
  flann::Index<flann::L2<double>> index(data, flann::KDTreeSingleIndexParams(12));
  index.buildIndex();
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Q = P;
  flann::Matrix<double> query(Q.data(), static_cast<size_t>(Q.rows()), 3);
  const int k = 4; // a few starts guard against the wrong sheet of a thin body (blade sides)
  std::vector<std::vector<size_t>> nn;
  std::vector<std::vector<double>> d2;
  index.knnSearch(query, nn, d2, k, flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
  SurfaceProjection out;
  out.u.resize(P.rows());
  out.v.resize(P.rows());
  out.distance.resize(P.rows());
  out.foot.resize(P.rows(), 3);
  for (Index i = 0; i < P.rows(); ++i) {
    Foot best{0, 0, INFINITY, Vector3d::Zero()};
    for (size_t c : nn[static_cast<size_t>(i)]) {
      const Index gi = static_cast<Index>(c) % su, gj = static_cast<Index>(c) / su;
      const Foot f = newton_foot(S, dom, P.row(i).transpose(), gu(gi), gv(gj));
      if (f.dist < best.dist)
        best = f;
    }
    out.u(i) = best.u;
    out.v(i) = best.v;
    out.distance(i) = best.dist;
    out.foot.row(i) = best.x.transpose();
  }
  return out;
}

} // namespace interlin
