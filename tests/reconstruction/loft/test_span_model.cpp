// The spanwise model: stations from the stack's geometry (parallel planes, coaxial surfaces of
// revolution), span parameters, the leave-one-out choice shared by plain and guided loft, and
// the exactness of its distances.
#include "interlin/interlineation/interlinate_curves.h"
#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/guided_loft.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/loft/span_parameters.h"

#include "cross_validate_span.h" // private: the folds exactly as cross-validation builds them

#include "support/analytic_blades.h"
#include "support/test_sections.h"

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using test::body_section;
using test::rotor37;

namespace {

std::vector<MatrixXd> points_of(const std::vector<Section>& s) {
  std::vector<MatrixXd> out;
  for (const Section& x : s)
    out.push_back(x.points);
  return out;
}

// The body's sections at heights z, each turned by the rotation R (a rigid motion of the stack).
std::vector<Section> turned_body(const std::vector<double>& z, const Eigen::Matrix3d& R) {
  std::vector<Section> out;
  for (size_t k = 0; k < z.size(); ++k) {
    Section s = body_section(z[k], 50 + 7 * static_cast<Index>(k), 0.3 * static_cast<double>(k));
    s.points = (s.points * R.transpose()).eval();
    out.push_back(s);
  }
  return out;
}

// Residual of the least-squares affine fit station = a + b s (0 for stations affine in s).
double affine_residual(const VectorXd& station, const std::vector<double>& s) {
  MatrixXd A(station.size(), 2);
  for (Index k = 0; k < station.size(); ++k)
    A.row(k) << 1.0, s[static_cast<size_t>(k)];
  const VectorXd c = A.colPivHouseholderQr().solve(station);
  return (A * c - station).cwiseAbs().maxCoeff();
}

// The whole fold without section j, as cross_validate builds it (interlineation of the other
// curves at the model's parameters of the whole stack), in explicit form over the whole span.
PiecewiseSurface fold_surface(const std::vector<BSplineCurve>& all, const VectorXd& v, size_t j,
                              int degree) {
  std::vector<BSplineCurve> curves = all;
  curves.erase(curves.begin() + static_cast<long>(j));
  VectorXd vj(v.size() - 1);
  vj << v.head(static_cast<Index>(j)), v.tail(v.size() - static_cast<Index>(j) - 1);
  return to_piecewise(interlinate_curves(curves, vj, degree, true));
}

// Four sections `step` apart, sheared out of their planes by a growing amount: neither planes
// nor surfaces of revolution, so a stack without stations.
std::vector<Section> sheared_stack(double step, Index points) {
  std::vector<Section> fan;
  for (int k = 0; k < 4; ++k) {
    Section s = body_section(step * k, points);
    for (Index i = 0; i < s.points.rows(); ++i)
      s.points(i, 2) += 0.05 * k * s.points(i, 0);
    fan.push_back(s);
  }
  return fan;
}

} // namespace

TEST_CASE("Stations of parallel planes: positions along the common normal, any orientation",
          "[span]") {
  const std::vector<double> z = {0.0, 0.05, 0.3, 0.9, 1.0};
  const Eigen::Matrix3d R =
      (Eigen::AngleAxisd(0.7, Vector3d(1, 2, 3).normalized())).toRotationMatrix();
  for (const Eigen::Matrix3d& turn : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), R}) {
    const SectionStations s = section_stations(points_of(turned_body(z, turn)));
    REQUIRE(s.stacking == Stacking::parallel_planes);
    // Exact planes: the normal and the stations to round-off of the point coordinates.
    CHECK(std::abs(std::abs(s.normal.dot(turn.col(2))) - 1) < 1e-12);
    for (Index k = 0; k < s.station.size(); ++k)
      CHECK(s.station(k) - s.station(0) ==
            Approx(z[static_cast<size_t>(k)]).epsilon(0).margin(1e-12));
    CHECK(s.spread < 1e-12);
  }
  // Reversed order: stations still increase from the first section to the last.
  std::vector<Section> down = turned_body(z, R);
  std::reverse(down.begin(), down.end());
  const SectionStations s = section_stations(points_of(down));
  CHECK(s.stacking == Stacking::parallel_planes);
  CHECK(s.station(4) - s.station(0) == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("Stations: tilted planes and warped stacks are not parallel planes", "[span]") {
  // Each section turned about x by a growing angle: the planes fan out; at the stack's spacing
  // 0.25 a tilt of 0.02 rad over a width of ~4 already moves a section's extent along the mean
  // normal beyond 1 % of the gap.
  std::vector<Section> fan;
  for (int k = 0; k < 5; ++k) {
    Section s = body_section(0.25 * k, 60);
    const Eigen::Matrix3d T = Eigen::AngleAxisd(0.02 * k, Vector3d::UnitX()).toRotationMatrix();
    s.points = (s.points * T.transpose()).eval();
    fan.push_back(s);
  }
  const SectionStations s = section_stations(points_of(fan));
  CHECK(s.stacking == Stacking::none);
  CHECK(s.spread > kStationSpread);
  CHECK(s.station.size() == 0);
  // Rotor 37: each section on its stream surface, not on a plane (the spread as planes is large),
  // and its two sides coincide in the meridional plane: coaxial surfaces of revolution about z.
  const SectionStations r = section_stations(points_of(rotor37()));
  CHECK(r.stacking == Stacking::coaxial_revolution);
  CHECK(r.spread < 1e-3); // the NASA table gives both sides at the same (Z, R) to 7 digits
  for (Index k = 1; k < r.station.size(); ++k)
    CHECK(r.station(k) > r.station(k - 1));
}

TEST_CASE("Stations of coaxial surfaces of revolution: cylinders and cones give the span",
          "[span]") {
  // Blades wrapped on cylinders R = R0 + L s and on cones R = R0 + L s + 0.25 z: the meridional
  // position is affine in the span fraction s exactly (a mean radius would not be on cones: it
  // moves with each section's axial extent).
  for (int index : {1, 2, 4, 5}) { // cylinders and cones (analytic_blades.h)
    const test::BladeCase c = test::blade_case(index);
    INFO(c.name);
    REQUIRE(c.blade.stacking != test::BladeStacking::planes);
    const SectionStations s = section_stations(points_of(c.sections));
    CHECK(s.stacking == Stacking::coaxial_revolution);
    CHECK(affine_residual(s.station, c.stations) < 1e-10);
  }
  // The planar blades of the family are found as planes with z as the station.
  const test::BladeCase p = test::blade_case(0);
  REQUIRE(p.blade.stacking == test::BladeStacking::planes);
  const SectionStations s = section_stations(points_of(p.sections));
  CHECK(s.stacking == Stacking::parallel_planes);
  CHECK(affine_residual(s.station, p.stations) < 1e-12);
}

TEST_CASE("span_parameters: stations, chord, centripetal and uniform spacing", "[span]") {
  const VectorXd d = (VectorXd(3) << 1.0, 4.0, 4.0).finished();
  const VectorXd st = (VectorXd(4) << 10.0, 10.5, 11.0, 12.0).finished();
  CHECK(span_parameters(SpanParameters::chord, d, st)
            .isApprox((VectorXd(4) << 0, 1.0 / 9, 5.0 / 9, 1).finished()));
  CHECK(span_parameters(SpanParameters::centripetal, d, st)
            .isApprox((VectorXd(4) << 0, 0.2, 0.6, 1).finished()));
  CHECK(span_parameters(SpanParameters::uniform, d, st)
            .isApprox((VectorXd(4) << 0, 1.0 / 3, 2.0 / 3, 1).finished()));
  CHECK(span_parameters(SpanParameters::station, d, st)
            .isApprox((VectorXd(4) << 0, 0.25, 0.5, 1).finished()));
  CHECK_THROWS(span_parameters(SpanParameters::station, d, VectorXd()));
  CHECK_THROWS(span_parameters(SpanParameters::automatic, d, st));
}

TEST_CASE("The default loft chooses its span model by leave-one-out, deterministically",
          "[span][loft]") {
  const LoftResult r = loft_sections(rotor37());
  const SpanModel& m = r.span;
  CHECK(m.chosen);
  CHECK(m.folds == 11);
  // station, chord, uniform x degrees 9 (#sections - 1 capped), 5, 3.
  REQUIRE(m.candidates.size() == 9);
  CHECK(m.candidates[0].parameters == SpanParameters::station);
  CHECK(m.candidates[0].degree == 9);
  CHECK(m.candidates[8].parameters == SpanParameters::uniform);
  CHECK(m.candidates[8].degree == 3);
  // The choice is the lowest leave-one-out maximum (the earliest of equals).
  for (const SpanCandidate& c : m.candidates) {
    CHECK(std::isfinite(c.loo_max));
    CHECK(m.used.loo_max <= c.loo_max);
  }
  CHECK(r.surface.degree_v == m.used.degree);
  // Exact as before, and the same bytes on a second run.
  CHECK(r.max_deviation <= 1e-13 * r.bbox_diagonal);
  const LoftResult again = loft_sections(rotor37());
  CHECK(again.surface.ctrl == r.surface.ctrl);
  CHECK(again.section_v == r.section_v);
  // A fixed model is one candidate, still with its leave-one-out error.
  LoftOptions fixed;
  fixed.span = SpanParameters::chord;
  fixed.span_degree = 5;
  const LoftResult f = loft_sections(rotor37(), fixed);
  CHECK_FALSE(f.span.chosen);
  REQUIRE(f.span.candidates.size() == 1);
  CHECK(f.span.used.parameters == SpanParameters::chord);
  CHECK(f.span.used.degree == 5);
  CHECK(f.span.used.loo_max > 0);
  // Only the degree fixed: the parameters are chosen among three.
  LoftOptions cubic;
  cubic.span_degree = 3;
  CHECK(loft_sections(rotor37(), cubic).span.candidates.size() == 3);
}

TEST_CASE("Without cross-validation (span_holdout false): the first candidate, no folds",
          "[span][loft]") {
  LoftOptions o;
  o.span_degree = 3;
  o.span_holdout = false;
  const LoftResult r = loft_sections(rotor37(), o);
  CHECK_FALSE(r.span.chosen);
  CHECK(r.span.folds == 0);
  CHECK(r.span.used.parameters == SpanParameters::station); // stream surfaces: the first choice
  CHECK(r.span.used.degree == 3);
  CHECK(std::isnan(r.span.used.loo_max));
  CHECK(std::isnan(r.span.used.loo_rms));
  // The same surface as the cross-validated loft of that one model (Rotor 37's default).
  LoftOptions fixed;
  fixed.span = SpanParameters::station;
  fixed.span_degree = 3;
  const LoftResult f = loft_sections(rotor37(), fixed);
  CHECK(f.span.folds == 11);
  CHECK(r.surface.ctrl == f.surface.ctrl);
  CHECK(r.section_v == f.section_v);
  // A stack without stations: chord, the next preference.
  CHECK(loft_sections(sheared_stack(0.5, 40), o).span.used.parameters == SpanParameters::chord);
}

TEST_CASE("Leave-one-out on dense sections: at most 256 points of each withheld section",
          "[span]") {
  // Sections of 1000 points (sectioned scans hand the loft 400 to 1000 samples per fitted
  // curve): every 4th is measured. Against all points (the same folds, a dense grid search):
  // never more, and the maximum within 1 % (measured: 2e-5 relative; the error varies smoothly
  // along a section).
  std::vector<Section> s;
  for (int k = 0; k < 6; ++k)
    s.push_back(body_section(0.2 * k * (1 + 0.3 * k), 1000, 0.2 * k));
  std::vector<std::string> notes;
  const std::vector<PreparedSection> prepared = prepare_sections(s, StartAlign::first, notes);
  LoftOptions o;
  o.span = SpanParameters::station;
  o.span_degree = 3;
  const detail::SectionCurves c =
      detail::section_curves(prepared, detail::edge_landmarks(prepared, o.align), o);
  const SpanModel m = detail::choose_span_model(prepared, c, o);
  const VectorXd v = span_parameters(
      SpanParameters::station, detail::neighbour_distances(c.curves, prepared), m.stations.station);
  double max = 0;
  for (size_t j = 1; j + 1 < s.size(); ++j) {
    const PiecewiseSurface S = fold_surface(c.curves, v, j, 3);
    max = std::max(max, project_to_surface(S, prepared[j].points, 512, 128, 8).distance.maxCoeff());
  }
  INFO("subsampled " << m.used.loo_max << ", all points " << max);
  CHECK(m.used.loo_max <= max + 1e-13);
  CHECK(m.used.loo_max >= 0.99 * max);
}

TEST_CASE("Ties: folds cannot tell degrees #sections-1 and #sections-2 apart, the higher wins",
          "[span]") {
  // 7 sections: each fold has 6, where degrees 6 and 5 are both the one quintic polynomial.
  std::vector<Section> s;
  for (int k = 0; k < 7; ++k)
    s.push_back(body_section(0.3 * k, 60));
  const LoftResult r = loft_sections(s);
  REQUIRE(r.span.candidates.size() == 9); // station, chord, uniform x 6, 5, 3
  for (size_t p = 0; p < 9; p += 3) {
    CHECK(r.span.candidates[p].degree == 6);
    CHECK(r.span.candidates[p].loo_max == r.span.candidates[p + 1].loo_max);
  }
  CHECK(r.span.used.degree != 5); // never the later of two equal candidates
}

TEST_CASE("Few sections: 2 sections have no interior section, 3 have one fold", "[span]") {
  const std::vector<Section> two = {body_section(0.0, 40), body_section(1.0, 50)};
  const LoftResult r2 = loft_sections(two);
  CHECK(r2.span.folds == 0);
  CHECK(std::isnan(r2.span.used.loo_max));
  CHECK(r2.span.used.parameters == SpanParameters::station); // planes: the first preference
  CHECK(r2.surface.degree_v == 1);
  const LoftResult r3 =
      loft_sections({body_section(0.0, 40), body_section(0.4, 45), body_section(1.0, 50)});
  CHECK(r3.span.folds == 1);
  CHECK(std::isfinite(r3.span.used.loo_max));
  CHECK(r3.max_deviation <= 1e-12 * r3.bbox_diagonal);
}

TEST_CASE("span = station needs stations: a warped stack is refused, naming the spread", "[span]") {
  const std::vector<Section> fan = sheared_stack(0.25, 60);
  LoftOptions o;
  o.span = SpanParameters::station;
  CHECK_THROWS_WITH(loft_sections(fan, o), Catch::Contains("span parameters 'station' need") &&
                                               Catch::Contains("x the smallest station gap"));
  CHECK_NOTHROW(loft_sections(fan)); // auto: chord and uniform only (4 sections: cubic)
  CHECK(loft_sections(fan).span.candidates.size() == 2);
}

TEST_CASE("Leave-one-out distances: the cross-validation's feet against a dense grid search",
          "[span][closest]") {
  // The folds exactly as cross_validate builds them (the loft's section curves and the model's
  // parameters of the whole stack without section j), section j's points projected by a dense
  // grid search over the whole surface (1024 x 256 samples, 16 starts), against
  // cross-validation's cheaper search (Newton from the points' own parameters and from the
  // nearest samples of a 256 x 8 grid on the band between the neighbouring sections).
  // Returns per model up to degree max_degree (dense max, dense rms).
  const auto folds = [](const std::vector<Section>& all, int max_degree) {
    std::vector<std::string> notes;
    const std::vector<PreparedSection> prepared = prepare_sections(all, StartAlign::first, notes);
    LoftOptions o;
    const detail::SectionCurves c =
        detail::section_curves(prepared, detail::edge_landmarks(prepared, o.align), o);
    const SpanModel m = detail::choose_span_model(prepared, c, o);
    std::vector<std::pair<SpanCandidate, Eigen::Vector2d>> out;
    for (const SpanCandidate& cand : m.candidates) {
      if (cand.degree > max_degree)
        continue;
      const VectorXd v = span_parameters(
          cand.parameters, detail::neighbour_distances(c.curves, prepared), m.stations.station);
      double max = 0, sum2 = 0;
      long count = 0;
      for (size_t j = 1; j + 1 < all.size(); ++j) {
        const PiecewiseSurface S = fold_surface(c.curves, v, j, cand.degree);
        const VectorXd d = project_to_surface(S, prepared[j].points, 1024, 256, 16).distance;
        max = std::max(max, d.maxCoeff());
        sum2 += d.squaredNorm();
        count += d.size();
      }
      out.push_back({cand, Eigen::Vector2d(max, std::sqrt(sum2 / double(count)))});
    }
    return out;
  };
  // Equal to round-off (distances ~1e-2 of coordinates ~20) where the folds stay closer to the
  // withheld sections than the blade is thick: Rotor 37 with stations or chord and degrees up
  // to 5, the analytic blade #26 with every model (its rms: below).
  for (const auto& [c, dense] : folds(rotor37(), 5)) {
    INFO("Rotor 37, " << to_string(c.parameters) << " " << c.degree);
    if (c.parameters == SpanParameters::uniform) { // as blade #10 below (measured +0.14 % rms)
      CHECK(c.loo_max >= dense(0) - 1e-13);
      CHECK(c.loo_rms >= dense(1) - 1e-13);
      CHECK(c.loo_rms <= 1.05 * dense(1));
      continue;
    }
    CHECK(c.loo_max == Approx(dense(0)).epsilon(0).margin(1e-13));
    CHECK(c.loo_rms == Approx(dense(1)).epsilon(0).margin(1e-13));
  }
  // Blade #26: the max to round-off, the rms to 1e-6 relative (with uniform spacing the two
  // searches' rms differ by 8e-8 relative, 2.3e-9: feet that differ below the max's point).
  for (const auto& [c, dense] : folds(test::blade_case(26).sections, kMaxAutoSpanDegree)) {
    INFO("blade 26, " << to_string(c.parameters) << " " << c.degree);
    CHECK(c.loo_max == Approx(dense(0)).epsilon(0).margin(1e-13));
    CHECK(c.loo_rms == Approx(dense(1)).epsilon(1e-6));
  }
  // Where a fold misses the withheld section by more than a thin edge is thick (blade #10: 0.02
  // at edge radii of ~1e-3; Rotor 37 with degree 9 or uniform spacing), a foot on the far side of
  // the edge can be closer than the band search finds: cross-validation then reports up to a few
  // per cent more (measured 2.5 % on the rms of blade #10's chosen model), never less than the
  // dense search.
  for (const auto& [c, dense] : folds(test::blade_case(10).sections, kMaxAutoSpanDegree)) {
    INFO("blade 10, " << to_string(c.parameters) << " " << c.degree);
    CHECK(c.loo_max >= dense(0) - 1e-13);
    CHECK(c.loo_rms >= dense(1) - 1e-13);
    CHECK(c.loo_rms <= 1.05 * dense(1));
  }
}

TEST_CASE("Plain and guided loft share the span model", "[span][guided]") {
  const GuidedLoftResult g = guided_loft(rotor37(), test::rotor37_edges(rotor37()));
  const LoftResult p = loft_sections(rotor37());
  CHECK(g.loft.span.used.parameters == p.span.used.parameters);
  CHECK(g.loft.span.used.degree == p.span.used.degree);
  CHECK(g.loft.span.used.loo_max == p.span.used.loo_max);
  CHECK(g.loft.surface.degree_v == p.surface.degree_v);
  CHECK(g.loft.section_v.isApprox(p.section_v, 1e-12)); // guides insert no point into Rotor 37
  GuidedLoftOptions go;
  go.loft.span = SpanParameters::centripetal;
  go.loft.span_degree = 3;
  const GuidedLoftResult f = guided_loft(rotor37(), test::rotor37_edges(rotor37()), go);
  CHECK(f.loft.span.used.parameters == SpanParameters::centripetal);
  CHECK(f.loft.surface.degree_v == 3);
}
