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
Foot newton_foot(const ParametricSurface& S, const Vector3d& p, double u, double v) {
  const Eigen::Vector4d& dom = S.domain;
  const auto clampu = [&](double x) {
    if (S.closed_u)
      return dom(0) + (x - dom(0)) -
             (dom(1) - dom(0)) * std::floor((x - dom(0)) / (dom(1) - dom(0)));
    return std::clamp(x, dom(0), dom(1));
  };
  const auto clampv = [&](double x) { return std::clamp(x, dom(2), dom(3)); };
  Vector3d x = S.point(u, v);
  double f = 0.5 * (x - p).squaredNorm();
  for (int it = 0; it < 50; ++it) {
    const SurfaceJet d = S.derivatives(u, v);
    const Vector3d r = x - p;
    const Vector2d g(d.Su.dot(r), d.Sv.dot(r));
    Eigen::Matrix2d H;
    H << d.Su.dot(d.Su) + d.Suu.dot(r), d.Su.dot(d.Sv) + d.Suv.dot(r),
        d.Su.dot(d.Sv) + d.Suv.dot(r), d.Sv.dot(d.Sv) + d.Svv.dot(r);
    Eigen::LDLT<Eigen::Matrix2d> ldlt(H);
    Vector2d step;
    if (ldlt.info() == Eigen::Success && ldlt.isPositive() && H.determinant() > 0)
      step = -ldlt.solve(g);
    else { // Gauss–Newton: the first-order part of H is positive semi-definite
      Eigen::Matrix2d J;
      J << d.Su.dot(d.Su), d.Su.dot(d.Sv), d.Su.dot(d.Sv), d.Sv.dot(d.Sv);
      step = -J.ldlt().solve(g);
    }
    if (!step.allFinite())
      break;
    double t = 1;
    bool moved = false;
    for (int ls = 0; ls < 30; ++ls, t *= 0.5) {
      const double un = clampu(u + t * step(0)), vn = clampv(v + t * step(1));
      const Vector3d xn = S.point(un, vn);
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

SurfaceProjection sized(Index n) {
  SurfaceProjection out;
  out.u.resize(n);
  out.v.resize(n);
  out.distance.resize(n);
  out.foot.resize(n, 3);
  return out;
}

void store(SurfaceProjection& out, Index i, const Foot& f) {
  out.u(i) = f.u;
  out.v(i) = f.v;
  out.distance(i) = f.dist;
  out.foot.row(i) = f.x.transpose();
}

} // namespace

ParametricSurface parametric(const PiecewiseSurface& S) {
  return {domain(S), S.closed_u, [&S](double u, double v) { return evaluate(S, u, v); },
          [&S](double u, double v) { return evaluate_jet(S, u, v); }};
}

SurfaceProjection project_to_surface(const PiecewiseSurface& S, const MatrixXd& P, int su, int sv,
                                     int starts) {
  return project_to_surface(parametric(S), P, su, sv, starts);
}

SurfaceProjection project_to_surface(const ParametricSurface& S, const MatrixXd& P, int su, int sv,
                                     int starts) {
  if (P.cols() != 3)
    throw std::invalid_argument("project_to_surface: points must be #P by 3");
  if (su < 2 || sv < 2)
    throw std::invalid_argument("project_to_surface: need at least a 2 x 2 start grid");
  if (starts < 1 || starts > su * sv)
    throw std::invalid_argument("project_to_surface: starts must be in [1, grid size]");
  const Eigen::Vector4d& dom = S.domain;
  const VectorXd gu = VectorXd::LinSpaced(su, dom(0), dom(1));
  const VectorXd gv = VectorXd::LinSpaced(sv, dom(2), dom(3));
  // Row-major for FLANN: grid point i + su * j.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> G(gu.size() * gv.size(), 3);
  for (Index j = 0; j < gv.size(); ++j)
    for (Index i = 0; i < gu.size(); ++i)
      G.row(i + gu.size() * j) = S.point(gu(i), gv(j)).transpose();
  flann::Matrix<double> data(G.data(), static_cast<size_t>(G.rows()), 3);
  flann::Index<flann::L2<double>> index(data, flann::KDTreeSingleIndexParams(12));
  index.buildIndex();
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> Q = P;
  flann::Matrix<double> query(Q.data(), static_cast<size_t>(Q.rows()), 3);
  std::vector<std::vector<size_t>> nn;
  std::vector<std::vector<double>> d2;
  index.knnSearch(query, nn, d2, starts, flann::SearchParams(flann::FLANN_CHECKS_UNLIMITED));
  SurfaceProjection out = sized(P.rows());
  for (Index i = 0; i < P.rows(); ++i) {
    Foot best{0, 0, INFINITY, Vector3d::Zero()};
    for (size_t c : nn[static_cast<size_t>(i)]) {
      const Index gi = static_cast<Index>(c) % su, gj = static_cast<Index>(c) / su;
      const Foot f = newton_foot(S, P.row(i).transpose(), gu(gi), gv(gj));
      if (f.dist < best.dist)
        best = f;
    }
    store(out, i, best);
  }
  return out;
}

SurfaceProjection project_from(const PiecewiseSurface& S, const MatrixXd& P, const VectorXd& u0,
                               const VectorXd& v0) {
  return project_from(parametric(S), P, u0, v0);
}

SurfaceProjection project_from(const ParametricSurface& S, const MatrixXd& P, const VectorXd& u0,
                               const VectorXd& v0) {
  if (P.cols() != 3 || u0.size() != P.rows() || v0.size() != P.rows())
    throw std::invalid_argument("project_from: points #P by 3 and #P start parameters expected");
  SurfaceProjection out = sized(P.rows());
  for (Index i = 0; i < P.rows(); ++i)
    store(out, i, newton_foot(S, P.row(i).transpose(), u0(i), v0(i)));
  return out;
}

} // namespace interlin
