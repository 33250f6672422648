// interlin implicit: sections or an R-function model -> implicit model file (.ifl), whose
// omega vanishes exactly on the body's boundary and is close to the signed distance.
#include "cli_common.h"
#include "commands.h"

#include "interlin/interflatation/models/ifl_file.h"
#include "interlin/reconstruction/implicit/normalize_model.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/section_csv.h"

#include <functional>
#include <iostream>

namespace interlin::cli {

const char* const kImplicitHelp =
    R"(interlin implicit - sections or an R-function model -> implicit model file (.ifl)

Usage: interlin implicit INPUT -o MODEL.ifl [options]

INPUT, by kind:
  SECTIONS.csv  blade sections (docs/formats.md, "Section files"): the body whose boundary is
                the loft through every section (as `interlin loft` builds it), closed at hub
                and tip by ruled caps across the end sections
  MODEL.rf      an R-function model: the same zero set, normalised (closer to the distance)

Output: MODEL.ifl (docs/formats.md, "Implicit model files"), read by `interlin eval`,
`interlin mesh` and by ifl("MODEL.ifl") inside .rf models. Its function omega is 0 exactly on
the boundary (loft surface and caps, or the model's F = 0), > 0 inside, and the signed
distance to the boundary within the inner band (sections) or to first order (R-function
models); far from the boundary a tricubic interpolant of the exact signed distance.

Options:
  -o, --output FILE      the .ifl file to write (written whole or not at all)
  --resolution N         grid cells along the longest side of the box (default 96)
  --band INNER,OUTER     blend band in grid cells (default 1.5,3): exact near field within
                         INNER, far field beyond OUTER
  --margin M             sections: box = body bounding box + M x its diagonal (default 0.05)
  --mesh-resolution N    R-function models: cells of the mesh of F = 0 whose distances make
                         the far field (default 2 x resolution, at least 128)
  --set NAME=VALUE       R-function models: override a 'param' (repeatable)
  --var NAME             R-function models: normalise the variable NAME instead of res
  --threads T            worker threads (default: all cores)
  -q, --quiet            no progress lines on stderr
  -h, --help             this help

Examples:
  interlin implicit data/rotor37/sections.csv -o blade.ifl
  interlin eval blade.ifl points.csv --gradient
  interlin mesh blade.ifl -o blade.stl --resolution 256
  interlin implicit data/models/uav.rf -o uav.ifl --resolution 128
)";

namespace {

// Parses INNER,OUTER of --band.
std::pair<double, double> band_option(const ParsedArgs& a) {
  const std::vector<double> b = parse_double_list("band", a.get("band", "1.5,3"));
  if (b.size() != 2 || !(b[0] > 0 && b[1] > b[0]))
    throw UsageError("--band: expected INNER,OUTER with 0 < INNER < OUTER (grid cells)");
  return {b[0], b[1]};
}

void write_model(const std::string& path, const IflBlock& model) {
  write_file_atomically(path, [&](std::ostream& out) { write_ifl(out, model); });
}

void sections_job(const ParsedArgs& a, const std::string& input, const std::string& output,
                  const Progress& progress) {
  for (const char* o : {"set", "var", "mesh-resolution"})
    if (a.has(o))
      throw UsageError(std::string("--") + o + " applies to R-function models (.rf) only");
  SectionBodyOptions o;
  o.resolution = parse_int("resolution", a.get("resolution", "96"), 8, 1024);
  std::tie(o.band_inner, o.band_outer) = band_option(a);
  o.margin = parse_double("margin", a.get("margin", "0.05"));
  if (!(o.margin > 0 && o.margin <= 1))
    throw UsageError("--margin: expected a number in (0, 1]");
  o.threads = parse_int("threads", a.get("threads", "0"), 0, 4096);
  o.progress = progress;
  progress("reading " + input);
  const SectionSet set = read_sections(input);
  if (!progress.quiet)
    for (const std::string& w : set.warnings)
      std::cerr << "warning: " << w << "\n";
  const SectionBodyBuild b = build_section_body(set.sections, o);
  const SectionBodyReport& r = b.report;
  const SectionBodyModel& m = b.model;
  std::cout << "interlin implicit " << input << "\n";
  std::cout << "  sections     " << set.sections.size() << ", loft " << m.side.degree_u << " x "
            << m.side.degree_v << ", max |S - P_i| = " << fmt(r.loft.max_deviation, 3) << "\n";
  std::cout << "  grid         " << m.grid.n(0) << " x " << m.grid.n(1) << " x " << m.grid.n(2)
            << " nodes, cell " << fmt(m.grid.h) << ", band " << fmt(m.band_inner) << " .. "
            << fmt(m.band_outer) << "\n";
  std::cout << "  near field   " << r.band_cells << " band cells, " << r.seeds << " starts; "
            << r.check_failures << " of " << r.check_points << " check points and "
            << r.validation_failures << " of " << r.validation_points
            << " validation points needed a start of their own\n";
  std::cout << "  exactness    max |omega| = " << fmt(r.max_surface_omega, 3) << " ("
            << fmt(r.max_surface_omega / r.bbox_diagonal, 3) << " x bbox diagonal "
            << fmt(r.bbox_diagonal) << ") at " << r.surface_points
            << " boundary points (every input point, samples of side and caps); "
            << r.boundary_misses << " of 100000 random boundary points needed a start\n";
  std::cout << "  far field    max |f - d| = " << fmt(r.max_far_error, 3)
            << " beyond the inner band (check points)\n";
  progress("writing " + output);
  write_model(output, to_ifl(m));
}

void rf_job(const ParsedArgs& a, const std::string& input, const std::string& output,
            const Progress& progress) {
  if (a.has("margin"))
    throw UsageError("--margin applies to sections only (an R-function model has its own box)");
  NormalizeOptions o;
  o.resolution = parse_int("resolution", a.get("resolution", "96"), 8, 1024);
  o.mesh_resolution = parse_int("mesh-resolution", a.get("mesh-resolution", "0"), 0, 4096);
  std::tie(o.band_inner, o.band_outer) = band_option(a);
  o.threads = parse_int("threads", a.get("threads", "0"), 0, 4096);
  o.progress = progress;
  const ModelOptions mo = model_options(a, SettingLabel::setting);
  progress("reading " + input);
  const NormalizeBuild b = normalize_model(input, mo, o);
  const NormalizedModel& m = b.model;
  std::cout << "interlin implicit " << input << "\n";
  std::cout << "  mesh of F=0  " << b.report.mesh_vertices << " vertices, "
            << b.report.mesh_triangles << " triangles\n";
  std::cout << "  grid         " << m.grid.n(0) << " x " << m.grid.n(1) << " x " << m.grid.n(2)
            << " nodes, cell " << fmt(m.grid.h) << ", band " << fmt(m.band_inner) << " .. "
            << fmt(m.band_outer) << "\n";
  std::cout << "  exactness    max |omega| = " << fmt(b.report.max_zero_omega, 3)
            << " at the mesh vertices (F = 0 to 1e-10 of a cell; |F| / |grad F| there <= "
            << fmt(b.report.max_zero_first_order, 3) << ")\n";
  progress("writing " + output);
  write_model(output, to_ifl(m));
}

// The kinds of input `interlin implicit` reads, chosen by extension. Another kind (e.g. point
// clouds) adds a row.
struct InputKind {
  std::vector<std::string> extensions;
  std::function<void(const ParsedArgs&, const std::string&, const std::string&, const Progress&)>
      job;
};

const std::vector<InputKind>& input_kinds() {
  static const std::vector<InputKind> kinds = {
      {{".csv", ".txt", ".dat"}, sections_job},
      {{".rf"}, rf_job},
  };
  return kinds;
}

void implicit_main(const ParsedArgs& a, std::vector<std::string>& written) {
  const std::string input = single_input(a, "input file");
  const std::vector<std::string> outputs = a.all("output");
  if (outputs.size() != 1)
    throw UsageError(outputs.empty() ? "nothing to do: give -o MODEL.ifl"
                                     : "expected one -o MODEL.ifl");
  const std::string& output = outputs[0];
  if (lower_extension(output) != ".ifl")
    throw UsageError("output '" + output + "': the model file must end in .ifl");
  check_outputs({input}, outputs);
  const std::string ext = lower_extension(input);
  for (const InputKind& k : input_kinds())
    for (const std::string& e : k.extensions)
      if (e == ext) {
        const Progress progress{a.has("quiet")};
        k.job(a, input, output, progress);
        written.push_back(output);
        print_written(written);
        progress("done");
        return;
      }
  throw UsageError("input '" + input +
                   "': unknown kind (expected sections .csv/.txt/.dat or an R-function model .rf)");
}

} // namespace

int run_implicit(int argc, const char* const* argv) {
  return run_command("implicit", kImplicitHelp, argc, argv,
                     {{"output", 'o', true, true},
                      {"resolution", 0, true, false},
                      {"band", 0, true, false},
                      {"margin", 0, true, false},
                      {"mesh-resolution", 0, true, false},
                      {"set", 0, true, true},
                      {"var", 0, true, false},
                      {"threads", 0, true, false}},
                     implicit_main);
}

} // namespace interlin::cli
