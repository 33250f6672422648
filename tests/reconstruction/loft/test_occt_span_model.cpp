// The default spanwise model (leave-one-out choice, span_model.h) on the analytic blade family
// (support/analytic_blades.h: six twist/taper/lean/sweep laws, sections on planes, cylinders or
// cones, even, cosine-clustered or hub-clustered stations, 5, 7 or 10 sections, 40 to 140 points
// per section with their own clustering) against OpenCASCADE ThruSections of the same sections,
// in the same run. The error between sections is the exact distance of true surface points at
// the middle of each gap (between_distances, the same code for both surfaces). For run time the
// test takes 36 of the 54 blades: every law with every spacing for two of the three section
// counts (bench/blade_family runs all 54).
//
// Bounds: the per-case targets of issue 9 (at most 1.0 x OCCT in max and rms on every blade,
// within 10 % of every fixed option) are not reachable by any choice among the span options on
// this family: on 11 of the 54 blades OCCT beats every one of the 12 fixed options in max or
// rms, and on 14 no option meets both targets at once (docs/benchmarks.md, "Spanwise model on
// analytic blades", has the table of one run of bench/blade_family and the evidence). What is
// asserted is what one run measured on these 36 blades, with the margin stated at each bound:
// exact on every input section, the worst ratio to OCCT, the number of blades at or below OCCT,
// the geometric means against OCCT and against the previous fixed default (centripetal, cubic).

#include "occt_loft.h"

#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"
#include "interlin/splines/parameterization.h"

#include "support/analytic_blades.h"

#include <catch2/catch.hpp>

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <gp_Pnt.hxx>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace interlin;

namespace {

#ifdef INTERLIN_SANITIZED
constexpr bool kSanitized = true; // ASan + UBSan build: every 4th case (run time ~10x)
#else
constexpr bool kSanitized = false;
#endif

struct Error {
  double max = 0, rms = 0;
};

Error error_of(const Eigen::VectorXd& d) {
  return {d.maxCoeff(), std::sqrt(d.squaredNorm() / static_cast<double>(d.size()))};
}

Error loft_error(const test::BladeCase& c, const LoftResult& r) {
  const PiecewiseSurface S = to_piecewise(r.surface);
  return error_of(test::between_distances(c, parametric(S)));
}

Error occt_error(const test::BladeCase& c) {
  std::vector<TopoDS_Wire> wires;
  for (const Section& s : c.sections)
    wires.push_back(bench::occt_section_wire(s.points));
  return error_of(test::between_distances(
      c, bench::occt_parametric(bench::occt_first_surface(bench::occt_thru_sections(wires)))));
}

double geometric_mean(const std::vector<double>& x) {
  double s = 0;
  for (double v : x)
    s += std::log(v);
  return std::exp(s / static_cast<double>(x.size()));
}

} // namespace

TEST_CASE("Analytic blade family: the default span model against OpenCASCADE ThruSections",
          "[occt][span]") {
  for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More();
       it.Next())
    it.Value()->SetTraceLevel(Message_Fail);
  LoftOptions previous; // the default before issue 9
  previous.span = SpanParameters::centripetal;
  previous.span_degree = 3;
  std::vector<double> vs_occt, vs_previous;
  int better_than_occt = 0;
  for (int i = 0; i < test::kBladeCases; ++i) {
    if ((i % 6 + i / 18) % 3 == 2) // law i % 6 skips the section count of block i / 18
      continue;
    if (kSanitized && i % 4 != 0) // the instrumented build checks memory, not the statistics
      continue;
    const test::BladeCase c = test::blade_case(i);
    INFO(c.name);
    const LoftResult r = loft_sections(c.sections);
    // Exact on the input sections, as before: round-off of one interpolation per direction.
    CHECK(r.max_deviation <= 1e-12 * r.bbox_diagonal);
    CHECK(r.span.chosen);
    const Error d = loft_error(c, r), o = occt_error(c),
                p = loft_error(c, loft_sections(c.sections, previous));
    const double ratio = std::max(d.max / o.max, d.rms / o.rms);
    INFO("default " << to_string(r.span.used.parameters) << " " << r.span.used.degree << ": max "
                    << d.max << " rms " << d.rms << "; OCCT max " << o.max << " rms " << o.rms);
    // Measured worst 1.87 (blade #35: a tie between degrees 5 and 6 that leave-one-out cannot
    // break; OCCT's degree-6 polynomial is closer); 1.9 leaves room for round-off, not for a
    // worse choice.
    CHECK(ratio <= 1.9);
    better_than_occt += ratio <= 1.0;
    vs_occt.push_back(ratio);
    vs_previous.push_back(std::max(d.max / p.max, d.rms / p.rms));
  }
  // Measured on these 36 blades (station, chord or uniform by leave-one-out): 24 at or below OCCT
  // in both max and rms, geometric mean of the worse of the two ratios 0.416; against the
  // previous default (centripetal, cubic) 0.544 (bench/blade_family on all 54: 40, 0.431 and
  // 0.543). The counts are exact on this platform (the choice is deterministic); the means get
  // 2 % for round-off in the distances.
  if (kSanitized)
    return;
  CHECK(better_than_occt >= 24);
  CHECK(geometric_mean(vs_occt) <= 0.425);
  CHECK(geometric_mean(vs_previous) <= 0.555);
}

TEST_CASE("occt_curve carries an interlin curve to OCCT unchanged", "[occt][loft]") {
  // A closed cubic through 12 points of an ellipse, clamped at its start (as the loft's).
  Eigen::MatrixXd P(12, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double t = 2 * M_PI * static_cast<double>(i) / 12.0 + 0.1 * std::sin(i);
    P.row(i) << 2 * std::cos(t), std::sin(t), 0.3 * std::sin(2 * t);
  }
  const BSplineCurve C =
      periodic_to_clamped(interpolate_closed(P, chord_parameters(P, true, 1.0), 3), 0.0);
  const Handle(Geom_BSplineCurve) O = bench::occt_curve(C);
  const Eigen::VectorXd u = Eigen::VectorXd::LinSpaced(50, 0, 1);
  const Eigen::MatrixXd X = evaluate(C, u);
  for (Eigen::Index i = 0; i < u.size(); ++i) {
    const gp_Pnt q = O->Value(u(i));
    CHECK((X.row(i) - Eigen::RowVector3d(q.X(), q.Y(), q.Z())).norm() <= 1e-14 * 3);
  }
  // The points on the curve are at distance 0 from it (round-off of the projector).
  CHECK(bench::occt_curve_distances(O, X).maxCoeff() <= 1e-9);
}

TEST_CASE("Analytic blade family: interlin's section curves against OCCT's at the stations",
          "[occt][loft]") {
  // The error of the section curves alone: true profile points between the input points of
  // every section, to interlin's loft at v = v_k (its section curve: chord-length periodic
  // cubic, C2 at the seam) and to OCCT's GeomAPI_Interpolate (the curve ThruSections lofts:
  // chord-length cubic, C1 at the seam with a tangent from a cubic through the first 4 points).
  // Six blades with 5 sections, one per law. Measured (7 points per gap, bench/blade_family
  // --section-curves): the geometric mean of interlin / OCCT over 53 of the 54 reference blades
  // is 0.87 in max and 0.84 in rms, worst 1.26 (docs/benchmarks.md "Where OCCT is closer"); on
  // these six 0.86 and 0.85 (3 points per gap, this test). The bounds leave 10 % for round-off
  // and the projector; a worse section interpolant fails them.
  std::vector<double> ratio_max, ratio_rms;
  for (int i = 0; i < (kSanitized ? 2 : 6); ++i) {
    const test::BladeCase c = test::blade_case(i);
    INFO(c.name);
    LoftOptions o;
    o.span = SpanParameters::chord;
    o.span_degree = 3;
    o.span_holdout = false; // the section curves do not depend on the span model
    const LoftResult r = loft_sections(c.sections, o);
    std::vector<double> ours, occt;
    for (size_t k = 0; k < c.sections.size(); ++k) {
      const Eigen::MatrixXd P = test::points_between_inputs(c, k, 4);
      const Eigen::VectorXd a = bench::occt_curve_distances(
          bench::occt_curve(test::iso_curve_at(r.surface, r.section_v(Eigen::Index(k)))), P);
      const Eigen::VectorXd b =
          bench::occt_curve_distances(bench::occt_section_curve(c.sections[k].points), P);
      ours.insert(ours.end(), a.begin(), a.end());
      occt.insert(occt.end(), b.begin(), b.end());
    }
    const auto err = [](const std::vector<double>& v) {
      return error_of(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())));
    };
    const Error e = err(ours), f = err(occt);
    INFO("interlin max " << e.max << " rms " << e.rms << "; OCCT max " << f.max << " rms "
                         << f.rms);
    // The same order of accuracy (both cubic, knots at the points): never far apart.
    CHECK(e.max <= 1.3 * f.max);
    CHECK(e.rms <= 1.3 * f.rms);
    ratio_max.push_back(e.max / f.max);
    ratio_rms.push_back(e.rms / f.rms);
  }
  if (kSanitized)
    return;
  CHECK(geometric_mean(ratio_max) <= 0.95);
  CHECK(geometric_mean(ratio_rms) <= 0.95);
}
