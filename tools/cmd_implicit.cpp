// interlin implicit: sections or an R-function model -> implicit model file (.ifl), whose
// omega vanishes exactly on the body's boundary and is close to the signed distance.
#include "cli_common.h"
#include "commands.h"
#include "implicit_input.h"
#include "implicit_jobs.h"

#include "interlin/interflatation/models/ifl_file.h"
#include "interlin/reconstruction/implicit/normalize_model.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/section_csv.h"

#include <cmath>
#include <iostream>

namespace interlin::cli {

const char* const kImplicitHelp =
    R"(interlin implicit - sections, a point cloud or an R-function model -> implicit model (.ifl)

Usage: interlin implicit INPUT -o MODEL.ifl [options]

INPUT, by kind:
  SECTIONS.csv  blade sections (docs/formats.md, "Section files"): the body whose boundary is
                the loft through every section (as `interlin loft` builds it), closed at hub
                and tip by ruled caps across the end sections
  SCAN.pcd .ply .xyz .xyzn .csv .txt
                a point cloud (docs/formats.md, "Point clouds"). A sectioned scan (points on 3
                or more parallel planes or coaxial cylinders, each slice a closed profile)
                becomes least-squares section curves -> loft -> the body as for sections; any
                other cloud a partition of unity of local fits (MPU, Ohtake et al. 2003) whose
                zero set passes through the points up to the noise
  MODEL.rf      an R-function model: the same zero set, normalised (closer to the distance)
A .csv or .txt is sections when its header has a `section` column or when blank lines split
its x y z rows into 2 or more groups; otherwise it is a point cloud (a .csv then needs a
header naming x, y, z). See docs/formats.md, "Sections or a cloud?".

Output: MODEL.ifl (docs/formats.md, "Implicit model files"), read by `interlin eval`,
`interlin mesh` and by ifl("MODEL.ifl") inside .rf models. Its function omega is 0 exactly on
the boundary (loft surface and caps, or the model's F = 0), > 0 inside, and the signed
distance to the boundary within the inner band (sections) or to first order (R-function
models, clouds); far from the boundary a tricubic interpolant of the exact signed distance
(sections, models) or the extension of the local fits (clouds).

Options:
  -o, --output FILE      the .ifl file to write (written whole or not at all)
  --resolution N         sections: grid cells along the longest side of the box (default 96)
  --band INNER,OUTER     sections: blend band in grid cells (default 1.5,3): exact near field
                         within INNER, far field beyond OUTER
  --margin M             sections: box = body bounding box + M x its diagonal (default 0.05)
  --mesh-resolution N    R-function models: cells of the mesh of F = 0 whose distances make
                         the far field (default 2 x resolution, at least 128)
  --set NAME=VALUE       R-function models: override a 'param' (repeatable)
  --var NAME             R-function models: normalise the variable NAME instead of res
Point clouds:
  --slices KIND          auto (default: a sectioned scan when slices are found, else the
                         unstructured fit), planar, radial (slices required), none (unstructured)
  --noise SIGMA          the scan noise (standard deviation); default: estimated (the slices'
                         spread, or quadric fits to neighbourhoods)
  --normals SOURCE       auto (default: the file's normals when consistently oriented,
                         re-oriented when not, else estimated), file, estimate
  --outliers K           statistical outlier removal with K neighbours (default 16, 0: off)
  --outlier-ratio R      ... removing points beyond R standard deviations (default 3)
  --voxel LEAF           voxel-grid downsampling with cubes of side LEAF (default 0: off)
  --normal-neighbours K  neighbours of the normal estimation: auto (default: 16, more where
                         the noise is large against the point spacing) or a number >= 3
  --sheet-normals MODE   estimated normals from the neighbours on one sheet at sharp edges,
                         narrow gaps and thin walls: auto (default: on clean scans, sampled
                         from a model or a mesh), on, off (PCA of all K neighbours)
  --fit METHOD           unstructured fit: auto (default: for clouds of at most 500 points
                         with normals in the file, the one of pu and hrbf whose five-fold
                         hold-out is closer; else pu), pu (partition of unity of local fits,
                         any size), hrbf (Hermite RBF interpolant of the points and their
                         normals, at most 1000 points)
  --max-depth D          unstructured fit: octree levels (default 12)
  --smooth-points MODE   unstructured fit: auto (default: a noisy scan's points are first moved
                         onto local quadrics of up to 512 neighbours, as many as the shape
                         allows), off (the points as they come)
  --span-smoothing MODE  sectioned scans: auto (default: the sections become isocurves of one
                         least-squares surface through all slices when Mallows' C_p prefers it),
                         off (each section fitted to its slice alone)
  --threads T            worker threads (default: all cores)
  --max-grid-nodes N     largest grid --resolution may ask for, (resolution + 5)^3 nodes
                         as for a cube box (default 4000000, about 4 GB of memory)
  -q, --quiet            no progress lines on stderr
  -h, --help             this help

Exit status: 0 success, 1 bad input (one line naming the file, and the line where there is
one), 2 wrong usage.

Examples:
  interlin implicit data/rotor37/sections.csv -o blade.ifl
  interlin eval blade.ifl points.csv --gradient
  interlin mesh blade.ifl -o blade.stl --resolution 256
  interlin implicit data/models/uav.rf -o uav.ifl --resolution 128
  interlin implicit data/clouds/bun0.pcd -o bunny.ifl
  interlin implicit probe_points.csv -o part.ifl --fit hrbf
  interlin implicit scan.xyz -o blade.ifl --slices planar --noise 0.005
)";

namespace {

// Parses INNER,OUTER of --band.
std::pair<double, double> band_option(const ParsedArgs& a) {
  const std::vector<double> b = parse_double_list("band", a.get("band", "1.5,3"));
  if (b.size() != 2 || !(b[0] > 0 && b[1] > b[0]))
    throw UsageError("--band: expected INNER,OUTER with 0 < INNER < OUTER (grid cells)");
  return {b[0], b[1]};
}

// --resolution, within --max-grid-nodes: the grid is checked as if the box were a cube, since
// its shape is known only after the loft or the model is built.
int resolution_option(const ParsedArgs& a) {
  const int r = parse_int("resolution", a.get("resolution", "96"), 8, 1024);
  const double nodes = std::pow(r + 5.0, 3); // two cells beyond the box on each side
  const long long max = limit_option(a, "max-grid-nodes", limits::implicit_grid_nodes);
  if (nodes > double(max))
    options_exceed("--resolution " + std::to_string(r),
                   "a grid of up to " + fmt(nodes, 3) + " nodes", max, "max-grid-nodes");
  return r;
}

} // namespace

SectionBodyOptions section_body_options(const ParsedArgs& a, const Progress& progress) {
  SectionBodyOptions o;
  o.resolution = resolution_option(a);
  std::tie(o.band_inner, o.band_outer) = band_option(a);
  o.margin = parse_double("margin", a.get("margin", "0.05"));
  if (!(o.margin > 0 && o.margin <= 1))
    throw UsageError("--margin: expected a number in (0, 1]");
  o.threads = parse_int("threads", a.get("threads", "0"), 0, 4096);
  o.progress = progress;
  return o;
}

void print_section_body(const SectionBodyBuild& b, const std::string& sections) {
  const SectionBodyReport& r = b.report;
  const SectionBodyModel& m = b.model;
  std::cout << "  sections     " << sections << ", loft " << m.side.degree_u << " x "
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
}

void write_model(const std::string& path, const IflBlock& model) {
  write_file_atomically(path, [&](std::ostream& out) { write_ifl(out, model); });
}

namespace {

// Options that only some inputs take: UsageError when one is given for another input.
void refuse(const ParsedArgs& a, const std::vector<const char*>& options, const std::string& why) {
  for (const char* o : options)
    if (a.has(o))
      throw UsageError(std::string("--") + o + " " + why);
}

const std::vector<const char*> kCloudOptions = {
    "slices",        "noise",         "normals",           "outliers",
    "outlier-ratio", "voxel",         "normal-neighbours", "sheet-normals",
    "max-depth",     "smooth-points", "span-smoothing",    "fit"};

void sections_job(const ParsedArgs& a, const std::string& input, const std::string& output,
                  const Progress& progress) {
  refuse(a, {"set", "var", "mesh-resolution"}, "applies to R-function models (.rf) only");
  refuse(a, kCloudOptions, "applies to point clouds only (this input holds blade sections)");
  const SectionBodyOptions o = section_body_options(a, progress);
  progress("reading " + input);
  const SectionSet set = read_sections(input);
  if (!progress.quiet)
    for (const std::string& w : set.warnings)
      std::cerr << "warning: " << w << "\n";
  const SectionBodyBuild b = build_section_body(set.sections, o);
  std::cout << "interlin implicit " << input << "\n";
  print_section_body(b, std::to_string(set.sections.size()));
  progress("writing " + output);
  write_model(output, to_ifl(b.model));
}

void rf_job(const ParsedArgs& a, const std::string& input, const std::string& output,
            const Progress& progress) {
  if (a.has("margin"))
    throw UsageError("--margin applies to sections only (an R-function model has its own box)");
  refuse(a, kCloudOptions, "applies to point clouds only (this input is an R-function model)");
  NormalizeOptions o;
  o.resolution = resolution_option(a);
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
  std::string why;
  const ImplicitInput kind = implicit_input_kind(input, &why);
  const Progress progress{a.has("quiet")};
  if (kind == ImplicitInput::sections)
    sections_job(a, input, output, progress);
  else if (kind == ImplicitInput::model)
    rf_job(a, input, output, progress);
  else
    cloud_job(a, input, output, progress, why);
  written.push_back(output);
  print_written(written);
  progress("done");
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
                      {"threads", 0, true, false},
                      {"slices", 0, true, false},
                      {"noise", 0, true, false},
                      {"normals", 0, true, false},
                      {"outliers", 0, true, false},
                      {"outlier-ratio", 0, true, false},
                      {"voxel", 0, true, false},
                      {"normal-neighbours", 0, true, false},
                      {"sheet-normals", 0, true, false},
                      {"max-depth", 0, true, false},
                      {"smooth-points", 0, true, false},
                      {"fit", 0, true, false},
                      {"span-smoothing", 0, true, false},
                      {"max-grid-nodes", 0, true, false}},
                     implicit_main);
}

} // namespace interlin::cli
