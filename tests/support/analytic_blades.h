#pragma once
// A family of analytic blades for spanwise accuracy studies (test_span_model, bench/blade_family):
// twisted, tapered, leaned and swept blades whose surface B(t, s) is known in closed form, cut
// into sections at stations s_k (even, cosine-clustered at both ends, or clustered at the hub),
// each section with its own point count and point clustering. The error of a loft "between
// sections" is the distance to it of true surface points B(t, s) at intermediate stations.
//
// The profile at span fraction s in [0, 1], local coordinates (x along the chord from the leading
// edge 0 to the trailing edge 1, y across), as a smooth closed curve of the angle t in [0, 2 pi)
// (t = 0 trailing edge, t = pi leading edge):
//   x(t) = (1 + cos t) / 2,   y(t) = T(s) sin t (1 - 0.7 x) + 4 m(s) x (1 - x)
// (rounded edges; thickness T, camber m). It is scaled by the chord c(s) about the 30 % chord
// point, turned by the twist theta(s), shifted by sweep(s) along x and lean(s) along y, and
// placed on the stacking surface of station s:
//   planes     z = L s                                  (x, y, z) = (a, b, L s)
//   cylinders  R = R0 + L s, wrapped (axial a, arc b)   (R cos(b/R), R sin(b/R), a)
//   cones      R = R0 + L s + 0.25 a (stream surfaces inclined like Rotor 37's hub)
// with (a, b) the placed profile point.

#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/splines/bspline_curve.h"
#include "interlin/splines/spline_basis.h"

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace interlin::test {

enum class BladeStacking { planes, cylinders, cones };
enum class BladeSpacing { even, cosine, hub, tip };

// Span laws of one blade: functions of the span fraction s in [0, 1].
struct BladeLaw {
  std::string name;
  std::function<double(double)> chord, twist, thickness, camber, sweep, lean;
};

struct AnalyticBlade {
  BladeLaw law;
  BladeStacking stacking = BladeStacking::planes;
  double span = 4.0, hub_radius = 6.0; // L and R0 above

  Eigen::Vector3d point(double t, double s) const {
    const double x = 0.5 * (1 + std::cos(t));
    const double y =
        law.thickness(s) * std::sin(t) * (1 - 0.7 * x) + 4 * law.camber(s) * x * (1 - x);
    const double c = law.chord(s), w = law.twist(s);
    const double px = c * (x - 0.3), py = c * y;
    const double a = std::cos(w) * px - std::sin(w) * py + law.sweep(s);
    const double b = std::sin(w) * px + std::cos(w) * py + law.lean(s);
    if (stacking == BladeStacking::planes)
      return {a, b, span * s};
    const double R = hub_radius + span * s + (stacking == BladeStacking::cones ? 0.25 * a : 0.0);
    return {R * std::cos(b / R), R * std::sin(b / R), a};
  }

  // The points at angles t (#t), on the section at span fraction s.
  Eigen::MatrixXd points(double s, const Eigen::VectorXd& t) const {
    Eigen::MatrixXd P(t.size(), 3);
    for (Eigen::Index i = 0; i < t.size(); ++i)
      P.row(i) = point(t(i), s).transpose();
    return P;
  }
};

// n angles t_i = tau_i + clustering sin(2 tau_i), tau_i = 2 pi i / n (clustering < 0 puts more
// points at the edges, > 0 fewer), from the trailing edge.
inline Eigen::VectorXd blade_angles(Eigen::Index n, double clustering) {
  Eigen::VectorXd t(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double tau = 2 * M_PI * static_cast<double>(i) / static_cast<double>(n);
    t(i) = tau + clustering * std::sin(2 * tau);
  }
  return t;
}

// K stations in [0, 1]: even, cosine-clustered at both ends, clustered at the hub (s = 0) or at
// the tip (s = 1).
inline std::vector<double> blade_stations(int K, BladeSpacing spacing) {
  std::vector<double> s;
  for (int k = 0; k < K; ++k) {
    const double f = static_cast<double>(k) / (K - 1);
    s.push_back(spacing == BladeSpacing::even     ? f
                : spacing == BladeSpacing::cosine ? 0.5 * (1 - std::cos(M_PI * f))
                : spacing == BladeSpacing::hub    ? 1 - std::cos(0.5 * M_PI * f)
                                                  : std::sin(0.5 * M_PI * f)); // tip
  }
  return s;
}

// One case of the family: a blade, its sections (the angle t of each point), and the true
// points between them: `samples` per gap, at the middle station of the gap, gap k in rows
// [k samples, (k+1) samples), at the angles between_t.
struct BladeCase {
  std::string name;
  AnalyticBlade blade;
  std::vector<double> stations;
  std::vector<Section> sections;
  std::vector<Eigen::VectorXd> angles;
  Eigen::Index samples = 0;
  Eigen::VectorXd between_t;
  Eigen::MatrixXd between;
};

// Deterministic pseudo-random numbers in [0, 1) (a 64-bit LCG: the same on every platform, unlike
// the <random> distributions), for the laws' coefficients.
class Coefficients {
public:
  explicit Coefficients(std::uint64_t seed) : x_(seed * 2862933555777941757ULL + 3037000493ULL) {}
  double operator()(double lo, double hi) {
    x_ = x_ * 6364136223846793005ULL + 1442695040888963407ULL;
    return lo + (hi - lo) * static_cast<double>(x_ >> 11) / 9007199254740992.0;
  }

private:
  std::uint64_t x_;
};

// Six laws; `r` draws each coefficient from its range, so that every case is a different blade.
inline BladeLaw blade_law(int which, Coefficients& r) {
  const double k1 = r(0.5, 1.0), k2 = r(0.2, 0.5), k3 = r(0.05, 0.1), k4 = r(0.02, 0.08);
  switch (which % 6) {
  case 0: // linear twist and taper
    return {"linear twist, taper",
            [=](double s) { return 1.5 - k2 * 1.5 * s; },
            [=](double s) { return k1 * s; },
            [=](double) { return k3; },
            [=](double) { return k4; },
            [](double) { return 0.0; },
            [](double) { return 0.0; }};
  case 1: // quadratic twist, lean and thinning
    return {"quadratic twist, lean",
            [](double) { return 1.2; },
            [=](double s) { return 0.3 + k1 * s * s; },
            [=](double s) { return k3 * (1 - 0.4 * s); },
            [=](double s) { return k4 * (1 - s); },
            [](double) { return 0.0; },
            [=](double s) { return k2 * s * s; }};
  case 2: // sinusoidal twist, compound sweep and lean
    return {"sine twist, sweep and lean",
            [=](double s) { return 1.0 + 0.3 * std::cos(2 * s); },
            [=](double s) { return k1 * std::sin(1.5 * s); },
            [=](double) { return k3; },
            [=](double s) { return k4 * (1 + s); },
            [=](double s) { return k2 * std::sin(M_PI * s); },
            [=](double s) { return -k2 * s; }};
  case 3: // turbine-like: strong cubic twist, squared taper, thick and cambered at the hub
    return {"cubic twist, squared taper",
            [=](double s) { return 1.3 * std::pow(1 - k2 * s, 2); },
            [=](double s) { return 1.2 * k1 * s - 0.4 * s * s * s; },
            [=](double s) { return 1.5 * k3 * (1 - 0.5 * s); },
            [=](double s) { return 2 * k4 * (1 - 0.7 * s); },
            [](double) { return 0.0; },
            [](double) { return 0.0; }};
  case 4: // wind-turbine-like: hyperbolic twist and exponential chord (fast change at the hub)
    return {"hyperbolic twist, exponential chord",
            [=](double s) { return 0.5 + 1.0 * std::exp(-3 * k2 * s); },
            [=](double s) { return 0.4 * k1 / (0.3 + s); },
            [=](double s) { return k3 * (1 - 0.3 * s); },
            [=](double) { return k4; },
            [](double) { return 0.0; },
            [=](double s) { return 0.3 * k2 * s; }};
  default: // propeller-like: bell-shaped chord, skew (sweep) growing with the span
    return {"bell chord, skew",
            [=](double s) { return 0.5 + 0.8 * std::sin(M_PI * (0.2 + 0.6 * s)); },
            [=](double s) { return k1 * (1 - s) * (1 - s); },
            [=](double) { return k3; },
            [=](double s) { return k4 * (1 - s); },
            [=](double s) { return k2 * s * s * s; },
            [](double) { return 0.0; }};
  }
}

// The case `index` of a family: law index % 6, stacking, spacing and section count from the
// index, coefficients, point counts (40 to 140) and clustering (-0.35 to 0.15) drawn per case.
// Family 0 is the reference family (kBladeCases cases, 5, 7 or 10 sections, even, cosine or hub
// spacing); a family f >= 1 is a fresh one for checks on blades a rule was not tuned on: its
// own draws (seed 1000 f + index + 1), 6, 8 or 9 sections, and tip instead of hub clustering for
// even f. `between` holds `samples` true points at the middle of each gap.
inline BladeCase blade_case(int index, int samples = 120, int family = 0) {
  const std::array<int, 3> counts =
      family == 0 ? std::array<int, 3>{5, 7, 10} : std::array<int, 3>{6, 8, 9};
  const BladeSpacing clustered =
      family > 0 && family % 2 == 0 ? BladeSpacing::tip : BladeSpacing::hub;
  const std::array<BladeSpacing, 3> spacings = {BladeSpacing::even, BladeSpacing::cosine,
                                                clustered};
  static const std::array<BladeStacking, 3> stackings = {
      BladeStacking::planes, BladeStacking::cylinders, BladeStacking::cones};
  const char* const spacing_names[] = {"even", "cosine",
                                       clustered == BladeSpacing::hub ? "hub" : "tip"};
  static const char* const stacking_names[] = {"planes", "cylinders", "cones"};
  Coefficients r(static_cast<std::uint64_t>(1000 * family + index) + 1);
  BladeCase c;
  const int spacing = (index / 6) % 3, K = counts[static_cast<size_t>((index / 18) % 3)];
  const int stacking = (index + index / 6) % 3;
  c.blade.law = blade_law(index, r);
  c.blade.stacking = stackings[static_cast<size_t>(stacking)];
  c.stations = blade_stations(K, spacings[static_cast<size_t>(spacing)]);
  c.name = "#" + std::to_string(index) + " " + c.blade.law.name + ", " + stacking_names[stacking] +
           ", " + spacing_names[spacing] + ", K = " + std::to_string(K);
  for (int k = 0; k < K; ++k) {
    Section s;
    s.id = std::to_string(k);
    const auto n = static_cast<Eigen::Index>(40 + 10 * static_cast<int>(r(0, 11)));
    c.angles.push_back(blade_angles(n, r(-0.35, 0.15)));
    s.points = c.blade.points(c.stations[static_cast<size_t>(k)], c.angles.back());
    for (Eigen::Index i = 0; i < n; ++i)
      s.lines.push_back(i + 2);
    c.sections.push_back(s);
  }
  c.samples = samples;
  c.between_t = blade_angles(samples, 0.0);
  c.between.resize((K - 1) * samples, 3);
  for (size_t k = 0; k + 1 < c.stations.size(); ++k)
    c.between.middleRows(static_cast<Eigen::Index>(k) * samples, samples) =
        c.blade.points(0.5 * (c.stations[k] + c.stations[k + 1]), c.between_t);
  return c;
}

// The exact distance of the true points between sections to a surface S lofted from the case's
// sections (interlin's, or another library's through ParametricSurface): the lower of two local
// minima of the distance, the feet from the nearest samples of a 1024 x 256 grid
// (project_to_surface, 32 starts) and the feet from corresponding parameters. The latter are the
// means of the feet of the true points at the same angle on the two neighbouring sections: those
// lie on S up to the section curves' own error, so their feet are unambiguous, and starting there
// keeps the right side of a thin edge where S is farther from the truth than the blade is thick.
// between_projection gives the feet (parameters, points, distances) of c.between.
inline SurfaceProjection between_projection(const BladeCase& c, const ParametricSurface& S) {
  const Eigen::Index m = c.samples, K = static_cast<Eigen::Index>(c.stations.size());
  const Eigen::Index nb = c.between.rows();
  // One grid search for the true points on the sections and between them.
  Eigen::MatrixXd P(nb + K * m, 3);
  P.topRows(nb) = c.between;
  for (Eigen::Index k = 0; k < K; ++k)
    P.middleRows(nb + k * m, m) = c.blade.points(c.stations[static_cast<size_t>(k)], c.between_t);
  const SurfaceProjection f = project_to_surface(S, P, 1024, 256, 32);
  const double period = S.domain(1) - S.domain(0);
  Eigen::VectorXd u0(nb), v0(nb);
  for (Eigen::Index k = 0; k + 1 < K; ++k)
    for (Eigen::Index i = 0; i < m; ++i) {
      const Eigen::Index a = nb + k * m + i, b = nb + (k + 1) * m + i;
      double ub = f.u(b);
      if (S.closed_u && std::abs(ub - f.u(a)) > period / 2) // the mean on the circle of u
        ub += ub < f.u(a) ? period : -period;
      u0(k * m + i) = 0.5 * (f.u(a) + ub);
      v0(k * m + i) = 0.5 * (f.v(a) + f.v(b));
    }
  SurfaceProjection g = project_from(S, c.between, u0, v0);
  for (Eigen::Index i = 0; i < nb; ++i)
    if (f.distance(i) < g.distance(i)) {
      g.u(i) = f.u(i);
      g.v(i) = f.v(i);
      g.distance(i) = f.distance(i);
      g.foot.row(i) = f.foot.row(i);
    }
  return g;
}

inline Eigen::VectorXd between_distances(const BladeCase& c, const ParametricSurface& S) {
  return between_projection(c, S).distance;
}

// True profile points of section k of a case densely between its input points: per_gap - 1
// angles evenly inside each gap between consecutive input angles (the input points, where every
// interpolant is exact, left out). Output: #P (per_gap - 1) by 3.
inline Eigen::MatrixXd points_between_inputs(const BladeCase& c, size_t k, int per_gap) {
  const Eigen::VectorXd& t = c.angles[k];
  Eigen::VectorXd dense(t.size() * (per_gap - 1));
  for (Eigen::Index i = 0; i < t.size(); ++i) {
    const double next = i + 1 < t.size() ? t(i + 1) : t(0) + 2 * M_PI;
    for (int j = 1; j < per_gap; ++j)
      dense(i * (per_gap - 1) + j - 1) = t(i) + (next - t(i)) * j / per_gap;
  }
  return c.blade.points(c.stations[k], dense);
}

// The curve u -> S(u, v) of a surface at one v (the section curve of a loft at v = v_k, where the
// loft interlineates it): control points sum_j M_j(v) ctrl(., j).
inline BSplineCurve iso_curve_at(const BSplineSurface& S, double v) {
  Eigen::Index span;
  const Eigen::MatrixXd M = basis_derivatives(explicit_basis(S.knots_v, S.degree_v), v, 0, &span);
  Eigen::MatrixXd ctrl = Eigen::MatrixXd::Zero(S.num_u, 3);
  for (int j = 0; j <= S.degree_v; ++j)
    ctrl += M(0, j) * S.ctrl.middleRows(S.num_u * (span - S.degree_v + j), S.num_u);
  return {S.degree_u, S.knots_u, ctrl, false};
}

// Number of cases in the family: every law with every spacing, stacking and count.
inline constexpr int kBladeCases = 54;

} // namespace interlin::test
