#pragma once
// Sectioned scans of a family of blade-like bodies (cambered, twisted, tapered thin profiles) in
// planar or radial slices with noise: the slices tests and the CLI's cloud tests.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <vector>

namespace interlin::test {

// The profile at span fraction t in [0, 1] (2D, chord about 2 - t): a thin cambered ellipse
// (thickness / chord `thick`), rotated by the twist 0.6 t rad.
inline Eigen::Vector2d profile(double theta, double t, double thick) {
  const double a = 1 - 0.5 * t, s = std::sin(theta);
  const Eigen::Vector2d q(a * std::cos(theta), a * (thick * s + 0.25 * s * s));
  return Eigen::Rotation2Dd(0.6 * t) * q;
}

// Other laws along the span for the same profile family: law 0 is `profile`; law 1 twists
// 1.5 t rad, tapers as 1 - 0.6 t + 0.3 t^2 and halves the camber towards the tip; law 2 sweeps the
// profile along its chord by 0.4 t^2, twists 0.8 t^3 rad and scales by 0.7 + 0.3 cos 2t.
inline Eigen::Vector2d profile(int law, double theta, double t, double thick) {
  if (law == 0)
    return profile(theta, t, thick);
  const double s = std::sin(theta);
  const double a = law == 1 ? 1 - 0.6 * t + 0.3 * t * t : 0.7 + 0.3 * std::cos(2 * t);
  const double camber = law == 1 ? 0.25 * (1 - 0.5 * t) : 0.15;
  const double sweep = law == 1 ? 0 : 0.4 * t * t, twist = law == 1 ? 1.5 * t : 0.8 * t * t * t;
  const Eigen::Vector2d q(a * std::cos(theta) + sweep, a * (thick * s + camber * s * s));
  return Eigen::Rotation2Dd(twist) * q;
}

struct Scan {
  Eigen::MatrixX3d P;
  std::vector<double> t; // span fraction of each slice
};

// Slices at span fractions `stations` (increasing, in [0, 1]) of `per` points each (random
// positions around the profile), noise sigma in 3D. Planar: planes x = 3 t; radial: cylinders r =
// 10 + 3 t about z, profile coordinates (r * angle, z).
inline Scan scan(bool radial, const std::vector<double>& stations, int per, double sigma,
                 double thick, unsigned seed, int law = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 2 * M_PI);
  std::normal_distribution<double> G(0, sigma);
  const int slices = int(stations.size());
  Scan s;
  s.P.resize(slices * per, 3);
  for (int k = 0; k < slices; ++k) {
    const double t = stations[size_t(k)];
    s.t.push_back(t);
    for (int i = 0; i < per; ++i) {
      const Eigen::Vector2d q = profile(law, U(rng), t, thick);
      Eigen::Vector3d p;
      if (radial) {
        const double r = 10 + 3 * t;
        p = {r * std::cos(q(0) / r), r * std::sin(q(0) / r), q(1)};
      } else {
        p = {3 * t, q(0), q(1)};
      }
      s.P.row(k * per + i) = (p + Eigen::Vector3d(G(rng), G(rng), G(rng))).transpose();
    }
  }
  return s;
}

// `slices` evenly spaced slices (t = k / (slices - 1)).
inline Scan scan(bool radial, int slices, int per, double sigma, double thick, unsigned seed) {
  std::vector<double> t;
  for (int k = 0; k < slices; ++k)
    t.push_back(double(k) / (slices - 1));
  return scan(radial, t, per, sigma, thick, seed);
}

} // namespace interlin::test
