// Signed distance to a closed polyline (seed 003 (3)-(6)), with bounding boxes per run of
// segments so that one evaluation touches few segments.
#include "interlin/interflatation/rfunctions/curve_distance.h"

#include "node.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace interlin::rf {

namespace detail {

namespace {

constexpr std::size_t kRun = 16; // segments per bounding box

} // namespace

double Polyline::signed_distance(double u, double v, double* du, double* dv) const {
  const std::size_t n = points.size();
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2d nearest(0, 0);
  std::size_t nearest_seg = 0;
  int crossings = 0;
  const Eigen::Vector2d p(u, v);
  for (std::size_t r = 0; r * kRun < n; ++r) {
    const std::size_t s0 = r * kRun, s1 = std::min(n, s0 + kRun);
    // bounding box of the run's segments
    double x0 = points[s0].x(), x1 = x0, y0 = points[s0].y(), y1 = y0;
    for (std::size_t s = s0; s < s1; ++s) {
      const Eigen::Vector2d& q = points[(s + 1) % n];
      x0 = std::min(x0, q.x()), x1 = std::max(x1, q.x());
      y0 = std::min(y0, q.y()), y1 = std::max(y1, q.y());
    }
    const double gx = std::max({x0 - u, 0.0, u - x1}), gy = std::max({y0 - v, 0.0, v - y1});
    const bool may_cross = y0 < v && v <= y1 && x1 > u;
    if (gx * gx + gy * gy >= best && !may_cross)
      continue;
    for (std::size_t s = s0; s < s1; ++s) {
      const Eigen::Vector2d& a = points[s];
      const Eigen::Vector2d& b = points[(s + 1) % n];
      // seed 003 (6): nearest point of the segment
      const Eigen::Vector2d e = b - a;
      const double t = std::clamp((p - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
      const Eigen::Vector2d q = a + t * e;
      const double d2 = (p - q).squaredNorm();
      if (d2 < best) {
        best = d2;
        nearest = q;
        nearest_seg = s;
      }
      // ray parity along +u, half-open in v
      if ((a.y() < v && v <= b.y()) || (b.y() < v && v <= a.y())) {
        const double xc = a.x() + (v - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
        if (xc > u)
          ++crossings;
      }
    }
  }
  const double sgn = (crossings % 2) ? 1.0 : -1.0;
  const double d = std::sqrt(best);
  if (du && dv) {
    if (d > 0) {
      *du = sgn * (u - nearest.x()) / d;
      *dv = sgn * (v - nearest.y()) / d;
    } else { // on the curve: the inward normal of the segment
      const Eigen::Vector2d e = points[(nearest_seg + 1) % n] - points[nearest_seg];
      const double o = orientation >= 0 ? 1.0 : -1.0; // interior on the left of CCW segments
      *du = -o * e.y() / e.norm();
      *dv = o * e.x() / e.norm();
    }
  }
  return sgn * d;
}

} // namespace detail

Expr polygon_region(const Expr& u, const Expr& v, const std::vector<Eigen::Vector2d>& vertices) {
  auto line = std::make_shared<detail::Polyline>();
  for (const Eigen::Vector2d& q : vertices) {
    if (!std::isfinite(q.x()) || !std::isfinite(q.y()))
      throw std::invalid_argument("polygon_region: vertex coordinates must be finite");
    if (line->points.empty() || q != line->points.back())
      line->points.push_back(q);
  }
  while (line->points.size() > 1 && line->points.front() == line->points.back())
    line->points.pop_back();
  if (line->points.size() < 3)
    throw std::invalid_argument("polygon_region: need at least 3 distinct vertices, got " +
                                std::to_string(line->points.size()));
  double area2 = 0; // twice the signed area (shoelace)
  const std::size_t n = line->points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = line->points[i];
    const Eigen::Vector2d& b = line->points[(i + 1) % n];
    area2 += a.x() * b.y() - b.x() * a.y();
  }
  line->orientation = area2;
  return Expr(detail::make(detail::Op::curve, u.node(), v.node(), 0, std::move(line)));
}

std::vector<Eigen::Vector2d>
sample_bezier_chain(const std::vector<std::vector<Eigen::Vector2d>>& branches, int segments) {
  if (segments < 1)
    throw std::invalid_argument("sample_bezier_chain: segments must be >= 1, got " +
                                std::to_string(segments));
  std::vector<Eigen::Vector2d> out;
  for (const auto& ctrl : branches) {
    if (ctrl.size() < 2)
      throw std::invalid_argument("sample_bezier_chain: a Bezier branch needs at least 2 control "
                                  "points, got " +
                                  std::to_string(ctrl.size()));
    for (int i = 0; i <= segments; ++i) {
      const double t = static_cast<double>(i) / segments;
      std::vector<Eigen::Vector2d> w(ctrl); // de Casteljau
      for (std::size_t r = 1; r < w.size(); ++r)
        for (std::size_t j = 0; j + r < w.size(); ++j)
          w[j] = (1 - t) * w[j] + t * w[j + 1];
      if (out.empty() || w[0] != out.back())
        out.push_back(w[0]);
    }
  }
  return out;
}

} // namespace interlin::rf
