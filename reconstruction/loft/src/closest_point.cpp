#include "interlin/reconstruction/loft/closest_point.h"

#include "interlin/splines/surface_foot.h"

#include <flann/flann.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

// The local Newton search shared with the implicit body equations (splines/surface_foot.h).
SurfaceFoot newton_foot(const ParametricSurface& S, const Vector3d& p, double u, double v) {
  return surface_foot(S.derivatives, S.domain, S.closed_u, p, u, v, 50);
}

SurfaceProjection sized(Index n) {
  SurfaceProjection out;
  out.u.resize(n);
  out.v.resize(n);
  out.distance.resize(n);
  out.foot.resize(n, 3);
  return out;
}

void store(SurfaceProjection& out, Index i, const SurfaceFoot& f) {
  out.u(i) = f.u;
  out.v(i) = f.v;
  out.distance(i) = f.distance;
  out.foot.row(i) = f.jet.S.transpose();
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
    SurfaceFoot best;
    best.distance = INFINITY;
    for (size_t c : nn[static_cast<size_t>(i)]) {
      const Index gi = static_cast<Index>(c) % su, gj = static_cast<Index>(c) / su;
      const SurfaceFoot f = newton_foot(S, P.row(i).transpose(), gu(gi), gv(gj));
      if (f.distance < best.distance)
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
