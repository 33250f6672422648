// Spanwise accuracy on the analytic blade family (tests/support/analytic_blades.h) against
// OpenCASCADE ThruSections, in one run (docs/benchmarks.md, "Spanwise model on analytic
// blades"). For every case: the default loft (span parameters and degree chosen by
// leave-one-out), every fixed span option, and OCCT ThruSections of the same sections; the error
// between sections is the exact distance of true surface points at the middle of each gap
// between stations, by project_to_surface for every surface (OCCT's evaluated by OCCT through
// occt_parametric).
//
// Usage: blade_family [--cases N] [--family F] [--all-degrees] [--csv FILE] [--check]
//   prints a Markdown table per case and a summary; --family F runs the fresh family F >= 1
//   (analytic_blades.h: its own draws and section counts) instead of the reference family 0;
//   --all-degrees adds the fixed options of every degree 2 to #sections - 1 (default 3, 5 and
//   #sections - 1); --csv writes one row per case and model (leave-one-out and between-section
//   errors) for studying the choice rule; --check verifies the projections of the default and
//   OCCT surfaces from a finer start grid.

#include "occt_loft.h"

#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/loft.h"

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

Error between_error(const test::BladeCase& c, const LoftResult& loft) {
  const PiecewiseSurface S = to_piecewise(loft.surface);
  return error_of(test::between_distances(c, parametric(S)));
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

int run(int cases, int family, bool all_degrees, const char* csv_path, bool check) {
  double excess = 0;
  for (Message_SequenceOfPrinters::Iterator it(Message::DefaultMessenger()->Printers()); it.More();
       it.Next())
    it.Value()->SetTraceLevel(Message_Fail);
  FILE* csv = csv_path ? std::fopen(csv_path, "w") : nullptr;
  if (csv)
    std::fprintf(csv, "case,K,stacking,model,loo_max,loo_rms,between_max,between_rms\n");
  double worst_occt_max = 0, worst_occt_rms = 0, worst_fixed_max = 0, worst_fixed_rms = 0;
  std::printf("| case | default model | LOO max | between max / rms | / OCCT (max, rms) | / best "
              "fixed (max, rms) | best fixed |\n|---|---|---|---|---|---|---|\n");
  for (int i = 0; i < cases; ++i) {
    const test::BladeCase c = test::blade_case(i, 120, family);
    const int K = static_cast<int>(c.sections.size());
    const LoftResult def = loft_sections(c.sections);
    std::vector<Row> rows;
    rows.push_back({"default", def.span.used, between_error(c, def)});
    if (check) {
      const PiecewiseSurface ps = to_piecewise(def.surface);
      const double e =
          projection_excess(test::between_distances(c, parametric(ps)), parametric(ps), c.between);
      excess = std::max(excess, e);
    }
    for (SpanParameters p : {SpanParameters::station, SpanParameters::chord,
                             SpanParameters::centripetal, SpanParameters::uniform})
      for (int q = 2; q < K; ++q) {
        if ((!all_degrees && q != 3 && q != 5 && q != K - 1) ||
            (p == SpanParameters::station && def.span.stations.stacking == Stacking::none))
          continue;
        LoftOptions o;
        o.span = p;
        o.span_degree = q;
        const LoftResult r = loft_sections(c.sections, o);
        rows.push_back({label(p, q), r.span.used, between_error(c, r)});
      }
    std::vector<TopoDS_Wire> wires;
    for (const Section& s : c.sections)
      wires.push_back(bench::occt_section_wire(s.points));
    const ParametricSurface occt_surface =
        bench::occt_parametric(bench::occt_first_surface(bench::occt_thru_sections(wires)));
    const Eigen::VectorXd occt_distance = test::between_distances(c, occt_surface);
    const Error occt = error_of(occt_distance);
    if (check) {
      const double e = projection_excess(occt_distance, occt_surface, c.between);
      excess = std::max(excess, e);
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
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  int cases = test::kBladeCases, family = 0;
  const char* csv = nullptr;
  bool check = false, all_degrees = false;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--check"))
      check = true;
    else if (!std::strcmp(argv[a], "--all-degrees"))
      all_degrees = true;
    else if (!std::strcmp(argv[a], "--family") && a + 1 < argc)
      family = std::atoi(argv[++a]);
    else if (!std::strcmp(argv[a], "--cases") && a + 1 < argc)
      cases = std::atoi(argv[++a]);
    else if (!std::strcmp(argv[a], "--csv") && a + 1 < argc)
      csv = argv[++a];
  }
  try {
    return run(cases, family, all_degrees, csv, check);
  } catch (const Standard_Failure& e) {
    std::fprintf(stderr, "blade_family: OpenCASCADE: %s\n", e.GetMessageString());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "blade_family: %s\n", e.what());
  }
  return 1;
}
