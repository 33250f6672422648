#pragma once
// Point clouds sampled from closed surfaces with known geometry, for the cloud -> implicit tests:
// points uniform by area, exact outward normals, optional Gaussian noise, and the exact signed
// distance (positive inside) of the sphere, torus and ellipsoid-like bodies where it is known;
// boxes, whose edges are sharp.

#include "interlin/reconstruction/clouds/point_cloud.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <random>

namespace interlin::test {

enum class Shape { sphere, torus, ellipsoid };

// The truth: `a` scales the body. Ellipsoid semi-axes a * (1, 0.6, c), c = 0.15 by default: a
// thin, wall-like body (the two sides 2 c a apart in the middle) whose rim is as sharp as a
// blade's edge (radius of curvature c^2 a in the x z plane).
struct SampledShape {
  Shape shape;
  double a = 1;
  double c = 0.15; // the ellipsoid's third semi-axis / a
  // Signed distance (sphere, torus) or the algebraic distance's first-order version (ellipsoid:
  // g / |grad g| with g = 1 - sum (x_i / s_i)^2, exact to first order near the surface).
  double distance(const Eigen::Vector3d& p) const {
    switch (shape) {
    case Shape::sphere:
      return a - p.norm();
    case Shape::torus:
      return 0.3 * a - std::hypot(std::hypot(p(0), p(1)) - a, p(2));
    case Shape::ellipsoid: {
      const Eigen::Vector3d s = a * Eigen::Vector3d(1, 0.6, c);
      const Eigen::Vector3d q = p.cwiseQuotient(s);
      const double g = 1 - q.squaredNorm();
      return g / (2 * q.cwiseQuotient(s).norm());
    }
    }
    return 0;
  }
  // Point and outward normal at surface parameters (s, t) in [0, 1)^2, and the area density
  // (relative) used for rejection sampling.
  void point(double s, double t, Eigen::Vector3d& p, Eigen::Vector3d& n, double& density) const {
    const double u = 2 * M_PI * s;
    switch (shape) {
    case Shape::sphere:
    case Shape::ellipsoid: {
      const double z = 2 * t - 1, r = std::sqrt(std::max(0.0, 1 - z * z));
      const Eigen::Vector3d d(r * std::cos(u), r * std::sin(u), z); // uniform on the sphere
      const Eigen::Vector3d sc =
          shape == Shape::sphere ? Eigen::Vector3d::Ones() : Eigen::Vector3d(1, 0.6, c);
      p = a * d.cwiseProduct(sc);
      n = d.cwiseQuotient(sc).normalized();
      // area element of the affine image relative to the sphere's: |S^-T d| * det S
      density = shape == Shape::sphere ? 1 : d.cwiseQuotient(sc).norm() * sc.prod() / 0.6;
      return;
    }
    case Shape::torus: {
      const double v = 2 * M_PI * t;
      n = Eigen::Vector3d(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
      p = a * Eigen::Vector3d(std::cos(u), std::sin(u), 0) + 0.3 * a * n;
      density = (1 + 0.3 * std::cos(v)) / 1.3;
      return;
    }
    }
  }
};

// n points uniform by area (rejection sampling), exact normals, Gaussian noise of standard
// deviation sigma on each coordinate; deterministic for a seed.
inline PointCloud sample_shape(const SampledShape& s, int n, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  std::normal_distribution<double> G(0, 1);
  PointCloud c;
  c.points.resize(n, 3);
  c.normals.resize(n, 3);
  for (int i = 0; i < n;) {
    Eigen::Vector3d p, nn;
    double density;
    s.point(U(rng), U(rng), p, nn, density);
    if (U(rng) > density) // density <= 1 for these shapes
      continue;
    c.points.row(i) = (p + sigma * Eigen::Vector3d(G(rng), G(rng), G(rng))).transpose();
    c.normals.row(i) = nn.transpose();
    ++i;
  }
  return c;
}

// n points uniform by area on the box [-h, h], exact outward normals, Gaussian noise sigma.
inline PointCloud box_cloud(const Eigen::Vector3d& h, int n, double sigma, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  std::normal_distribution<double> G(0, sigma);
  const double area[3] = {h(1) * h(2), h(0) * h(2), h(0) * h(1)}; // per face of each axis / 4
  PointCloud c;
  c.points.resize(n, 3);
  c.normals.setZero(n, 3);
  for (int i = 0; i < n; ++i) {
    double t = 0.5 * (U(rng) + 1) * (area[0] + area[1] + area[2]);
    const int a = t < area[0] ? 0 : t < area[0] + area[1] ? 1 : 2;
    const double side = U(rng) < 0 ? -1 : 1;
    for (int k = 0; k < 3; ++k)
      c.points(i, k) = k == a ? side * h(k) : U(rng) * h(k);
    c.normals(i, a) = side;
    for (int k = 0; k < 3 && sigma > 0; ++k)
      c.points(i, k) += G(rng);
  }
  return c;
}

// Signed distance to the box [-h, h], positive inside.
inline double box_distance(const Eigen::Vector3d& h, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = p.cwiseAbs() - h;
  return -(q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0));
}

// Whether p lies within `reach` of two of the box's faces' planes: near an edge.
inline bool near_box_edge(const Eigen::Vector3d& h, const Eigen::Vector3d& p, double reach) {
  return ((p.cwiseAbs() - h).array().abs() < reach).count() >= 2;
}

} // namespace interlin::test
