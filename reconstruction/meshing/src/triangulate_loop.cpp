// Triangulation of one closed loop (a cap of a lofted solid): ear clipping in the best-fit plane,
// then Lawson flips to the constrained Delaunay triangulation of the projected polygon.
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include "min_angle.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace interlin {

namespace {

// Smallest corner angle of the 2D triangle (a, b, c) of Q.
double min_angle_2d(const Eigen::MatrixX2d& Q, int a, int b, int c) {
  const auto lift = [&](int i) { return Eigen::Vector3d(Q(i, 0), Q(i, 1), 0.0); };
  return detail::min_angle(lift(a), lift(b), lift(c));
}

// Lawson's edge flips (Lawson 1977; de Berg et al., "Computational Geometry", ch. 9): while an
// interior edge's two triangles form a strictly convex quadrilateral whose other diagonal gives
// a larger smallest angle, flip it. Each flip raises the sorted angle vector lexicographically,
// so the loop ends, at the constrained Delaunay triangulation of the polygon: among all
// triangulations on the loop's vertices, the one with the largest smallest angle (in the plane
// of Q). Greedy ear clipping alone leaves slivers where a very short loop edge (a blade's
// trailing-edge arc) is joined to a vertex far across. `side(a, b, q)` is the orientation test
// with the caller's round-off threshold; T's triangles run counter-clockwise in Q. Edges to
// check sit on a stack and each flip pushes its four outer edges, so a flip costs O(1).
template <class Side>
void delaunay_flips(const Eigen::MatrixX2d& Q, const Side& side, Eigen::MatrixXi& T) {
  // Relative margin: a flip must gain more than round-off, so near-cocircular quadrilaterals
  // (points on an edge circle) do not flip back and forth.
  constexpr double kGain = 1e-12;
  const int m = int(T.rows());
  // Half-edge k of triangle t runs T(t, k) -> T(t, k + 1); across[3 t + k] is the twin half-edge
  // 3 t' + k' of the neighbour, -1 on the loop.
  std::vector<int> across(static_cast<size_t>(3 * m), -1);
  {
    std::vector<std::array<int, 3>> half; // (min vertex, max vertex, half-edge)
    for (int t = 0; t < m; ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = T(t, k), b = T(t, (k + 1) % 3);
        half.push_back({std::min(a, b), std::max(a, b), 3 * t + k});
      }
    std::sort(half.begin(), half.end());
    for (size_t i = 0; i + 1 < half.size(); ++i)
      if (half[i][0] == half[i + 1][0] && half[i][1] == half[i + 1][1]) {
        across[static_cast<size_t>(half[i][2])] = half[i + 1][2];
        across[static_cast<size_t>(half[i + 1][2])] = half[i][2];
      }
  }
  const auto vertex = [&](int h, int offset) { return T(h / 3, (h % 3 + offset) % 3); };
  const auto link = [&](int h, int g) {
    across[static_cast<size_t>(h)] = g;
    if (g >= 0)
      across[static_cast<size_t>(g)] = h;
  };
  std::vector<int> stack;
  for (int h = 0; h < 3 * m; ++h)
    if (across[static_cast<size_t>(h)] > h)
      stack.push_back(h);
  while (!stack.empty()) {
    const int h1 = stack.back();
    stack.pop_back();
    const int h2 = across[static_cast<size_t>(h1)];
    if (h2 < 0)
      continue;
    const int a = vertex(h1, 0), b = vertex(h1, 1), c = vertex(h1, 2), d = vertex(h2, 2);
    // (a, b, c) and (b, a, d) counter-clockwise; (a, d, c) and (d, b, c) too: strictly convex.
    if (c == d || side(a, b, c) <= 0 || side(b, a, d) <= 0 || side(a, d, c) <= 0 ||
        side(d, b, c) <= 0)
      continue;
    const double before = std::min(min_angle_2d(Q, a, b, c), min_angle_2d(Q, b, a, d));
    const double after = std::min(min_angle_2d(Q, a, d, c), min_angle_2d(Q, d, b, c));
    if (after <= before * (1 + kGain))
      continue;
    const int t1 = h1 / 3, t2 = h2 / 3, k1 = h1 % 3, k2 = h2 % 3;
    const int bc = across[static_cast<size_t>(3 * t1 + (k1 + 1) % 3)],
              ca = across[static_cast<size_t>(3 * t1 + (k1 + 2) % 3)],
              ad = across[static_cast<size_t>(3 * t2 + (k2 + 1) % 3)],
              db = across[static_cast<size_t>(3 * t2 + (k2 + 2) % 3)];
    T.row(t1) << a, d, c; // half-edges a->d, d->c, c->a
    T.row(t2) << d, b, c; // half-edges d->b, b->c, c->d
    link(3 * t1, ad);
    link(3 * t1 + 1, 3 * t2 + 2);
    link(3 * t1 + 2, ca);
    link(3 * t2, db);
    link(3 * t2 + 1, bc);
    for (int h : {3 * t1, 3 * t1 + 2, 3 * t2, 3 * t2 + 1})
      stack.push_back(h);
  }
}

// The loop in its best-fit plane: the Newell normal (the loop's vector area) through the
// centroid; with the basis (e1, e2, normal) right-handed the loop runs counter-clockwise.
Eigen::MatrixX2d best_fit_plane_coordinates(const Eigen::MatrixXd& P) {
  const int n = int(P.rows());
  Eigen::Vector3d N = Eigen::Vector3d::Zero();
  const Eigen::RowVector3d c = P.colwise().mean();
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a = P.row(i) - c, b = P.row((i + 1) % n) - c;
    N += a.cross(b);
  }
  if (!(N.norm() > 0) || !std::isfinite(N.norm()))
    N = Eigen::Vector3d::UnitZ(); // no area: any projection; the fallback keeps the topology
  N.normalize();
  const Eigen::Vector3d e1 = N.unitOrthogonal(), e2 = N.cross(e1);
  Eigen::MatrixX2d Q(n, 2);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d d = P.row(i) - c;
    Q(i, 0) = d.dot(e1);
    Q(i, 1) = d.dot(e2);
  }
  return Q;
}

// Ear clipping of the counter-clockwise polygon Q, best ear first (largest smallest angle of
// the triangle in 3D, P); when no ear is left (round-off on nearly collinear runs) the most
// convex vertex is clipped, which keeps a topological disk. Returns the n - 2 triangles.
template <class Orient, class Side>
Eigen::MatrixXi clip_ears(const Eigen::MatrixXd& P, const Eigen::MatrixX2d& Q, const Orient& orient,
                          const Side& side) {
  const int n = int(P.rows());
  Eigen::MatrixXi T(n - 2, 3);
  auto same = [&](int a, int b) { return Q(a, 0) == Q(b, 0) && Q(a, 1) == Q(b, 1); };
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  // is_ear(i): strictly convex, and no other remaining vertex inside or on the triangle
  // (vertices at the same position as a corner do not block).
  auto is_ear = [&](int i) {
    const int a = prev[i], b = next[i];
    if (side(a, i, b) <= 0)
      return false;
    for (int q = next[b]; q != a; q = next[q]) {
      if (same(q, a) || same(q, i) || same(q, b))
        continue;
      if (side(a, i, q) >= 0 && side(i, b, q) >= 0 && side(b, a, q) >= 0)
        return false;
    }
    return true;
  };
  std::vector<char> ear(n);
  std::vector<double> quality(n);
  auto update = [&](int i) {
    ear[i] = is_ear(i);
    quality[i] = ear[i] ? detail::min_angle(P.row(prev[i]).transpose(), P.row(i).transpose(),
                                            P.row(next[i]).transpose())
                        : 0.0;
  };
  for (int i = 0; i < n; ++i)
    update(i);
  int remaining = n, first = 0, t = 0;
  while (remaining > 3) {
    auto best_ear = [&]() {
      int best = -1, i = first;
      for (int k = 0; k < remaining; ++k, i = next[i])
        if (ear[i] && (best < 0 || quality[i] > quality[best]))
          best = i;
      return best;
    };
    int best = best_ear();
    if (best < 0) { // cached flags may be stale (a clipped vertex blocked an ear): recompute
      int i = first;
      for (int k = 0; k < remaining; ++k, i = next[i])
        update(i);
      best = best_ear();
    }
    if (best < 0) { // no valid ear: clip the most convex vertex (keeps a topological disk)
      int i = first;
      double most = -std::numeric_limits<double>::infinity();
      for (int k = 0; k < remaining; ++k, i = next[i]) {
        const double o = orient(prev[i], i, next[i]);
        if (o > most) {
          most = o;
          best = i;
        }
      }
    }
    const int a = prev[best], b = next[best];
    T.row(t++) << a, best, b;
    next[a] = b;
    prev[b] = a;
    if (first == best)
      first = b;
    --remaining;
    update(a);
    update(b);
  }
  T.row(t) << prev[first], first, next[first];
  return T;
}

} // namespace

Eigen::MatrixXi triangulate_loop(const Eigen::MatrixXd& P) {
  if (P.rows() < 3 || P.cols() != 3)
    throw std::invalid_argument("triangulate_loop: need at least 3 points in 3D, got " +
                                std::to_string(P.rows()) + " by " + std::to_string(P.cols()));
  const Eigen::MatrixX2d Q = best_fit_plane_coordinates(P);
  auto orient = [&](int a, int b, int q) {
    return (Q(b, 0) - Q(a, 0)) * (Q(q, 1) - Q(a, 1)) - (Q(b, 1) - Q(a, 1)) * (Q(q, 0) - Q(a, 0));
  };
  // side(a, b, q): +1 / -1 when q is left / right of the line a -> b, 0 when within round-off.
  // Points collinear in 3D stay collinear after projection only up to a few ulps of the
  // coordinates, i.e. about eps R |ab| in orient (R the loop's size), so the threshold scales
  // with the local edge lengths and tiny leading-edge ears stay valid. Collinear blocks a
  // diagonal and is not convex.
  const double R = Q.cwiseAbs().maxCoeff();
  auto side = [&](int a, int b, int q) {
    const double o = orient(a, b, q);
    const double noise = 1e-13 * R * ((Q.row(b) - Q.row(a)).norm() + (Q.row(q) - Q.row(a)).norm());
    return o > noise ? 1 : o < -noise ? -1 : 0;
  };
  Eigen::MatrixXi T = clip_ears(P, Q, orient, side);
  delaunay_flips(Q, side, T);
  return T;
}

} // namespace interlin
