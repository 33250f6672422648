#include "interlin/reconstruction/meshing/ray_cast.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace interlin {

using Eigen::Index;
using Eigen::Vector3d;

namespace {

// A triangle as Moller-Trumbore wants it (corner a, edges e1 = b - a, e2 = c - a) and its
// bounding box, computed once per mesh rather than once per ray.
struct Triangle {
  Vector3d a, e1, e2;
  double lo[3], hi[3];
};

std::vector<Triangle> triangles(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  std::vector<Triangle> T(static_cast<size_t>(F.rows()));
  for (Index f = 0; f < F.rows(); ++f) {
    Triangle& t = T[static_cast<size_t>(f)];
    t.a = V.row(F(f, 0)).transpose();
    t.e1 = V.row(F(f, 1)).transpose() - t.a;
    t.e2 = V.row(F(f, 2)).transpose() - t.a;
    double extent = 0;
    for (int k = 0; k < 3; ++k) {
      t.lo[k] = std::min({V(F(f, 0), k), V(F(f, 1), k), V(F(f, 2), k)});
      t.hi[k] = std::max({V(F(f, 0), k), V(F(f, 1), k), V(F(f, 2), k)});
      extent = std::max(extent, t.hi[k] - t.lo[k]);
    }
    // Grown by 1e-9 of its size, so that rounding in the slab test never drops a hit on an edge.
    for (int k = 0; k < 3; ++k)
      t.lo[k] -= 1e-9 * extent, t.hi[k] += 1e-9 * extent;
  }
  return T;
}

// Moller-Trumbore: the ray parameter t of the hit with triangle t, or NaN.
double hit(const Vector3d& o, const Vector3d& d, const Triangle& t) {
  const Vector3d q = d.cross(t.e2);
  const double det = t.e1.dot(q);
  if (det == 0)
    return std::numeric_limits<double>::quiet_NaN();
  const Vector3d s = o - t.a;
  const double u = s.dot(q) / det;
  if (u < 0 || u > 1)
    return std::numeric_limits<double>::quiet_NaN();
  const Vector3d r = s.cross(t.e1);
  const double v = d.dot(r) / det;
  if (v < 0 || u + v > 1)
    return std::numeric_limits<double>::quiet_NaN();
  return t.e2.dot(r) / det;
}

// Slab test: does the ray o + s d, 0 < s < t_max, meet the triangle's box (closed)?
bool meets_box(const double o[3], const double d[3], const Triangle& t, double t_max) {
  double s0 = 0, s1 = t_max;
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (o[k] < t.lo[k] || o[k] > t.hi[k])
        return false;
      continue;
    }
    double a = (t.lo[k] - o[k]) / d[k], b = (t.hi[k] - o[k]) / d[k];
    if (a > b)
      std::swap(a, b);
    s0 = std::max(s0, a), s1 = std::min(s1, b);
    if (s0 > s1)
      return false;
  }
  return true;
}

void check(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& P) {
  if (V.cols() != 3 || F.cols() != 3 || P.cols() != 3)
    throw std::invalid_argument("ray_cast: V, F and the points must have 3 columns");
  if (F.size() > 0 && (F.minCoeff() < 0 || F.maxCoeff() >= V.rows()))
    throw std::invalid_argument("ray_cast: face index out of range");
}

} // namespace

std::vector<char> inside_by_ray_parity(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                       const Eigen::MatrixXd& P) {
  check(V, F, P);
  std::vector<char> inside(static_cast<size_t>(P.rows()), 0);
  if (F.rows() == 0)
    return inside;
  const Vector3d dir = Vector3d(1, 1e-4, 2e-4).normalized();
  const Vector3d lo = V.colwise().minCoeff(), hi = V.colwise().maxCoeff();
  // From the leftmost point to the mesh's right end a ray drifts in y and z by at most this much:
  // triangles are bucketed with their y-z boxes grown by it.
  const double x0 = P.rows() ? std::min(lo(0), P.col(0).minCoeff()) : lo(0);
  const double drift = 2.5e-4 * (hi(0) - x0) + 1e-12 * (hi - lo).norm();
  const int nb = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(F.rows()) / 4)), 1, 512);
  const double sy = std::max(hi(1) - lo(1), 1e-300) / nb, sz = std::max(hi(2) - lo(2), 1e-300) / nb;
  auto bucket = [&](double y, double z, int& by, int& bz) {
    by = std::clamp(static_cast<int>(std::floor((y - lo(1)) / sy)), 0, nb - 1);
    bz = std::clamp(static_cast<int>(std::floor((z - lo(2)) / sz)), 0, nb - 1);
  };
  const std::vector<Triangle> T = triangles(V, F);
  std::vector<std::vector<int>> buckets(static_cast<size_t>(nb) * nb);
  for (Index f = 0; f < F.rows(); ++f) {
    double y0 = INFINITY, y1 = -INFINITY, z0 = INFINITY, z1 = -INFINITY;
    for (int k = 0; k < 3; ++k) {
      y0 = std::min(y0, V(F(f, k), 1)), y1 = std::max(y1, V(F(f, k), 1));
      z0 = std::min(z0, V(F(f, k), 2)), z1 = std::max(z1, V(F(f, k), 2));
    }
    int a0, b0, a1, b1;
    bucket(y0 - drift, z0 - drift, a0, b0);
    bucket(y1 + drift, z1 + drift, a1, b1);
    for (int a = a0; a <= a1; ++a)
      for (int b = b0; b <= b1; ++b)
        buckets[static_cast<size_t>(a) * nb + b].push_back(static_cast<int>(f));
  }
  for (Index i = 0; i < P.rows(); ++i) {
    const Vector3d o = P.row(i).transpose();
    if (o(1) < lo(1) - drift || o(1) > hi(1) + drift || o(2) < lo(2) - drift ||
        o(2) > hi(2) + drift || o(0) > hi(0))
      continue;
    int a, b;
    bucket(o(1), o(2), a, b);
    int crossings = 0;
    for (int f : buckets[static_cast<size_t>(a) * nb + b])
      crossings += hit(o, dir, T[static_cast<size_t>(f)]) > 0;
    inside[static_cast<size_t>(i)] = crossings % 2;
  }
  return inside;
}

Eigen::VectorXd ray_hit_distance(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                 const Eigen::MatrixXd& O, const Eigen::MatrixXd& D) {
  check(V, F, O);
  if (D.rows() != O.rows() || D.cols() != 3)
    throw std::invalid_argument("ray_hit_distance: one direction per origin");
  const std::vector<Triangle> T = triangles(V, F);
  Eigen::VectorXd out = Eigen::VectorXd::Constant(O.rows(), INFINITY);
  for (Index i = 0; i < O.rows(); ++i) {
    const Vector3d o = O.row(i).transpose(), d = D.row(i).transpose();
    for (const Triangle& t : T) {
      if (!meets_box(o.data(), d.data(), t, out(i))) // only boxes nearer than the best hit
        continue;
      const double h = hit(o, d, t);
      if (h > 0 && h < out(i))
        out(i) = h;
    }
  }
  return out;
}

} // namespace interlin
