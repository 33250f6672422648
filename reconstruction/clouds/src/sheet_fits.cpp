// One quadric sheet or two joined, fitted to oriented points (sheet_fits.h).
#include "sheet_fits.h"

#include "local_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace interlin::detail {

using Eigen::Vector3d;

namespace {

// Curvature coefficients are damped by this ridge (in coordinates scaled by the ball radius) so
// that points along one line (a single scan line through a cell) give a cylinder, not garbage.
constexpr double kRidge = 1e-3;

} // namespace

bool fit_sheet(const OrientedPoints& pts, const std::vector<int>& idx, const std::vector<double>& w,
               double scale, bool quadric, HeightSheet& s) {
  Vector3d m = Vector3d::Zero(), o = Vector3d::Zero();
  double sw = 0;
  for (size_t j = 0; j < idx.size(); ++j) {
    m += w[j] * pts.N.row(idx[j]).transpose();
    o += w[j] * pts.P.row(idx[j]).transpose();
    sw += w[j];
  }
  if (!(sw > 0) || !(m.norm() > 1e-9 * sw))
    return false;
  s.origin = o / sw;
  s.frame = tangent_frame(m.normalized());
  const int np = quadric && int(idx.size()) >= kQuadricPoints ? 6 : 3;
  Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> b = Eigen::Matrix<double, 6, 1>::Zero();
  for (size_t j = 0; j < idx.size(); ++j) {
    const Vector3d l = s.frame * (pts.P.row(idx[j]).transpose() - s.origin) / scale;
    Eigen::Matrix<double, 6, 1> phi;
    if (np == 6)
      phi << l(0) * l(0), l(0) * l(1), l(1) * l(1), l(0), l(1), 1;
    else
      phi << l(0), l(1), 1, 0, 0, 0;
    M += w[j] * phi * phi.transpose();
    b += w[j] * phi * l(2);
  }
  for (int k = 0; k < 6; ++k)
    M(k, k) += (k >= np ? 1.0 : (np == 6 && k < 3 ? kRidge : 1e-12)) * sw;
  const Eigen::Matrix<double, 6, 1> x = M.ldlt().solve(b);
  if (!x.allFinite())
    return false;
  s.c = np == 6 ? std::array<double, 6>{x(0) / scale, x(1) / scale, x(2) / scale,
                                        x(3),         x(4),         x(5) * scale}
                : std::array<double, 6>{0, 0, 0, x(0), x(1), x(2) * scale};
  return true;
}

void split_by_normal(const OrientedPoints& pts, const std::vector<int>& idx, const Vector3d& mean,
                     std::vector<size_t>& a, std::vector<size_t>& b) {
  auto n = [&](size_t j) -> Vector3d { return pts.N.row(idx[j]).transpose(); };
  size_t s0 = 0, s1 = 0;
  for (size_t j = 0; j < idx.size(); ++j)
    if (n(j).dot(mean) < n(s0).dot(mean))
      s0 = j;
  for (size_t j = 0; j < idx.size(); ++j)
    if (n(j).dot(n(s0)) < n(s1).dot(n(s0)))
      s1 = j;
  Vector3d ca = n(s0), cb = n(s1);
  for (int it = 0; it < 8; ++it) {
    a.clear();
    b.clear();
    Vector3d sa = Vector3d::Zero(), sb = Vector3d::Zero();
    for (size_t j = 0; j < idx.size(); ++j) {
      if (n(j).dot(ca) >= n(j).dot(cb)) {
        a.push_back(j);
        sa += n(j);
      } else {
        b.push_back(j);
        sb += n(j);
      }
    }
    if (a.empty() || b.empty() || sa.norm() == 0 || sb.norm() == 0)
      return;
    ca = sa.normalized();
    cb = sb.normalized();
  }
}

double join_distance(const LocalFit& f, const Vector3d& x, int* deciding) {
  const auto distance = [&](int k) {
    Vector3d g;
    const double q = sheet_value(f.sheet[k], x, &g);
    return q / std::max(g.norm(), 1e-300);
  };
  const double a = distance(0);
  if (deciding)
    *deciding = 0;
  if (f.sheets == 1)
    return a;
  const double b = distance(1);
  const bool first = f.conjunction ? a <= b : a >= b;
  if (deciding)
    *deciding = first ? 0 : 1;
  return first ? a : b;
}

void misfit(const LocalFit& f, const OrientedPoints& pts, const std::vector<int>& idx, double& rms,
            double& mx) {
  const bool thin_wall =
      f.sheets == 2 && f.sheet[0].frame.row(2).dot(f.sheet[1].frame.row(2)) < kThinWallCos;
  double s2 = 0;
  mx = 0;
  for (int i : idx) {
    Vector3d g;
    const double d = thin_wall ? std::abs(join_distance(f, pts.P.row(i).transpose()))
                               : std::abs(fit_value(f, pts.P.row(i).transpose(), &g)) /
                                     std::max(g.norm(), 1e-12);
    s2 += d * d;
    mx = std::max(mx, d);
  }
  rms = idx.empty() ? 0 : std::sqrt(s2 / double(idx.size()));
}
bool fit_two_sheets(const OrientedPoints& pts, const std::vector<int>& idx,
                    const std::vector<double>& w, double R, const std::vector<size_t>& a,
                    const std::vector<size_t>& b, LocalFit& f) {
  std::vector<int> ia, ib;
  std::vector<double> wa, wb;
  for (size_t j : a)
    ia.push_back(idx[j]), wa.push_back(w[j]);
  for (size_t j : b)
    ib.push_back(idx[j]), wb.push_back(w[j]);
  f.sheets = 2;
  if (!fit_sheet(pts, ia, wa, R, true, f.sheet[0]) || !fit_sheet(pts, ib, wb, R, true, f.sheet[1]))
    return false;
  double inside = 0;
  for (int i : ib)
    inside += sheet_value(f.sheet[0], pts.P.row(i).transpose(), nullptr) / double(ib.size());
  for (int i : ia)
    inside += sheet_value(f.sheet[1], pts.P.row(i).transpose(), nullptr) / double(ia.size());
  f.conjunction = inside >= 0;
  return true;
}

// Edge sheets (Ohtake et al. 2003: a cell across a sharp feature takes a Boolean of two
// fits): a cell that passes the one-sheet test may still hold an edge whose faces' normals are
// within 60 degrees of their mean (a 90-degree edge: 45 each), where one quadric rounds the edge
// by up to the acceptance's 1.5 sigma rms. When its normals split into two groups whose mean
// normals differ by kEdgeAngle or more, each with kEdgeShare of the weight and kQuadricPoints
// points, the join of the groups' sheets replaces the quadric if it misses the cell's points by
// at most kEdgeGain times the quadric's rms. Measured on 18 blade and valve scans, the clean
// models, sparse clouds and the smoothing families (docs/benchmarks.md, "Edge sheets"): at most
// 0.8 % worse, the noisy valve -7 %, the clean valve -11 %.

bool may_hold_edge(const Vector3d& m, double sw) {
  static const double resultant =
      std::sqrt(1 - 2 * kEdgeShare * (1 - kEdgeShare) * (1 - std::cos(kEdgeAngle * M_PI / 180)));
  return m.norm() < resultant * sw;
}

void fit_edge_sheets(const OrientedPoints& pts, const std::vector<int>& idx,
                     const std::vector<double>& w, double R, const Vector3d& mean, LocalFit& f) {
  std::vector<size_t> a, b;
  split_by_normal(pts, idx, mean, a, b);
  if (a.size() < size_t(kQuadricPoints) || b.size() < size_t(kQuadricPoints))
    return;
  Vector3d na = Vector3d::Zero(), nb = Vector3d::Zero();
  double wa = 0, wb = 0;
  for (size_t j : a)
    na += w[j] * pts.N.row(idx[j]).transpose(), wa += w[j];
  for (size_t j : b)
    nb += w[j] * pts.N.row(idx[j]).transpose(), wb += w[j];
  if (std::min(wa, wb) < kEdgeShare * (wa + wb) ||
      na.normalized().dot(nb.normalized()) > std::cos(kEdgeAngle * M_PI / 180))
    return;
  LocalFit g = f;
  if (!fit_two_sheets(pts, idx, w, R, a, b, g))
    return;
  double rms1 = 0, rms2 = 0, mx = 0;
  misfit(f, pts, idx, rms1, mx);
  misfit(g, pts, idx, rms2, mx);
  if (rms2 <= kEdgeGain * rms1)
    f = g;
}

} // namespace interlin::detail
