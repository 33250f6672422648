// Convexity / concavity maps along the parameter directions (seed 001 §2.5, Theorem 3).
#include "interlin/interlineation/shape_diagnostics.h"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXi;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

int sign_of(double k, double tol) {
  return k > tol ? 1 : (k < -tol ? -1 : 0);
}

} // namespace

ShapeMap shape_map(const PiecewiseSurface& S, const VectorXd& u, const VectorXd& v, double tol) {
  const Index nu = u.size(), nv = v.size();
  Eigen::MatrixXd ku(nu, nv), kv(nu, nv);
  Vector3d lo = Vector3d::Constant(INFINITY), hi = -lo;
  double outward = 0;
  for (Index j = 0; j < nv; ++j) {
    Eigen::MatrixXd P(nu, 3), N(nu, 3);
    for (Index i = 0; i < nu; ++i) {
      const Vector3d Su = evaluate(S, u(i), v(j), 1, 0), Sv = evaluate(S, u(i), v(j), 0, 1);
      const Vector3d n = Su.cross(Sv);
      if (!(n.norm() > 0) || !std::isfinite(n.norm()))
        throw std::invalid_argument("shape_map: degenerate surface point (S_u x S_v = 0) at (" +
                                    std::to_string(u(i)) + ", " + std::to_string(v(j)) + ")");
      const Vector3d nn = n.normalized();
      ku(i, j) = evaluate(S, u(i), v(j), 2, 0).dot(nn) / Su.squaredNorm();
      kv(i, j) = evaluate(S, u(i), v(j), 0, 2).dot(nn) / Sv.squaredNorm();
      P.row(i) = evaluate(S, u(i), v(j)).transpose();
      N.row(i) = nn.transpose();
      lo = lo.cwiseMin(P.row(i).transpose());
      hi = hi.cwiseMax(P.row(i).transpose());
    }
    const Eigen::RowVector3d c = P.colwise().mean();
    for (Index i = 0; i < nu; ++i)
      outward += (P.row(i) - c).dot(N.row(i));
  }
  // Convex = bending away from the (outward) normal: kappa < 0.
  const double flip = (S.closed_u && outward < 0) ? 1.0 : -1.0;
  const double D = (hi - lo).norm();
  ShapeMap m{u, v, MatrixXi(nu, nv), MatrixXi(nu, nv)};
  for (Index j = 0; j < nv; ++j)
    for (Index i = 0; i < nu; ++i) {
      m.along_u(i, j) = sign_of(flip * ku(i, j) * D, tol);
      m.along_v(i, j) = sign_of(flip * kv(i, j) * D, tol);
    }
  return m;
}

ShapeMap shape_map(const GordonSurface& O, const VectorXd& x, const VectorXd& y, double tol) {
  if (O.dim != 1)
    throw std::invalid_argument("shape_map: the operator must be scalar (dim 1)");
  ShapeMap m{x, y, MatrixXi(x.size(), y.size()), MatrixXi(x.size(), y.size())};
  for (Index j = 0; j < y.size(); ++j)
    for (Index i = 0; i < x.size(); ++i) {
      m.along_u(i, j) = sign_of(evaluate(O, x(i), y(j), 2, 0)(0), tol);
      m.along_v(i, j) = sign_of(evaluate(O, x(i), y(j), 0, 2)(0), tol);
    }
  return m;
}

std::vector<SignRun> sign_runs(const VectorXd& s, const Eigen::VectorXi& signs) {
  if (s.size() != signs.size())
    throw std::invalid_argument("sign_runs: one sign per sample");
  std::vector<SignRun> runs;
  for (Index i = 0; i < s.size(); ++i) {
    if (!runs.empty() && runs.back().sign == signs(i))
      continue;
    const double at = i == 0 ? s(0) : 0.5 * (s(i - 1) + s(i));
    if (!runs.empty())
      runs.back().end = at;
    runs.push_back({at, s(s.size() - 1), signs(i)});
  }
  return runs;
}

ShapeSummary summarize(const ShapeMap& m) {
  const auto frac = [](const MatrixXi& a, int sign) {
    return a.size()
               ? static_cast<double>((a.array() == sign).count()) / static_cast<double>(a.size())
               : 0.0;
  };
  return {frac(m.along_u, 1), frac(m.along_u, -1), frac(m.along_u, 0),
          frac(m.along_v, 1), frac(m.along_v, -1), frac(m.along_v, 0)};
}

} // namespace interlin
