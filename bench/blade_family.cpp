// Spanwise accuracy on the analytic blade family (tests/support/analytic_blades.h) against
// OpenCASCADE ThruSections, in one run (docs/benchmarks.md, "Spanwise model on analytic
// blades"). For every case: the default loft (span parameters and degree chosen by
// leave-one-out), every fixed span option, and OCCT ThruSections of the same sections; the error
// between sections is the exact distance of true surface points at the middle of each gap
// between stations, by project_to_surface for every surface (OCCT's evaluated by OCCT through
// occt_parametric).
//
// Usage: blade_family [--cases N | --only I,J,...] [--family F] [--all-degrees] [--csv FILE]
//                     [--check] [--section-exponent E] [--section-curves]
//                     [--pairs L1,L2,... --pairs-csv FILE]
//   prints a Markdown table per case and a summary; --cases N runs the first N cases, --only the
//   listed ones; --family F runs the fresh family F >= 1 (analytic_blades.h: its own draws and
//   section counts) instead of the reference family 0; --all-degrees adds the fixed options of
//   every degree 2 to #sections - 1 (default 3, 5 and #sections - 1); --csv writes one row per
//   case and model (leave-one-out and between-section errors) for studying the choice rule;
//   --check verifies the projections of the default and OCCT surfaces from a finer start grid;
//   --section-exponent E lofts with section parameters chord^E (LoftOptions::section_exponent,
//   default 1; 0.5 is `interlin loft --param centripetal`). --section-curves instead measures the
//   section curves alone at the input stations (no span model): interlin's, variants of its
//   closed interpolation, and OCCT's GeomAPI_Interpolate ("Where OCCT is closer"). --pairs
//   writes the pair study to FILE: for every case, every surface X (each fixed option and OCCT)
//   and every fraction L, a second truth with the same input points, the true points between
//   sections moved the fraction L of the way to their feet on X, and the error of every surface
//   against it ("No input-only rule meets both targets").

#include "occt_loft.h"

#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/knot_insertion.h"
#include "interlin/splines/parameterization.h"

#include "support/analytic_blades.h"

#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <Standard_Failure.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace interlin;

struct Error {
  double max = 0, rms = 0;
};

Error error_of(const Eigen::VectorXd& d) {
  return {d.maxCoeff(), std::sqrt(d.squaredNorm() / double(d.size()))};
}

// Every surface of a case with its feet of the true points between sections (the pair study
// measures against them again).
struct Surfaces {
  std::deque<PiecewiseSurface> pieces; // referenced by `surface` (a deque: stable addresses)
  std::vector<ParametricSurface> surface;
  std::vector<SurfaceProjection> feet;

  Error add(const test::BladeCase& c, const ParametricSurface& S) {
    surface.push_back(S);
    feet.push_back(test::between_projection(c, S));
    return error_of(feet.back().distance);
  }
  Error add(const test::BladeCase& c, const LoftResult& loft) {
    pieces.push_back(to_piecewise(loft.surface));
    return add(c, parametric(pieces.back()));
  }
};

// The pair study of one case (--pairs): surfaces 1 .. #-1 (0 is the default, one of the fixed
// options) are the targets X. For each X and fraction L the second truth moves each true point
// B_i between sections to Q_i = B_i + L (F_i - B_i), F_i its foot on X: it is smooth, has the
// same input points (X interpolates them), and B_i and Q_i lie on X's normal, s_i = L |F_i - B_i|
// apart. Every surface Z is measured against Q by Newton from its feet of B (Q is within s_i of
// B). One CSV row per (X, L, Z): Z's max and rms distance to Q, and the shift on the middle halves
// of the blade's sides (sin^2 t_i >= 1/2, t_i the profile angle; there the blade is a graph over
// X's normal on the scale of the errors, at the edges it is not): its max, and the root of its
// sum of squares over all #B points (the rms of s with the edges' shifts set to 0).
void pair_study(FILE* out, int index, const test::BladeCase& c,
                const std::vector<std::string>& names, const Surfaces& s,
                const std::vector<double>& fractions) {
  Eigen::VectorXd side(c.between.rows());
  for (Eigen::Index i = 0; i < side.size(); ++i)
    side(i) = std::pow(std::sin(c.between_t(i % c.samples)), 2) >= 0.5 ? 1.0 : 0.0;
  for (size_t x = 1; x < s.surface.size(); ++x) {
    const SurfaceProjection& fx = s.feet[x];
    for (double L : fractions) {
      const Eigen::MatrixXd Q = c.between + L * (fx.foot - c.between);
      const Error moved = error_of(L * side.cwiseProduct(fx.distance));
      for (size_t z = 0; z < s.surface.size(); ++z) {
        const Error e = error_of(project_from(s.surface[z], Q, s.feet[z].u, s.feet[z].v).distance);
        std::fprintf(out, "%d,%d,%s,%.3g,%s,%.6g,%.6g,%.6g,%.6g\n", index,
                     static_cast<int>(c.sections.size()), names[x].c_str(), L, names[z].c_str(),
                     e.max, e.rms, moved.max, moved.rms);
      }
    }
  }
  std::fflush(out);
}

FILE* open_for_writing(const char* path) {
  FILE* f = std::fopen(path, "w");
  if (!f)
    throw std::runtime_error(std::string(path) + ": cannot be written");
  return f;
}

struct Row {
  std::string model;
  SpanCandidate span;
  Error between;
};

std::string label(SpanParameters p, int q) {
  return to_string(p) + " " + std::to_string(q);
}

// The check of the projections: the same distances from a 4x finer start grid with twice the
// starts; the largest amount by which the measured distance exceeds it (0: no closer foot).
double projection_excess(const Eigen::VectorXd& measured, const ParametricSurface& S,
                         const Eigen::MatrixXd& P) {
  return (measured - project_to_surface(S, P, 2048, 512, 64).distance).maxCoeff();
}

// A section curve variant of the --section-curves study: closed interpolation of degree
// `degree` with section parameters chord^exponent (interlin's periodic interpolant).
struct CurveVariant {
  std::string name;
  double exponent;
  int degree;
  bool arc_length = false; // parameters: arc length along the first interpolant
  bool midpoints = false;  // chord-length sites plus the midpoints of the first interpolant
};

// The closed cubic through P at chord-length sites u and, between consecutive points, at the mid
// sites (u_i + u_i+1) / 2 through the parametric midpoints of C (sites s, #P + 1).
BSplineCurve with_midpoints(const Eigen::MatrixXd& P, const BSplineCurve& C,
                            const Eigen::VectorXd& s, const Eigen::VectorXd& u) {
  const Eigen::Index n = P.rows();
  Eigen::VectorXd mid_s(n), sites(2 * n + 1);
  for (Eigen::Index i = 0; i < n; ++i)
    mid_s(i) = 0.5 * (s(i) + s(i + 1));
  const Eigen::MatrixXd M = evaluate(C, mid_s);
  Eigen::MatrixXd Q(2 * n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    Q.row(2 * i) = P.row(i);
    Q.row(2 * i + 1) = M.row(i);
    sites(2 * i) = u(i);
    sites(2 * i + 1) = 0.5 * (u(i) + u(i + 1));
  }
  sites(2 * n) = 1;
  return periodic_to_clamped(interpolate_closed(Q, sites, 3), 0.0);
}

// Normalised arc length of the closed curve C at its sites u (#P + 1, the last closing the loop),
// by the trapezoidal rule on |C'| with 32 steps per interval.
Eigen::VectorXd arc_length_at(const BSplineCurve& C, const Eigen::VectorXd& u) {
  Eigen::VectorXd s = Eigen::VectorXd::Zero(u.size());
  for (Eigen::Index i = 1; i < u.size(); ++i) {
    const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(33, u(i - 1), u(i));
    const Eigen::VectorXd speed = evaluate(C, t, 1).rowwise().norm();
    s(i) = s(i - 1) + (speed.sum() - 0.5 * (speed(0) + speed(32))) * (u(i) - u(i - 1)) / 32;
  }
  return s / s(s.size() - 1);
}

// --section-curves: the error of the section curves alone at the input stations: interlin's
// loft (its iso-curves there), variants of interlin's closed interpolation, and OCCT's
// GeomAPI_Interpolate (the curves ThruSections lofts), all measured by
// GeomAPI_ProjectPointOnCurve at true profile points between the input points.
int run_section_curves(const std::vector<int>& cases, int family) {
  const std::vector<CurveVariant> variants = {
      {"chord 3", 1.0, 3},
      {"centripetal 3", 0.5, 3},
      {"chord 5", 1.0, 5},
      {"arc length of centripetal 3", 0.5, 3, true},
      {"chord sites + centripetal midpoints", 0.5, 3, false, true}};
  std::printf("| case | loft (max / rms) |");
  for (const CurveVariant& v : variants)
    std::printf(" %s |", v.name.c_str());
  std::printf(" OCCT | loft / OCCT (max, rms) |\n|---|---|");
  for (size_t v = 0; v < variants.size() + 2; ++v)
    std::printf("---|");
  std::printf("\n");
  std::vector<double> log_max(variants.size() + 1), log_rms(variants.size() + 1);
  std::vector<double> worst(variants.size() + 1);
  std::vector<int> worse(variants.size() + 1);
  for (int i : cases) {
    const test::BladeCase c = test::blade_case(i, 120, family);
    LoftOptions o;
    o.span = SpanParameters::chord;
    o.span_degree = 3;
    o.span_holdout = false; // the section curves do not depend on the span model
    const LoftResult r = loft_sections(c.sections, o);
    std::vector<std::vector<double>> d(variants.size() + 2);
    const auto add = [&](size_t j, const Eigen::VectorXd& e) {
      d[j].insert(d[j].end(), e.begin(), e.end());
    };
    for (size_t k = 0; k < c.sections.size(); ++k) {
      const Eigen::MatrixXd& S = c.sections[k].points;
      const Eigen::MatrixXd P = test::points_between_inputs(c, k, 8);
      add(0, bench::occt_curve_distances(bench::occt_curve(test::iso_curve_at(
                                             r.surface, r.section_v(static_cast<Eigen::Index>(k)))),
                                         P));
      for (size_t v = 0; v < variants.size(); ++v) {
        Eigen::VectorXd u = chord_parameters(S, true, variants[v].exponent);
        BSplineCurve C = periodic_to_clamped(interpolate_closed(S, u, variants[v].degree), 0.0);
        if (variants[v].midpoints)
          C = with_midpoints(S, C, u, chord_parameters(S, true, 1.0));
        if (variants[v].arc_length) {
          u = arc_length_at(C, u);
          C = periodic_to_clamped(interpolate_closed(S, u, variants[v].degree), 0.0);
        }
        add(v + 1, bench::occt_curve_distances(bench::occt_curve(C), P));
      }
      add(variants.size() + 1, bench::occt_curve_distances(bench::occt_section_curve(S), P));
    }
    std::vector<Error> e;
    for (const std::vector<double>& x : d)
      e.push_back(error_of(Eigen::Map<const Eigen::VectorXd>(x.data(), Eigen::Index(x.size()))));
    const Error& occt = e.back();
    std::printf("| %s |", c.name.c_str());
    for (size_t j = 0; j + 1 < e.size(); ++j) {
      std::printf(" %.3g / %.3g |", e[j].max, e[j].rms);
      log_max[j] += std::log(e[j].max / occt.max);
      log_rms[j] += std::log(e[j].rms / occt.rms);
      worst[j] = std::max({worst[j], e[j].max / occt.max, e[j].rms / occt.rms});
      worse[j] += e[j].max > occt.max || e[j].rms > occt.rms;
    }
    std::printf(" %.3g / %.3g | %.3f, %.3f |\n", occt.max, occt.rms, e[0].max / occt.max,
                e[0].rms / occt.rms);
    std::fflush(stdout);
  }
  std::printf("\n| section curves | / OCCT, geometric mean (max, rms) | worst / OCCT | worse "
              "than OCCT (max or rms) |\n|---|---|---|---|\n");
  for (size_t j = 0; j < log_max.size(); ++j)
    std::printf("| %s | %.3f, %.3f | %.3f | %d of %d |\n",
                j == 0 ? "loft (chord 3)" : variants[j - 1].name.c_str(),
                std::exp(log_max[j] / double(cases.size())),
                std::exp(log_rms[j] / double(cases.size())), worst[j], worse[j], int(cases.size()));
  return 0;
}

void quiet_occt() {
  for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More();
       it.Next())
    it.Value()->SetTraceLevel(Message_Fail);
}

int run(const std::vector<int>& cases, int family, bool all_degrees, const char* csv_path,
        bool check, double section_exponent, const std::vector<double>& fractions,
        const char* pairs_path) {
  double excess = 0;
  FILE* csv = csv_path ? open_for_writing(csv_path) : nullptr;
  if (csv)
    std::fprintf(csv, "case,K,stacking,model,loo_max,loo_rms,between_max,between_rms\n");
  FILE* pairs = pairs_path && !fractions.empty() ? open_for_writing(pairs_path) : nullptr;
  if (pairs)
    std::fprintf(pairs, "case,K,target,fraction,model,max,rms,shift_max,shift_rms\n");
  double worst_occt_max = 0, worst_occt_rms = 0, worst_fixed_max = 0, worst_fixed_rms = 0;
  std::printf("| case | default model | LOO max | between max / rms | / OCCT (max, rms) | / best "
              "fixed (max, rms) | best fixed |\n|---|---|---|---|---|---|---|\n");
  for (int i : cases) {
    const test::BladeCase c = test::blade_case(i, 120, family);
    const int K = static_cast<int>(c.sections.size());
    LoftOptions base;
    base.section_exponent = section_exponent;
    const LoftResult def = loft_sections(c.sections, base);
    Surfaces surfaces;
    std::vector<Row> rows;
    rows.push_back({"default", def.span.used, surfaces.add(c, def)});
    if (check)
      excess = std::max(
          excess, projection_excess(surfaces.feet[0].distance, surfaces.surface[0], c.between));
    for (SpanParameters p : {SpanParameters::station, SpanParameters::chord,
                             SpanParameters::centripetal, SpanParameters::uniform})
      for (int q = 2; q < K; ++q) {
        if ((!all_degrees && q != 3 && q != 5 && q != K - 1) ||
            (p == SpanParameters::station && def.span.stations.stacking == Stacking::none))
          continue;
        LoftOptions o = base;
        o.span = p;
        o.span_degree = q;
        const LoftResult r = loft_sections(c.sections, o);
        rows.push_back({label(p, q), r.span.used, surfaces.add(c, r)});
      }
    std::vector<TopoDS_Wire> wires;
    for (const Section& s : c.sections)
      wires.push_back(bench::occt_section_wire(s.points));
    const Error occt = surfaces.add(
        c, bench::occt_parametric(bench::occt_first_surface(bench::occt_thru_sections(wires))));
    if (check) {
      const double e =
          projection_excess(surfaces.feet.back().distance, surfaces.surface.back(), c.between);
      excess = std::max(excess, e);
    }
    if (pairs) {
      std::vector<std::string> names;
      for (const Row& r : rows)
        names.push_back(r.model);
      names.push_back("occt");
      pair_study(pairs, i, c, names, surfaces, fractions);
    }
    if (csv) {
      for (const Row& r : rows)
        std::fprintf(csv, "%d,%d,%s,%s,%.6g,%.6g,%.6g,%.6g\n", i, K,
                     to_string(def.span.stations.stacking).c_str(), r.model.c_str(), r.span.loo_max,
                     r.span.loo_rms, r.between.max, r.between.rms);
      std::fprintf(csv, "%d,%d,%s,occt,,,%.6g,%.6g\n", i, K,
                   to_string(def.span.stations.stacking).c_str(), occt.max, occt.rms);
      std::fflush(csv);
    }
    Error best{INFINITY, INFINITY};
    std::string best_name;
    for (size_t r = 1; r < rows.size(); ++r) {
      if (rows[r].between.max < best.max)
        best_name = rows[r].model;
      best.max = std::min(best.max, rows[r].between.max);
      best.rms = std::min(best.rms, rows[r].between.rms);
    }
    const Error& d = rows[0].between;
    worst_occt_max = std::max(worst_occt_max, d.max / occt.max);
    worst_occt_rms = std::max(worst_occt_rms, d.rms / occt.rms);
    worst_fixed_max = std::max(worst_fixed_max, d.max / best.max);
    worst_fixed_rms = std::max(worst_fixed_rms, d.rms / best.rms);
    std::printf("| %s | %s | %.3g | %.3g / %.3g | %.2f, %.2f | %.2f, %.2f | %s |\n", c.name.c_str(),
                label(def.span.used.parameters, def.span.used.degree).c_str(),
                def.span.used.loo_max, d.max, d.rms, d.max / occt.max, d.rms / occt.rms,
                d.max / best.max, d.rms / best.rms, best_name.c_str());
    std::fflush(stdout);
  }
  std::printf("\nworst default / OCCT: max %.3f, rms %.3f; worst default / best fixed option: max "
              "%.3f, rms %.3f\n",
              worst_occt_max, worst_occt_rms, worst_fixed_max, worst_fixed_rms);
  if (check)
    std::printf("projection check (default and OCCT surfaces): a 2048 x 512 start grid with 64 "
                "starts finds feet closer by at most %.3g\n",
                excess);
  if (csv)
    std::fclose(csv);
  if (pairs)
    std::fclose(pairs);
  return 0;
}

} // namespace

// The comma-separated numbers of an option's value ("0.5,0.75,1"); anything else is an error
// (strtod stops where it fails, so a loop that only skips commas would never end on "x").
std::vector<double> number_list(const char* option, const char* text) {
  std::vector<double> out;
  for (const char* p = text; *p;) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || (*end != '\0' && *end != ','))
      throw std::invalid_argument(std::string(option) + " '" + text +
                                  "': expected comma-separated numbers");
    out.push_back(v);
    p = end + (*end == ',');
  }
  return out;
}

int main(int argc, char** argv) {
  try {
    int family = 0;
    std::vector<int> cases;
    for (int i = 0; i < test::kBladeCases; ++i)
      cases.push_back(i);
    double section_exponent = LoftOptions{}.section_exponent;
    const char* csv = nullptr;
    const char* pairs_csv = nullptr;
    std::vector<double> fractions;
    bool check = false, all_degrees = false, section_curves = false;
    for (int a = 1; a < argc; ++a) {
      if (!std::strcmp(argv[a], "--check"))
        check = true;
      else if (!std::strcmp(argv[a], "--section-curves"))
        section_curves = true;
      else if (!std::strcmp(argv[a], "--all-degrees"))
        all_degrees = true;
      else if (!std::strcmp(argv[a], "--family") && a + 1 < argc)
        family = std::atoi(argv[++a]);
      else if (!std::strcmp(argv[a], "--cases") && a + 1 < argc)
        cases.resize(static_cast<size_t>(std::clamp(std::atoi(argv[++a]), 0, test::kBladeCases)));
      else if (!std::strcmp(argv[a], "--only") && a + 1 < argc) {
        cases.clear();
        for (double v : number_list("--only", argv[++a]))
          cases.push_back(static_cast<int>(v));
      } else if (!std::strcmp(argv[a], "--section-exponent") && a + 1 < argc)
        section_exponent = std::atof(argv[++a]);
      else if (!std::strcmp(argv[a], "--csv") && a + 1 < argc)
        csv = argv[++a];
      else if (!std::strcmp(argv[a], "--pairs-csv") && a + 1 < argc)
        pairs_csv = argv[++a];
      else if (!std::strcmp(argv[a], "--pairs") && a + 1 < argc)
        fractions = number_list("--pairs", argv[++a]);
    }
    if (!fractions.empty() && !pairs_csv)
      throw std::invalid_argument("--pairs needs --pairs-csv FILE");
    quiet_occt();
    return section_curves ? run_section_curves(cases, family)
                          : run(cases, family, all_degrees, csv, check, section_exponent, fractions,
                                pairs_csv);
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "blade_family: OpenCASCADE: %s\n", e.GetMessageString());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blade_family: %s\n", e.what());
  }
  return 1;
}
