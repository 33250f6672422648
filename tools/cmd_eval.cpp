// interlin eval: an implicit model (.rf or .ifl) evaluated at the points of a CSV file.
#include "cli_common.h"
#include "commands.h"

#include "interlin/interflatation/load_implicit.h"

#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/points_csv.h"

#include <cstdio>
#include <iostream>

namespace interlin::cli {

const char* const kEvalHelp =
    R"(interlin eval - evaluate an implicit model at points

Usage: interlin eval MODEL POINTS.csv [options]

MODEL       an R-function model MODEL.rf (docs/formats.md, "R-function model files") or an
            implicit model file MODEL.ifl (`interlin implicit`; "Implicit model files");
            F > 0 inside, F = 0 on the surface, F < 0 outside
POINTS.csv  a CSV file with a header naming the columns x, y, z (any order, case-insensitive,
            other columns ignored), one point per row; '#' comment lines and blank lines are
            skipped

Output: CSV with the header x,y,z,F (x,y,z,F,Fx,Fy,Fz with --gradient), one row per input
point in input order, numbers with 17 significant digits; on stdout, or in the file of -o.

Options:
  --gradient             also print the gradient of F (.rf: exact, forward-mode dual numbers)
  --set NAME=VALUE       .rf: override a 'param NAME = ...;' of the model (repeatable)
  --var NAME             .rf: evaluate the variable NAME instead of res
  --max-model-size N     .rf: work the model may expand to: expression nodes, function calls,
                         Bezier samples (default 5000000)
  -o, --output FILE      write the CSV to FILE (written whole or not at all)
  -q, --quiet            no progress lines on stderr
  -h, --help             this help

Examples:
  interlin eval data/models/impeller.rf points.csv
  interlin eval data/models/uav.rf points.csv --gradient -o values.csv
  interlin eval data/models/car.rf points.csv --var fig5 --set xs=7
  interlin eval blade.ifl points.csv --gradient
)";

namespace {

void write_values(std::ostream& out, const Points3& P, const Eigen::VectorXd& F, const Points3* G) {
  out << (G ? "x,y,z,F,Fx,Fy,Fz\n" : "x,y,z,F\n");
  char buf[32];
  auto put = [&](double v, char end) {
    std::snprintf(buf, sizeof buf, "%.17g", v);
    out << buf << end;
  };
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    put(P(i, 0), ',');
    put(P(i, 1), ',');
    put(P(i, 2), ',');
    put(F(i), G ? ',' : '\n');
    if (G) {
      put((*G)(i, 0), ',');
      put((*G)(i, 1), ',');
      put((*G)(i, 2), '\n');
    }
  }
}

// The body of `interlin eval` (run_command handles help and exit statuses).
void eval_main(const ParsedArgs& a, std::vector<std::string>&) {
  if (a.positional.size() != 2)
    throw UsageError("expected MODEL POINTS.csv, got " + std::to_string(a.positional.size()) +
                     " argument(s) (see --help)");
  const std::string output = a.get("output");
  if (!output.empty())
    check_outputs(a.positional, {output});
  const ModelOptions mo = model_file_options(a, a.positional[0], SettingLabel::setting);
  const bool with_gradient = a.has("gradient");
  const Progress progress{a.has("quiet")};
  progress("reading " + a.positional[0]);
  const ImplicitFunction f = load_implicit(a.positional[0], mo);
  progress("reading " + a.positional[1]);
  const Points3 P = read_points_csv(a.positional[1]);
  progress("evaluating at " + std::to_string(P.rows()) + " points");
  Eigen::VectorXd F(P.rows());
  Points3 G(P.rows(), 3);
  if (with_gradient)
    f.gradient(P, F, G);
  else
    f.value(P, F);
  if (output.empty()) {
    write_values(std::cout, P, F, with_gradient ? &G : nullptr);
    std::cout.flush();
    if (!std::cout)
      throw std::runtime_error("cannot write to standard output");
  } else {
    write_file_atomically(
        output, [&](std::ostream& out) { write_values(out, P, F, with_gradient ? &G : nullptr); });
    progress("wrote " + output);
  }
}

} // namespace

int run_eval(int argc, const char* const* argv) {
  return run_command("eval", kEvalHelp, argc, argv,
                     {{"output", 'o', true, false},
                      {"gradient", 0, false, false},
                      {"set", 0, true, true},
                      {"var", 0, true, false},
                      {"max-model-size", 0, true, false}},
                     eval_main);
}

} // namespace interlin::cli
