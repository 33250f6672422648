// Sectioned scans: slice detection, profile ordering, fitted sections and their loft, on a
// family of generated blade-like bodies (cambered, twisted, tapered thin profiles) scanned in
// planar or radial slices with noise, against the exact profiles.

#include "interlin/reconstruction/clouds/fit_sliced_scan.h"
#include "interlin/reconstruction/loft/closest_point.h"

#include "support/sliced_scans.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>

#include <cmath>
#include <iostream>
#include <random>

using namespace interlin;
using Eigen::Index;
using Eigen::VectorXd;
using test::profile;
using test::scan;
using test::Scan;

namespace {

// The distance of a 2D point to the exact profile (dense polygon; its sag at 20000 vertices is
// below 1e-7 of the chord).
double profile_distance(const Eigen::Vector2d& q, double t, double thick) {
  static thread_local Eigen::MatrixX2d poly;
  static thread_local double key = -1;
  const int n = 20000;
  if (key != t + 10 * thick) {
    poly.resize(n, 2);
    for (int i = 0; i < n; ++i)
      poly.row(i) = profile(2 * M_PI * i / n, t, thick).transpose();
    key = t + 10 * thick;
  }
  double best = 1e300;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d a = poly.row(i).transpose(), b = poly.row((i + 1) % n).transpose();
    const double h = std::clamp((q - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    best = std::min(best, (a + h * (b - a) - q).norm());
  }
  return best;
}

// rms and max distance of the fitted sections' samples to the exact profiles.
std::pair<double, double> section_error(const SlicedFit& f, const Scan& s, bool radial,
                                        double thick) {
  double sq = 0, mx = 0;
  long n = 0;
  for (size_t k = 0; k < f.sections.size(); ++k) {
    const Eigen::MatrixXd& S = f.sections[k].section;
    for (Index i = 0; i < S.rows(); i += 10) { // every 10th: the brute-force distance is slow
      const Eigen::Vector3d p = S.row(i).transpose();
      const double r = std::hypot(p(0), p(1));
      const Eigen::Vector2d q =
          radial ? Eigen::Vector2d(r * std::atan2(p(1), p(0)), p(2)) : Eigen::Vector2d(p(1), p(2));
      const double d = profile_distance(q, s.t[k], thick);
      sq += d * d;
      mx = std::max(mx, d);
      ++n;
    }
  }
  return {std::sqrt(sq / double(n)), mx};
}

} // namespace

TEST_CASE("detect_slices finds planar and radial families and rejects unstructured clouds",
          "[clouds][slices]") {
  for (bool radial : {false, true})
    for (double sigma : {0.0, 0.003}) {
      const Scan s = scan(radial, 12, 300, sigma, 0.1, 3);
      const SliceFamily f = detect_slices(s.P);
      INFO("radial " << radial << ", sigma " << sigma);
      REQUIRE(f.kind == (radial ? SliceKind::radial : SliceKind::planar));
      REQUIRE(f.members.size() == 12);
      // the axis to round-off, or (planar, refined by least squares) to the noise's share
      CHECK(std::abs(std::abs(f.axis(radial ? 2 : 0)) - 1) < (sigma > 0 ? 1e-6 : 1e-12));
      for (const auto& m : f.members)
        CHECK(m.size() == 300);
      // the spread estimates the noise normal to the slices (3600 samples: 5 % accuracy)
      CHECK(f.spread == Approx(sigma).margin(1e-12).epsilon(0.05));
    }
  // the same body scanned without structure: 60 slices' worth of random span positions
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(0, 1);
  Eigen::MatrixX3d P(4000, 3);
  for (Index i = 0; i < P.rows(); ++i) {
    const double t = U(rng);
    const Eigen::Vector2d q = profile(2 * M_PI * U(rng), t, 0.1);
    P.row(i) << 3 * t, q(0), q(1);
  }
  CHECK(detect_slices(P).kind == SliceKind::none);
  // asking for the other kind finds nothing
  CHECK(detect_slices(scan(false, 12, 300, 0.0, 0.1, 5).P, SliceKind::radial).kind ==
        SliceKind::none);
}

// Unevenly spaced slices (denser at the root, at both ends, or jittered), the closest two 10 sigma
// apart: the gaps between the close slices rival the gaps inside the others, so the gap cuts alone
// merged the closest pair (9 slices at the root: 8 found; 17: 16), a slice of two peaks that
// passed the family's checks. Every slice is found, with exactly its own points.
TEST_CASE("detect_slices separates unevenly spaced slices", "[clouds][slices]") {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> U(-0.3, 0.3);
  for (bool radial : {false, true})
    for (int K : {9, 17})
      for (int law : {0, 1, 2}) {
        std::vector<double> t;
        for (int k = 0; k < K; ++k) {
          const double x = double(k) / (K - 1);
          t.push_back(law == 0   ? x * x
                      : law == 1 ? 0.5 * (1 - std::cos(M_PI * x))
                                 : (k == 0 || k == K - 1 ? x : x + U(rng) / (K - 1)));
        }
        double gap = 1;
        for (int k = 0; k + 1 < K; ++k)
          gap = std::min(gap, t[size_t(k + 1)] - t[size_t(k)]);
        const double sigma = 3 * gap / 10; // stations are 3 t (planes x, cylinders r - 10)
        const Scan s = scan(radial, t, 300, sigma, 0.1, 7 + unsigned(K + law));
        const SliceFamily f = detect_slices(s.P);
        INFO("radial " << radial << ", " << K << " slices, spacing law " << law << ", sigma "
                       << sigma);
        REQUIRE(f.kind == (radial ? SliceKind::radial : SliceKind::planar));
        REQUIRE(f.members.size() == size_t(K));
        for (size_t k = 0; k < f.members.size(); ++k) {
          REQUIRE(f.members[k].size() == 300);
          for (Index i : f.members[k])
            CHECK(i / 300 == Index(k));
        }
      }
}

// A family: thickness 0.04 to 0.3, twist and camber of four span stations, 150 to 1000 random
// points, 40 seeds. Random points leave some chord bins with points of one side only; before
// order_profile left those bins out of its mean line, seeds 12 and 37 of the 0.04 profiles failed.
TEST_CASE("order_profile walks around a thin cambered profile", "[clouds][slices]") {
  for (double thick : {0.04, 0.1, 0.3})
    for (double t : {0.0, 3.0 / 7, 0.5, 1.0})
      for (int n : {150, 400, 1000})
        for (unsigned seed = 1; seed <= 40; ++seed) {
          std::mt19937 rng(seed);
          std::uniform_real_distribution<double> U(0, 2 * M_PI);
          std::vector<double> theta(static_cast<size_t>(n), 0.0);
          Eigen::MatrixX2d P(n, 2);
          for (int i = 0; i < n; ++i) {
            theta[size_t(i)] = U(rng);
            P.row(i) = profile(theta[size_t(i)], t, thick).transpose();
          }
          const std::vector<Index> order = order_profile(P);
          REQUIRE(order.size() == size_t(n));
          // consecutive points are neighbours on the profile: their angle steps are all one sign
          // (up to the wrap) and sum to one turn
          double turn = 0;
          int backwards = 0;
          for (int i = 0; i < n; ++i) {
            const double d = std::remainder(theta[size_t(order[size_t((i + 1) % n)])] -
                                                theta[size_t(order[size_t(i)])],
                                            2 * M_PI);
            turn += d;
            backwards += d * turn < 0;
          }
          INFO("thickness " << thick << ", span " << t << ", " << n << " points, seed " << seed);
          CHECK(std::abs(std::abs(turn) - 2 * M_PI) < 1e-9);
          CHECK(backwards == 0);
        }
}

TEST_CASE("fitted sections follow the exact profiles within 0.3 sigma and the loft contains them",
          "[clouds][slices]") {
  for (bool radial : {false, true})
    for (double sigma : {0.0, 0.002, 0.008}) {
      const Scan s = scan(radial, 8, 500, sigma, 0.1, 11);
      const SliceFamily f = detect_slices(s.P, radial ? SliceKind::radial : SliceKind::planar);
      REQUIRE(f.members.size() == 8);
      const SlicedFit fit = fit_sliced_scan(s.P, f);
      const auto [rms, mx] = section_error(fit, s, radial, 0.1);
      int control = 0;
      for (const FittedSection& fs : fit.sections)
        control = std::max(control, fs.control);
      INFO("radial " << radial << ", sigma " << sigma << ": rms " << rms << ", max " << mx
                     << ", section gap " << fit.section_gap << ", control points <= " << control);
      // the target is 1.5 sigma; measured with feet, turning-weighted knots and C_p:
      // rms 0.21 sigma (sigma 0.002 and 0.008; before them 0.4-0.55 sigma) and 5.5e-7 without
      // noise (before 8.2e-5), max 0.64-0.81 sigma and 6.4e-6; bounds with a margin of 1.4 to 4
      CHECK(rms <= 0.3 * sigma + 2e-6);
      CHECK(mx <= 1.2 * sigma + 3e-5);
      // the loft contains the fitted curves: at their samples and halfway between them
      CHECK(fit.loft.max_deviation <= 1e-9 * fit.loft.bbox_diagonal);
      CHECK(fit.section_gap <= 1e-9 * fit.loft.bbox_diagonal);
    }
}

// Sections are fitted in parallel, each on its own: the result does not depend on the threads.
TEST_CASE("sectioned scans: the fit is the same on 1 and 3 threads", "[clouds][slices]") {
  const Scan s = scan(true, 7, 300, 0.004, 0.1, 9);
  const SliceFamily f = detect_slices(s.P, SliceKind::radial);
  SliceFitOptions one, three;
  one.threads = 1;
  three.threads = 3;
  const SlicedFit a = fit_sliced_scan(s.P, f, one), b = fit_sliced_scan(s.P, f, three);
  REQUIRE(a.sections.size() == b.sections.size());
  for (size_t k = 0; k < a.sections.size(); ++k) {
    CHECK(a.sections[k].curve.knots == b.sections[k].curve.knots);
    CHECK(a.sections[k].curve.ctrl == b.sections[k].curve.ctrl);
  }
}

// The loft contains every fitted section curve, not only its samples: S(u, v_k) = C_k(u) at
// random u between the samples, to 1e-9 of the diagonal (a linear solve per control-point
// column: round-off), on a family of scans (planar and radial, 3 to 12 slices, 150 to 800
// points per slice, thin and thick profiles, noise 0 to 0.01). Planar sections stay in their
// planes to round-off (the fit is affine-invariant); radial ones are cubics fitted to points on
// their cylinder, which leave it where they leave the profile, in gaps between random points
// (4.2e-4 over a gap of 200 noise-free points; the bound is the fit's own, as above).
TEST_CASE("the loft of a sectioned scan contains the fitted section curves between their samples",
          "[clouds][slices]") {
  struct Case {
    bool radial;
    int slices, per;
    double sigma, thick;
  };
  for (const Case c : {Case{false, 3, 150, 0.0, 0.1}, Case{false, 12, 300, 0.01, 0.04},
                       Case{true, 5, 800, 0.003, 0.3}, Case{true, 9, 200, 0.0, 0.1}}) {
    const Scan s = scan(c.radial, c.slices, c.per, c.sigma, c.thick, 23);
    const SliceFamily f = detect_slices(s.P, c.radial ? SliceKind::radial : SliceKind::planar);
    REQUIRE(int(f.members.size()) == c.slices);
    const SlicedFit fit = fit_sliced_scan(s.P, f);
    const PiecewiseSurface S = to_piecewise(fit.loft.surface);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(0, 1);
    double gap = 0, off = 0;
    for (size_t k = 0; k < fit.sections.size(); ++k) {
      const BSplineCurve& C = fit.sections[k].curve;
      const VectorXd u = VectorXd::NullaryExpr(2000, [&] { return U(rng); });
      const Eigen::MatrixXd X = evaluate(C, u);
      for (Index i = 0; i < u.size(); ++i) {
        const Eigen::Vector3d x = X.row(i).transpose();
        gap = std::max(gap, (evaluate(S, u(i), fit.loft.section_v(Index(k))) - x).norm());
        off = std::max(off, std::abs(f.station(x) - fit.sections[k].station));
      }
    }
    INFO("radial " << c.radial << ", " << c.slices << " slices: gap " << gap << ", off the slice "
                   << off << ", diagonal " << fit.loft.bbox_diagonal);
    CHECK(gap <= 1e-9 * fit.loft.bbox_diagonal);
    CHECK(off <= (c.radial ? 5 * c.sigma + 1e-3 : 1e-12 * fit.loft.bbox_diagonal));
  }
}

// Measurement, not a test (hidden tag; docs/benchmarks.md, "Sectioned scans: the spanwise
// model"): the loft of the fitted sections with the sectioned scans' fixed spanwise model
// (station cubic, no cross-validation) against the leave-one-out choice (--span auto), by the
// distance of the true profiles halfway between the slices to each surface. Slices at even or
// cosine-clustered stations, 6 or 12 of them, planar or radial, three noise levels.
TEST_CASE("sectioned scans: the fixed station cubic against the leave-one-out span model",
          "[.measure][clouds][slices]") {
  constexpr double kThick = 0.1;
  constexpr int kPer = 400, kTruth = 256;
  std::cout << "| slices | spacing | sigma | fixed: max / rms | auto: max / rms | auto model |\n"
               "|---|---|---|---|---|---|\n";
  for (bool radial : {false, true})
    for (int K : {6, 12})
      for (bool clustered : {false, true})
        for (double sigma : {0.0, 0.002, 0.008}) {
          std::vector<double> t(static_cast<size_t>(K));
          for (int k = 0; k < K; ++k)
            t[size_t(k)] =
                clustered ? 0.5 - 0.5 * std::cos(M_PI * k / (K - 1)) : double(k) / (K - 1);
          const auto place = [&](const Eigen::Vector2d& q, double tk) -> Eigen::Vector3d {
            const double r = 10 + 3 * tk;
            return radial ? Eigen::Vector3d(r * std::cos(q(0) / r), r * std::sin(q(0) / r), q(1))
                          : Eigen::Vector3d(3 * tk, q(0), q(1));
          };
          std::mt19937 rng(17 + K);
          std::uniform_real_distribution<double> U(0, 2 * M_PI);
          std::normal_distribution<double> G(0, sigma);
          Eigen::MatrixX3d P(K * kPer, 3);
          for (int k = 0; k < K; ++k)
            for (int i = 0; i < kPer; ++i)
              P.row(k * kPer + i) = (place(profile(U(rng), t[size_t(k)], kThick), t[size_t(k)]) +
                                     Eigen::Vector3d(G(rng), G(rng), G(rng)))
                                        .transpose();
          const SliceFamily f = detect_slices(P, radial ? SliceKind::radial : SliceKind::planar);
          if (int(f.members.size()) != K) { // close slices within the noise merge
            std::cout << "| " << K << (radial ? " radial" : " planar") << " | "
                      << (clustered ? "cosine" : "even") << " | " << sigma << " | "
                      << f.members.size() << " slices detected | | |\n";
            continue;
          }
          const SlicedFit fit = fit_sliced_scan(P, f);
          LoftOptions automatic = sliced_scan_loft_options();
          automatic.span_degree = kAutoSpanDegree;
          automatic.span_holdout = true;
          const LoftResult loo = loft_sections(fitted_sections(fit.sections), automatic);
          Eigen::MatrixXd T((K - 1) * kTruth, 3);
          for (int k = 0; k + 1 < K; ++k)
            for (int i = 0; i < kTruth; ++i) {
              const double tm = 0.5 * (t[size_t(k)] + t[size_t(k) + 1]);
              T.row(k * kTruth + i) =
                  place(profile(2 * M_PI * i / kTruth, tm, kThick), tm).transpose();
            }
          const auto error = [&](const LoftResult& l) {
            const VectorXd d = project_to_surface(to_piecewise(l.surface), T).distance;
            return std::make_pair(d.maxCoeff(), std::sqrt(d.squaredNorm() / double(d.size())));
          };
          const auto [fm, fr] = error(fit.loft);
          const auto [am, ar] = error(loo);
          std::cout << "| " << K << (radial ? " radial" : " planar") << " | "
                    << (clustered ? "cosine" : "even") << " | " << sigma << " | " << fm << " / "
                    << fr << " | " << am << " / " << ar << " | "
                    << to_string(loo.span.used.parameters) << " " << loo.span.used.degree << " |\n";
        }
}

// Measurement, not a test (hidden tag; docs/benchmarks.md, "Sectioned scans: feet, knots where
// the profile turns, and C_p"): the fitted sections' rms and max distance to the
// exact profiles over a family of scans (planar and radial, 150 to 1000 random points per slice,
// thickness 0.04 to 0.3 of the chord, noise 0 to 0.01, chord about 1.5), the yardstick for any
// change to the section fit.
TEST_CASE("sectioned scans: fitted sections against the exact profiles over a family",
          "[.measure][clouds][slices]") {
  std::cout << "| slices | points | thickness | sigma | one by one: rms | max | control points "
               "| smoothed along the span: rms | max | control points |\n"
               "|---|---|---|---|---|---|---|---|---|---|\n";
  for (bool radial : {false, true})
    for (int per : {150, 400, 1000})
      for (double thick : {0.04, 0.1, 0.3})
        for (double sigma : {0.0, 0.001, 0.004, 0.01}) {
          const Scan s = scan(radial, 8, per, sigma, thick, 31);
          const SliceFamily f = detect_slices(s.P, radial ? SliceKind::radial : SliceKind::planar);
          std::cout << "| " << (radial ? "radial" : "planar") << " | " << per << " | " << thick
                    << " | " << sigma;
          if (f.members.size() != 8) {
            std::cout << " | " << f.members.size() << " slices | | | | | |\n";
            continue;
          }
          for (bool smooth : {false, true}) {
            SliceFitOptions o;
            o.smooth_span = smooth;
            const SlicedFit fit = fit_sliced_scan(s.P, f, o);
            const auto [rms, mx] = section_error(fit, s, radial, thick);
            int lo = 1 << 30, hi = 0;
            for (const FittedSection& fs : fit.sections)
              lo = std::min(lo, fs.control), hi = std::max(hi, fs.control);
            std::cout << " | " << rms << " | " << mx << " | " << lo << " - " << hi;
            if (fit.span_control > 0)
              std::cout << " x " << fit.span_control;
          }
          std::cout << " |\n";
        }
}

namespace {

// rms and max distance from n random points of the true surface (span law `law`, between the
// first and last slice; random generator seeded with `seed`) to the loft.
std::pair<double, double> surface_error(const SlicedFit& f, bool radial, double thick, Index n,
                                        unsigned seed, int law = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(0, 1);
  Eigen::MatrixXd T(n, 3);
  for (Index i = 0; i < T.rows(); ++i) {
    const double t = U(rng), r = 10 + 3 * t;
    const Eigen::Vector2d q = profile(law, 2 * M_PI * U(rng), t, thick);
    if (radial)
      T.row(i) << r * std::cos(q(0) / r), r * std::sin(q(0) / r), q(1);
    else
      T.row(i) << 3 * t, q(0), q(1);
  }
  const VectorXd d = project_to_surface(to_piecewise(f.loft.surface), T).distance;
  return {std::sqrt(d.squaredNorm() / double(d.size())), d.maxCoeff()};
}

// The scan's slices (`slices` of them, planar or radial) fitted one by one and smoothed along the
// span (the default).
std::pair<SlicedFit, SlicedFit> alone_and_smoothed(const Scan& s, bool radial, size_t slices) {
  const SliceFamily f = detect_slices(s.P, radial ? SliceKind::radial : SliceKind::planar);
  REQUIRE(f.members.size() == slices);
  SliceFitOptions alone;
  alone.smooth_span = false;
  return {fit_sliced_scan(s.P, f, alone), fit_sliced_scan(s.P, f, SliceFitOptions{})};
}

} // namespace

// Measurement, not a test (hidden tag; docs/benchmarks.md, "Sectioned scans: smoothing along the
// span"): the distance from the true surface (4000 random points between the first and last
// slice) to the loft, and from the fitted sections to the true profiles, with the sections fitted
// one by one and smoothed along the span, over a family of scans: planar and radial, 8 to 32
// slices of 150 or 1000 random points, thickness 0.04 and 0.3, noise 0 to 0.01.
TEST_CASE("sectioned scans: smoothing along the span against the sections one by one",
          "[.measure][clouds][slices]") {
  std::cout << "| slices | points | thickness | sigma | one by one: surface rms | max | sections "
               "rms | max | smoothed: surface rms | max | sections rms | max | control points |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (bool radial : {false, true})
    for (int K : {8, 16, 32})
      for (int per : {150, 1000})
        for (double thick : {0.04, 0.3})
          for (double sigma : {0.0, 0.002, 0.01}) {
            const Scan s = scan(radial, K, per, sigma, thick, 41);
            const SliceFamily f =
                detect_slices(s.P, radial ? SliceKind::radial : SliceKind::planar);
            std::cout << "| " << K << (radial ? " radial" : " planar") << " | " << per << " | "
                      << thick << " | " << sigma;
            if (int(f.members.size()) != K) {
              std::cout << " | " << f.members.size() << " slices | | | | | | | | |\n";
              continue;
            }
            for (bool smooth : {false, true}) {
              SliceFitOptions o;
              o.smooth_span = smooth;
              const SlicedFit fit = fit_sliced_scan(s.P, f, o);
              const auto [surface_rms, surface_max] = surface_error(fit, radial, thick, 4000, 7);
              const auto [rms, mx] = section_error(fit, s, radial, thick);
              std::cout << " | " << surface_rms << " | " << surface_max << " | " << rms << " | "
                        << mx;
              if (smooth)
                std::cout << " | " << fit.sections.front().control << " x " << fit.span_control;
            }
            std::cout << " |\n";
          }
}

// Measurement, not a test (hidden tag; docs/benchmarks.md, "Sectioned scans: uneven spacing and
// other span laws"): the loft's distance from the true surface (3000 random points) with the
// sections fitted one by one and smoothed along the span, over scans the families above do not
// cover: three span laws (profile), slices evenly spaced, denser at the root (t = x^2) or
// jittered by up to 0.3 of the mean spacing, 5 to 17 planar slices of 150 or 600 points,
// thickness 0.05 and 0.2, noise 0.001 and 0.005. Rows whose slices are not all found (the closest
// two less than 3 sigma apart) say so.
TEST_CASE("sectioned scans: smoothing along the span on uneven spacing and other span laws",
          "[.measure][clouds][slices]") {
  std::cout << "| law | spacing | slices | points | thickness | sigma | one by one: surface rms | "
               "max | smoothed: surface rms | max | control points |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (int law : {0, 1, 2})
    for (int spacing : {0, 1, 2})
      for (int K : {5, 9, 17})
        for (int per : {150, 600})
          for (double thick : {0.05, 0.2})
            for (double sigma : {0.001, 0.005}) {
              const unsigned seed = unsigned(17 + K + per + 7 * law + 3 * spacing);
              std::mt19937 rng(seed);
              std::uniform_real_distribution<double> U(-0.3, 0.3);
              std::vector<double> t;
              for (int k = 0; k < K; ++k) {
                const double x = double(k) / (K - 1);
                t.push_back(spacing == 0   ? x
                            : spacing == 1 ? x * x
                                           : (k == 0 || k == K - 1 ? x : x + U(rng) / (K - 1)));
              }
              const Scan s = scan(false, t, per, sigma, thick, seed, law);
              const SliceFamily f = detect_slices(s.P, SliceKind::planar);
              std::cout << "| " << law << " | "
                        << (spacing == 0   ? "even"
                            : spacing == 1 ? "root"
                                           : "jittered")
                        << " | " << K << " | " << per << " | " << thick << " | " << sigma;
              if (int(f.members.size()) != K) {
                std::cout << " | " << f.members.size() << " slices | | | | |\n";
                continue;
              }
              for (bool smooth : {false, true}) {
                SliceFitOptions o;
                o.smooth_span = smooth;
                const SlicedFit fit = fit_sliced_scan(s.P, f, o);
                const auto [rms, mx] = surface_error(fit, false, thick, 3000, 7, law);
                std::cout << " | " << rms << " | " << mx;
                if (smooth)
                  std::cout << " | " << fit.sections.front().control << " x " << fit.span_control;
              }
              std::cout << " |\n";
            }
}

// Smoothing along the span: on 16 noisy slices of a smoothly twisted, tapered body, the sections
// become isocurves of one surface, and the loft comes closer to the true surface than the loft of
// the sections fitted one by one (the family's geometric means are 0.40 of the rms and 0.35 of
// the max, docs/benchmarks.md).
TEST_CASE("sectioned scans: smoothing along the span brings the loft closer to the true surface",
          "[clouds][slices]") {
  for (bool radial : {false, true}) {
    const Scan s = scan(radial, 16, 400, 0.004, 0.1, 5);
    const auto [a, b] = alone_and_smoothed(s, radial, 16);
    const auto [ar, am] = surface_error(a, radial, 0.1, 2000, 3);
    const auto [br, bm] = surface_error(b, radial, 0.1, 2000, 3);
    const auto [sr, sm] = section_error(b, s, radial, 0.1);
    INFO("radial " << radial << ": surface rms " << ar << " -> " << br << ", max " << am << " -> "
                   << bm << "; sections rms " << sr << ", max " << sm << "; control points "
                   << b.sections.front().control << " x " << b.span_control);
    CHECK(a.span_control == 0);
    CHECK(b.span_control >= 4);
    CHECK(b.span_control <= 16);
    // measured 0.55 / 0.52 (rms) and 0.90 / 0.41 (max) of the sections' loft, planar / radial
    CHECK(br <= 0.7 * ar);
    CHECK(bm <= 0.95 * am);
    CHECK(sr <= 0.3 * 0.004);
    // one knot vector for all sections, and the loft still contains them
    for (const FittedSection& fs : b.sections)
      CHECK(fs.curve.knots == b.sections.front().curve.knots);
    CHECK(b.loft.max_deviation <= 1e-9 * b.loft.bbox_diagonal);
    CHECK(b.section_gap <= 1e-9 * b.loft.bbox_diagonal);
  }
}

// A thin profile (0.04 of the chord, nose radius about 0.0016) scanned without noise at 400 points
// per slice: a point's foot started from its neighbour's can sit on the far side, about one
// thickness off. Before closest_parameters searched globally, such feet inflated the sections'
// RSS, so a net that oscillated at the nose won on C_p: its sections' max error was 0.008, 33x
// the sections fitted alone (0.00025). Measured now: the sections alone 0.00011 (their own feet
// are global too), and C_p keeps them, planar and radial.
TEST_CASE("sectioned scans: smoothing along the span keeps a noise-free thin profile's nose",
          "[clouds][slices]") {
  for (bool radial : {false, true}) {
    const Scan s = scan(radial, 8, 400, 0.0, 0.04, 31);
    const auto [a, b] = alone_and_smoothed(s, radial, 8);
    const auto [ar, am] = section_error(a, s, radial, 0.04);
    const auto [br, bm] = section_error(b, s, radial, 0.04);
    INFO("radial " << radial << ": sections rms " << ar << " -> " << br << ", max " << am << " -> "
                   << bm << "; control points " << b.sections.front().control << " x "
                   << b.span_control);
    // the sections alone: the nose's few points bound the max (measured 0.00011 both ways)
    CHECK(am <= 2.5e-4);
    CHECK(br <= ar);
    CHECK(bm <= 1.25 * am);
  }
}

// A body whose sections do not follow one smooth law along the span (the chord alternates by
// 15 % from slice to slice): smoothing must not cost accuracy; C_p keeps the sections apart or
// takes a spanwise count that follows the jumps.
TEST_CASE("sectioned scans: smoothing along the span costs nothing on alternating sections",
          "[clouds][slices]") {
  for (bool radial : {false, true}) {
    Scan s = scan(radial, 12, 400, 0.002, 0.1, 8);
    for (Index i = 0; i < s.P.rows(); ++i) {
      const Index k = i / 400;
      if (k % 2 == 1) { // scale the profile coordinates about the axis by 1.15
        Eigen::Vector3d p = s.P.row(i).transpose();
        if (radial) {
          const double r = std::hypot(p(0), p(1)), a = std::atan2(p(1), p(0)) * 1.15;
          p << r * std::cos(a), r * std::sin(a), 1.15 * p(2);
        } else {
          p(1) *= 1.15, p(2) *= 1.15;
        }
        s.P.row(i) = p.transpose();
      }
    }
    const auto [a, b] = alone_and_smoothed(s, radial, 12);
    double worst_a = 0, worst_b = 0;
    for (size_t k = 0; k < a.sections.size(); ++k) {
      worst_a = std::max(worst_a, a.sections[k].rms);
      worst_b = std::max(worst_b, b.sections[k].rms);
    }
    INFO("radial " << radial << ": largest rms residual " << worst_a << " -> " << worst_b
                   << "; spanwise control points " << b.span_control);
    // measured: C_p keeps the sections apart (span_control 0) and the residuals agree to 3 %
    // (the smoothing step measures them at the points' feet)
    CHECK(worst_b <= 1.05 * worst_a);
  }
}
