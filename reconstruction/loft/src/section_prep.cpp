#include "interlin/reconstruction/loft/section_prep.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;

Vector3d vector_area(const MatrixXd& P) {
  Vector3d a = Vector3d::Zero();
  for (Index i = 0, n = P.rows(); i < n; ++i)
    a += Vector3d(P.row(i)).cross(Vector3d(P.row((i + 1) % n)));
  return 0.5 * a;
}

namespace {

// Index reached by walking from e along the polygon in `step` direction (+1/-1) until the
// travelled arc length reaches `dist` (at most a quarter of the points).
Index arc_walk(const MatrixXd& P, Index e, double dist, int step) {
  const Index n = P.rows();
  Index i = e;
  double s = 0;
  for (Index k = 0; k < std::max<Index>(1, n / 4) && s < dist; ++k) {
    const Index j = (i + step + n) % n;
    s += (P.row(j) - P.row(i)).norm();
    i = j;
  }
  return i;
}

// Moves an edge candidate to the nose tip: the point farthest along the direction from the
// midpoint of the two flanks (8 % of the chord away along the profile) through the edge.
Index nose_tip(const MatrixXd& P, Index e, double chord) {
  const Index n = P.rows();
  for (int it = 0; it < 8; ++it) {
    const Vector3d mid =
        0.5 * (P.row(arc_walk(P, e, 0.08 * chord, 1)) + P.row(arc_walk(P, e, 0.08 * chord, -1)))
                  .transpose();
    const Vector3d d = (P.row(e).transpose() - mid).normalized();
    Index best = e;
    double best_h = (P.row(e).transpose() - mid).dot(d);
    for (int step : {1, -1}) {
      const Index end = arc_walk(P, e, 0.04 * chord, step);
      for (Index i = e; i != end;) {
        i = (i + step + n) % n;
        const double h = (P.row(i).transpose() - mid).dot(d);
        if (h > best_h) {
          best_h = h;
          best = i;
        }
      }
    }
    if (best == e)
      break;
    e = best;
  }
  return e;
}

// Reorders the rows of a section: new row i is old row order[i].
void reorder(PreparedSection& s, const std::vector<Index>& order) {
  MatrixXd Q(s.points.rows(), 3);
  std::vector<long> L(order.size());
  std::vector<Index> S(order.size());
  for (size_t i = 0; i < order.size(); ++i) {
    Q.row(static_cast<Index>(i)) = s.points.row(order[i]);
    L[i] = s.lines[static_cast<size_t>(order[i])];
    S[i] = s.source[static_cast<size_t>(order[i])];
  }
  s.points = std::move(Q);
  s.lines = std::move(L);
  s.source = std::move(S);
}

} // namespace

std::pair<Index, Index> profile_edges(const MatrixXd& P) {
  const Index n = P.rows();
  Index a = 0, b = 1;
  double best = -1;
  for (Index i = 0; i < n; ++i)
    for (Index j = i + 1; j < n; ++j) {
      const double d = (P.row(i) - P.row(j)).squaredNorm();
      if (d > best) {
        best = d;
        a = i;
        b = j;
      }
    }
  const double chord = std::sqrt(best);
  return {nose_tip(P, a, chord), nose_tip(P, b, chord)};
}

double max_thickness_position(const MatrixXd& P, Index a, Index b) {
  const Index n = P.rows();
  const Vector3d normal = vector_area(P).normalized();
  Vector3d x = (P.row(b) - P.row(a)).transpose();
  x -= x.dot(normal) * normal;
  const double chord = x.norm();
  x /= chord;
  const Vector3d y = normal.cross(x);
  // Each side as a polyline in chord coordinates (xi in [0,1], eta).
  const auto side = [&](Index from, Index to) {
    std::vector<Eigen::Vector2d> s;
    for (Index i = from;; i = (i + 1) % n) {
      const Vector3d d = (P.row(i) - P.row(a)).transpose();
      s.emplace_back(d.dot(x) / chord, d.dot(y));
      if (i == to)
        break;
    }
    return s;
  };
  const auto eta_at = [](const std::vector<Eigen::Vector2d>& s, double xi) {
    for (size_t i = 1; i < s.size(); ++i) {
      const double x0 = s[i - 1].x(), x1 = s[i].x();
      if ((x0 - xi) * (x1 - xi) <= 0 && x0 != x1)
        return s[i - 1].y() + (s[i].y() - s[i - 1].y()) * (xi - x0) / (x1 - x0);
    }
    return std::nan("");
  };
  const auto s1 = side(a, b), s2 = side(b, a);
  double best_xi = 0.5, best_t = -1;
  for (int k = 1; k < 100; ++k) {
    const double xi = k / 100.0, t = std::abs(eta_at(s1, xi) - eta_at(s2, xi));
    if (t > best_t) { // NaN compares false: stations not spanned by both sides are skipped
      best_t = t;
      best_xi = xi;
    }
  }
  return best_xi;
}

std::vector<PreparedSection> prepare_sections(const std::vector<Section>& sections,
                                              StartAlign align, std::vector<std::string>& notes) {
  std::vector<PreparedSection> out;
  for (size_t k = 0; k < sections.size(); ++k) {
    PreparedSection s;
    s.id = sections[k].id;
    s.points = sections[k].points;
    s.lines = sections[k].lines;
    const Index n = s.points.rows();
    s.source.resize(static_cast<size_t>(n));
    for (Index i = 0; i < n; ++i)
      s.source[static_cast<size_t>(i)] = i;
    // Same winding as the previous section (gradual twist keeps neighbours comparable); the
    // start point stays.
    if (k > 0 && vector_area(s.points).dot(vector_area(out.back().points)) < 0) {
      std::vector<Index> order(static_cast<size_t>(n));
      for (Index i = 0; i < n; ++i)
        order[static_cast<size_t>(i)] = (n - i) % n;
      reorder(s, order);
      s.reversed = true;
      notes.push_back("section " + s.id + ": reversed to match the winding of section " +
                      out.back().id);
    }
    out.push_back(std::move(s));
  }
  if (align == StartAlign::first)
    return out;
  // Edges, matched to the previous section's edges by proximity.
  std::vector<std::pair<Index, Index>> edges;
  double vote = 0; // > 0: the first edge of each pair is nearer the maximum thickness
  for (size_t k = 0; k < out.size(); ++k) {
    auto [a, b] = profile_edges(out[k].points);
    if (k > 0) {
      const MatrixXd &P = out[k].points, &Q = out[k - 1].points;
      const auto [pa, pb] = edges.back();
      if ((P.row(a) - Q.row(pa)).norm() + (P.row(b) - Q.row(pb)).norm() >
          (P.row(a) - Q.row(pb)).norm() + (P.row(b) - Q.row(pa)).norm())
        std::swap(a, b);
    }
    edges.emplace_back(a, b);
    vote += 0.5 - max_thickness_position(out[k].points, a, b);
  }
  for (size_t k = 0; k < out.size(); ++k) {
    PreparedSection& s = out[k];
    const auto [a, b] = edges[k];
    const Index le = vote >= 0 ? a : b, te = vote >= 0 ? b : a;
    const Index start = align == StartAlign::leading_edge ? le : te;
    const Index n = s.points.rows();
    std::vector<Index> order(static_cast<size_t>(n));
    for (Index i = 0; i < n; ++i)
      order[static_cast<size_t>(i)] = (start + i) % n;
    reorder(s, order);
    s.le = (le - start + n) % n;
    s.te = (te - start + n) % n;
  }
  return out;
}

} // namespace interlin
