#pragma once
// Synthetic blades for the implicit-body tests: families of cambered, twisted, tapering,
// leaning NACA four-digit sections with uneven point spacing and uneven section spacing, so
// that defaults are checked on shapes the Rotor 37 file does not have.

#include "interlin/reconstruction/io/section_csv.h"

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

namespace interlin::test {

// One family member.
//   sections, points   section count and points per section (even; LE and TE are points)
//   camber, camber_at, thickness   NACA 4-digit m, p, t (fractions of the chord)
//   chord, taper       chord at the hub, and its relative change to the tip
//   twist_deg          stagger change from hub to tip
//   span               hub-to-tip height (sections at z in [0, span])
//   lean               tip offset along the tangential direction (x chord units)
//   section_power      z_k = span (k / (K-1))^power: 1 uniform, else clustered at one end
//   point_power        x = ((1 - cos(pi s)) / 2)^point_power along each side (cosine at 1)
struct BladeFamily {
  int sections = 6, points = 60;
  double camber = 0.05, camber_at = 0.4, thickness = 0.12;
  double chord = 1, taper = 0.3, twist_deg = 25, span = 1.5, lean = 0.15;
  double section_power = 1, point_power = 1;
};

// NACA 4-digit camber line and half thickness (closed trailing edge: -0.1036).
inline void naca(const BladeFamily& f, double x, double& yc, double& dyc, double& yt) {
  const double m = f.camber, p = f.camber_at, t = f.thickness;
  if (x < p) {
    yc = m / (p * p) * (2 * p * x - x * x);
    dyc = 2 * m / (p * p) * (p - x);
  } else {
    yc = m / ((1 - p) * (1 - p)) * (1 - 2 * p + 2 * p * x - x * x);
    dyc = 2 * m / ((1 - p) * (1 - p)) * (p - x);
  }
  yt = 5 * t *
       (0.2969 * std::sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x -
        0.1036 * x * x * x * x);
}

// The sections of the family, hub first; points from the trailing edge over the upper side to
// the leading edge and back over the lower side (the closing edge implicit).
inline std::vector<Section> blade_sections(const BladeFamily& f) {
  std::vector<Section> out;
  const int half = f.points / 2;
  for (int k = 0; k < f.sections; ++k) {
    const double s = double(k) / (f.sections - 1);
    const double z = f.span * std::pow(s, f.section_power);
    const double c = f.chord * (1 - f.taper * z / f.span);
    const double w = f.twist_deg * M_PI / 180 * z / f.span;
    const double shift = f.lean * z / f.span;
    Section sec;
    sec.id = std::to_string(k);
    sec.points.resize(2 * half, 3);
    for (int i = 0; i < 2 * half; ++i) {
      const bool upper = i <= half; // TE (i = 0) ... LE (i = half)
      const double a = upper ? 1 - double(i) / half : double(i - half) / half; // 1 .. 0 .. 1
      const double x = std::pow(0.5 * (1 - std::cos(M_PI * a)), f.point_power);
      double yc, dyc, yt;
      naca(f, x, yc, dyc, yt);
      const double th = std::atan(dyc), sg = upper ? 1 : -1;
      const double px = (x - sg * yt * std::sin(th) - 0.5) * c,
                   py = (yc + sg * yt * std::cos(th)) * c;
      sec.points.row(i) << std::cos(w) * px - std::sin(w) * py + shift,
          std::sin(w) * px + std::cos(w) * py, z;
      sec.lines.push_back(i + 2);
    }
    out.push_back(sec);
  }
  return out;
}

// A few family members with different shapes and spacings.
inline std::vector<BladeFamily> blade_families() {
  std::vector<BladeFamily> f(3);
  f[1].camber = 0.08;
  f[1].thickness = 0.06;
  f[1].twist_deg = 50;
  f[1].sections = 9;
  f[1].points = 90;
  f[1].section_power = 1.6;
  f[1].point_power = 1.3;
  f[2].camber = 0.02;
  f[2].thickness = 0.2;
  f[2].taper = -0.2;
  f[2].lean = -0.3;
  f[2].sections = 4;
  f[2].points = 48;
  return f;
}

} // namespace interlin::test
