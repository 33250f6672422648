// interlin loft: blade-section file -> exact B-spline surface -> mesh, CAD, preview.
#include "cli_common.h"
#include "commands.h"

#include "interlin/interlineation/shape_diagnostics.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/guide_csv.h"
#include "interlin/reconstruction/io/iges.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/io/preview.h"
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/io/step.h"
#include "interlin/reconstruction/io/surface_json.h"
#include "interlin/reconstruction/loft/end_caps.h"
#include "interlin/reconstruction/loft/guided_loft.h"
#include "interlin/reconstruction/loft/holdout.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>
#include <tuple>

namespace interlin::cli {

const char* const kLoftHelp =
    R"(interlin loft - closed sections -> B-spline surface through every section exactly

Usage: interlin loft SECTIONS.csv -o OUT [-o OUT ...] [options]
       interlin loft SECTIONS.csv --guides GUIDES.csv -o OUT [...]

Input: a section file: CSV with header section,index,x,y,z (index optional, any column
order) or plain x y z lines with blank lines between sections (docs/formats.md).

Outputs (-o, repeatable, format by extension; units = input units):
  .stl .obj .ply .off   triangle mesh of the surface (binary STL/PLY)
  .igs .iges            IGES 5.3, one rational B-spline surface (entity 128)
  .step .stp            STEP AP214: one B-spline face, with --cap one closed solid
  .json                 the surface: degrees, knots, control points (+ metadata)
  .png                  shaded 3/4 preview with the input sections drawn on it
  .csv                  per-point report: exactness deviation (or hold-out distance)

Options:
  -o, --output FILE          output file (repeatable)
  --samples NU,NV            mesh samples around x along the span (default 400,120);
                             the rows at the input sections are always included
  --cap                      close hub and tip: a watertight solid (3D printing)
  --degree P                 spline degree around the sections (default 3)
  --span auto|station|chord|centripetal|uniform
                             spacing of the sections along the span (default auto):
                             station = the sections' own positions (planes along their
                             common normal; stream surfaces about z across the flow path),
                             chord = mean distance between neighbouring sections,
                             centripetal = its square root, uniform = equal steps;
                             auto = station (if detected), chord or uniform, chosen
                             by leave-one-out cross-validation
  --span-degree auto|Q       spline degree along the span (default auto: 3, 5 or
                             #sections-1 by leave-one-out; Q is reduced to #sections-1)
  --align first|le|te        section start: keep the first point (default), or start at
                             the leading / trailing edge detected geometrically
  --match auto|index|arclength
                             point correspondence between sections (default auto: index
                             when the sections have equal point counts)
  --param chord|centripetal  parameters along each section (default chord)
  --units mm|cm|m|in         unit written to IGES and STEP (coordinates are not scaled)
  --mesh-precision double|single
                             coordinates in .ply and .obj files (default double: exact;
                             .stl is single precision by definition, .off too)
  --view AZ,EL               preview camera: azimuth and elevation in degrees around the
                             span direction (default 45,25)
  --guides FILE              guide lines (CSV guide,index,x,y,z; docs/formats.md): spanwise
                             polylines (leading/trailing edge, any line on the surface); the
                             surface is then a Gordon surface through the sections AND the
                             guides exactly (crossings found and made compatible for you)
  --guide-tolerance T        a guide must pass within T x bounding-box diagonal of every
                             section (default 1e-3)
  --max-triangles N          largest mesh --samples may ask for (default 20000000, about
                             4.5 GB of memory)
  --holdout K                study: loft sections 0, K, 2K, ... (and the last), report the
                             exact distance of the withheld sections to the surface
  --withhold I,J,...         study: withhold these section indices (0-based)
  -q, --quiet                no progress or warnings on stderr
  -h, --help                 this help

The summary names the spanwise model used and its leave-one-out error: each interior
section withheld in turn, the exact distance of its points to the loft of the others
(how far to trust the surface between sections).

Examples:
  interlin loft data/rotor37/sections.csv -o out/rotor37.stl -o out/rotor37.igs --units cm
  interlin loft blade.csv -o blade.stl --cap --samples 600,200 --align le
  interlin loft data/rotor37/sections.csv -o blade.step --cap --units cm
  interlin loft blade.csv -o blade.igs --span station --span-degree 5
  interlin loft data/rotor37/sections.csv --holdout 2 -o holdout.csv
  interlin loft data/rotor37/sections.csv --guides edges.csv -o blade.igs --units cm
  interlin loft data/rotor37/sections.csv --guides edges.csv --holdout 2
)";

namespace {

// Everything `interlin loft` was asked to do (parse_loft_job).
struct LoftJob {
  std::string input, align, units, guides;
  LoftOptions options;
  GuidedLoftOptions guided;
  LengthUnit unit = LengthUnit::mm;
  MeshPrecision precision = MeshPrecision::float64;
  int nu = 400, nv = 120, azimuth = 45, elevation = 25;
  bool cap = false, quiet = false;
  int holdout = 0;              // --holdout K (0: not asked)
  std::vector<size_t> withhold; // --withhold I,J,...
  std::vector<std::string> outputs;
  bool study() const { return holdout > 0 || !withhold.empty(); }
  bool with_guides() const { return !guides.empty(); }
};

// What it computed (run_loft_job): the input, the loft (of all sections, or of the training
// sections of a study) and, with --guides, the Gordon surface's guides.
struct LoftRun {
  SectionSet set;
  GuideSet guide_set;
  LoftResult loft;
  GuidedLoftResult guided;
  HoldoutResult holdout;
};

// The triangle mesh of the surface, made once when an output needs it.
struct Mesh {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
};

// One output format: its extensions, whether it needs the mesh, and its writer.
struct OutputFormat {
  std::vector<std::string> extensions;
  bool needs_mesh;
  void (*write)(const std::string& path, const LoftJob& job, const LoftRun& run, const Mesh& mesh);
};

LengthUnit unit_of(const std::string& u) {
  static const std::map<std::string, LengthUnit> m = {{"mm", LengthUnit::mm},
                                                      {"cm", LengthUnit::cm},
                                                      {"m", LengthUnit::m},
                                                      {"in", LengthUnit::inch}};
  return m.at(u);
}

// --span-degree: "auto" or 1..9.
int span_degree_of(const std::string& text) {
  return text == "auto" ? kAutoSpanDegree : parse_int("span-degree", text, 1, 9);
}

// --span: "auto", "station", "chord", "centripetal" or "uniform".
SpanParameters span_of(const std::string& text) {
  const std::vector<SpanParameters> all = {SpanParameters::automatic, SpanParameters::station,
                                           SpanParameters::chord, SpanParameters::centripetal,
                                           SpanParameters::uniform};
  std::vector<std::string> names;
  for (SpanParameters p : all)
    names.push_back(to_string(p));
  const std::string choice = parse_choice("span", text, names);
  return all[static_cast<size_t>(std::find(names.begin(), names.end(), choice) - names.begin())];
}

// --guide-tolerance: a number in (0, 1); needs --guides.
double guide_tolerance_of(const ParsedArgs& a) {
  if (!a.has("guide-tolerance"))
    return GuidedLoftOptions{}.guide_tolerance;
  const std::string t = a.get("guide-tolerance");
  char* end = nullptr;
  const double tol = std::strtod(t.c_str(), &end);
  if (t.empty() || *end != '\0' || !(tol > 0) || !(tol < 1))
    throw UsageError("--guide-tolerance: expected a number in (0, 1), got '" + t + "'");
  if (!a.has("guides"))
    throw UsageError("--guide-tolerance needs --guides");
  return tol;
}

// Per-point report: the deviation of the surface from each input point (loft) or the distance of
// each withheld point (hold-out), then the guides' own points.
void write_report(const std::string& path, const LoftJob& job, const LoftRun& run, const Mesh&) {
  const std::vector<Section>& all = run.set.sections;
  const HoldoutResult* h = job.study() ? &run.holdout : nullptr;
  write_file_atomically(path, [&](std::ostream& out) {
    out.precision(17);
    out << "section,index,line,x,y,z," << (h ? "distance" : "deviation") << "\n";
    const auto row = [&](const Section& s, Eigen::Index i, double value) {
      out << s.id << ',' << i << ',' << s.lines[static_cast<size_t>(i)] << ',' << s.points(i, 0)
          << ',' << s.points(i, 1) << ',' << s.points(i, 2) << ',' << value << '\n';
    };
    if (h) {
      for (size_t t = 0; t < h->test.size(); ++t)
        for (Eigen::Index i = 0; i < h->distance[t].size(); ++i)
          row(all[h->test[t]], i, h->distance[t](i));
    } else {
      for (size_t k = 0; k < run.loft.sections.size(); ++k) {
        const PreparedSection& p = run.loft.sections[k];
        for (Eigen::Index i = 0; i < p.points.rows(); ++i) // report in input order
          if (p.source[static_cast<size_t>(i)] >= 0)       // not a crossing inserted by a guide
            row(all[k], p.source[static_cast<size_t>(i)], run.loft.deviation[k](i));
      }
    }
    if (job.with_guides()) // the guides' own points, section column "guide:ID"
      for (size_t l = 0; l < run.guided.guides.size(); ++l) {
        const Guide& g = run.guide_set.guides[l];
        for (Eigen::Index j = 0; j < g.points.rows(); ++j)
          out << "guide:" << g.id << ',' << j << ',' << g.lines[static_cast<size_t>(j)] << ','
              << g.points(j, 0) << ',' << g.points(j, 1) << ',' << g.points(j, 2) << ','
              << run.guided.guides[l].input_deviation(j) << '\n';
      }
  });
}

void write_mesh_file(const std::string& path, const LoftJob& job, const LoftRun&,
                     const Mesh& mesh) {
  warn_single_precision(path, mesh.V, job.precision, job.quiet);
  write_mesh(path, mesh.V, mesh.F, job.precision);
}

void write_iges_file(const std::string& path, const LoftJob& job, const LoftRun& run, const Mesh&) {
  IgesOptions io;
  io.unit = job.unit;
  io.description = "interlin loft of " + job.input;
  write_iges(path, run.loft.surface, io);
}

// With --cap the lateral face and the two ruled end caps as one closed shell (a solid).
void write_step_file(const std::string& path, const LoftJob& job, const LoftRun& run, const Mesh&) {
  StepOptions so;
  so.unit = job.unit;
  so.description = "interlin loft of " + job.input;
  const BSplineSurface& s = run.loft.surface;
  if (!job.cap) {
    write_step(path, s, nullptr, so);
    return;
  }
  const std::array<StepCap, 2> caps{end_cap(s, false), end_cap(s, true)};
  write_step(path, s, &caps, so);
}

std::string joined(const Eigen::VectorXd& x) {
  std::ostringstream s;
  s.precision(17);
  for (Eigen::Index k = 0; k < x.size(); ++k)
    s << (k ? "," : "") << x(k);
  return s.str();
}

void write_json_file(const std::string& path, const LoftJob& job, const LoftRun& run, const Mesh&) {
  const LoftResult& loft = run.loft;
  const SpanCandidate& span = loft.span.used;
  std::map<std::string, std::string> meta = {{"source", job.input},
                                             {"units", job.units},
                                             {"section_v", joined(loft.section_v)},
                                             {"max_deviation", fmt(loft.max_deviation, 17)},
                                             {"span_parameters", to_string(span.parameters)},
                                             {"span_degree", std::to_string(span.degree)},
                                             {"span_loo_max", fmt(span.loo_max, 17)},
                                             {"span_loo_rms", fmt(span.loo_rms, 17)}};
  if (job.with_guides()) {
    std::ostringstream ids;
    Eigen::VectorXd us(static_cast<Eigen::Index>(run.guided.guides.size()));
    for (size_t l = 0; l < run.guided.guides.size(); ++l) {
      ids << (l ? "," : "") << run.guided.guides[l].id;
      us(static_cast<Eigen::Index>(l)) = run.guided.guides[l].u;
    }
    meta["guides"] = job.guides;
    meta["guide_ids"] = ids.str();
    meta["guide_u"] = joined(us);
  }
  write_surface_json(path, loft.surface, meta);
}

void write_png_file(const std::string& path, const LoftJob& job, const LoftRun& run,
                    const Mesh& mesh) {
  std::vector<Eigen::MatrixXd> lines;
  for (const PreparedSection& s : run.loft.sections) {
    Eigen::MatrixXd L(s.points.rows() + 1, 3);
    L << s.points, s.points.row(0);
    lines.push_back(L);
  }
  for (const GuideFit& g : run.guided.guides)
    lines.push_back(g.points);
  PreviewOptions po;
  po.azimuth_deg = job.azimuth;
  po.elevation_deg = job.elevation;
  po.up = (run.loft.sections.back().points.colwise().mean() -
           run.loft.sections.front().points.colwise().mean())
              .transpose();
  write_preview_png(path, mesh.V, mesh.F, lines, po);
}

// The formats of -o, by extension (a new format is one row here).
const std::vector<OutputFormat>& output_formats() {
  static const std::vector<OutputFormat> formats = {
      {{".stl", ".obj", ".ply", ".off"}, true, write_mesh_file},
      {{".igs", ".iges"}, false, write_iges_file},
      {{".step", ".stp"}, false, write_step_file},
      {{".json"}, false, write_json_file},
      {{".png"}, true, write_png_file},
      {{".csv"}, false, write_report},
  };
  return formats;
}

const OutputFormat& output_format(const std::string& path) {
  const std::string ext = lower_extension(path);
  std::string known;
  for (const OutputFormat& f : output_formats())
    for (const std::string& e : f.extensions) {
      if (e == ext)
        return f;
      known += (known.empty() ? "" : " ") + e;
    }
  throw UsageError("output '" + path + "': unknown extension (use " + known + ")");
}

// Step 1: the options, checked before any work (UsageError for wrong usage).
LoftJob parse_loft_job(const ParsedArgs& a) {
  LoftJob job;
  job.input = single_input(a, "section file");
  LoftOptions& opt = job.options;
  opt.degree = parse_int("degree", a.get("degree", "3"), 1, 9);
  opt.span = span_of(a.get("span", "auto"));
  opt.span_degree = span_degree_of(a.get("span-degree", "auto"));
  job.align = parse_choice("align", a.get("align", "first"), {"first", "le", "te"});
  opt.align = job.align == "le"   ? StartAlign::leading_edge
              : job.align == "te" ? StartAlign::trailing_edge
                                  : StartAlign::first;
  const std::string match =
      parse_choice("match", a.get("match", "auto"), {"auto", "index", "arclength"});
  opt.match = match == "index"       ? Correspondence::index
              : match == "arclength" ? Correspondence::arc_length
                                     : Correspondence::automatic;
  opt.section_exponent =
      parse_choice("param", a.get("param", "chord"), {"chord", "centripetal"}) == "chord" ? 1.0
                                                                                          : 0.5;
  job.units = parse_choice("units", a.get("units", "mm"), {"mm", "cm", "m", "in"});
  job.unit = unit_of(job.units);
  std::tie(job.nu, job.nv) = parse_int_pair("samples", a.get("samples", "400,120"), 3, 1000000000);
  const long long max_triangles = limit_option(a, "max-triangles", limits::mesh_triangles);
  if (2LL * job.nu * job.nv > max_triangles) // two per sample cell; the section rows add a few
    options_exceed("--samples " + a.get("samples", "400,120"),
                   std::to_string(2LL * job.nu * job.nv) + " triangles", max_triangles,
                   "max-triangles");
  std::tie(job.azimuth, job.elevation) = parse_int_pair("view", a.get("view", "45,25"), -360, 360);
  job.precision = mesh_precision(a);
  job.cap = a.has("cap");
  job.quiet = a.has("quiet");
  job.guides = a.get("guides");
  job.guided.loft = opt;
  job.guided.guide_tolerance = guide_tolerance_of(a);
  if (a.has("holdout") && a.has("withhold"))
    throw UsageError("--holdout and --withhold exclude each other");
  if (a.has("holdout"))
    job.holdout = parse_int("holdout", a.get("holdout"), 2, 1000000);
  if (a.has("withhold"))
    for (int i : parse_int_list("withhold", a.get("withhold"), 0))
      job.withhold.push_back(static_cast<size_t>(i));
  job.outputs = a.all("output");
  if (job.outputs.empty() && !job.study())
    throw UsageError("nothing to do: give -o FILE (or --holdout K for a study)");
  for (const std::string& o : job.outputs)
    output_format(o);
  check_outputs(job.with_guides() ? std::vector{job.input, job.guides} : std::vector{job.input},
                job.outputs);
  return job;
}

// Step 2: read the input and loft it (with guides: the Gordon surface; a study: the training
// sections, measuring the withheld ones). Properties of the file's sections that make a loft
// impossible are input errors naming the file.
LoftRun run_loft_job(const LoftJob& job, const Progress& progress) {
  LoftRun run;
  progress("reading " + job.input);
  run.set = read_sections(job.input);
  if (!job.quiet)
    for (const std::string& w : run.set.warnings)
      std::cerr << "warning: " << w << "\n";
  const std::vector<Section>& all = run.set.sections;
  if (job.with_guides()) {
    progress("reading guides " + job.guides);
    run.guide_set = read_guides(job.guides);
  }
  const auto loft_of = [&](const std::vector<Section>& secs) {
    if (!job.with_guides())
      return loft_sections(secs, job.options);
    run.guided = guided_loft(secs, run.guide_set, job.guided);
    return run.guided.loft;
  };
  try {
    if (job.study()) {
      const std::vector<size_t> out =
          job.holdout > 0 ? withheld_every(all.size(), job.holdout) : job.withhold;
      progress("hold-out study: lofting " + std::to_string(all.size() - out.size()) +
               " sections, measuring " + std::to_string(out.size()));
      run.holdout = holdout_study(all, out, loft_of);
      run.loft = run.holdout.loft;
    } else {
      progress("lofting " + std::to_string(all.size()) + " sections" +
               (job.with_guides()
                    ? " with " + std::to_string(run.guide_set.guides.size()) + " guides"
                    : ""));
      run.loft = loft_of(all);
    }
  } catch (const std::invalid_argument& e) {
    throw_input_error(job.input, 0, e.what()); // a property of the file's sections
  }
  if (!job.quiet)
    for (const std::string& n : run.loft.notes)
      std::cerr << "note: " << n << "\n";
  return run;
}

// The spanwise model line: parameters, degree, how chosen, and the leave-one-out error that
// tells how far to trust the surface between sections.
std::string span_summary(const SpanModel& m) {
  std::ostringstream s;
  s << to_string(m.used.parameters);
  if (m.used.parameters == SpanParameters::station)
    s << " (" << to_string(m.stations.stacking) << ")";
  s << ", degree " << m.used.degree;
  if (m.chosen)
    s << ", chosen by leave-one-out among " << m.candidates.size() << " models";
  if (m.folds == 0) {
    s << "; no leave-one-out error (no interior section)";
    return s.str();
  }
  s << "\n               leave-one-out error max " << fmt(m.used.loo_max) << ", rms "
    << fmt(m.used.loo_rms) << " (" << m.folds << " interior sections withheld in turn)";
  return s.str();
}

// Step 3: the summary on stdout.
void print_summary(const LoftJob& job, const LoftRun& run) {
  const LoftResult& loft = run.loft;
  const BSplineSurface& S = loft.surface;
  long points = 0;
  for (const PreparedSection& s : loft.sections)
    points += s.points.rows();
  std::cout << "interlin loft " << job.input << "\n";
  std::cout << "  sections     " << loft.sections.size() << " (" << points
            << " points), correspondence "
            << (loft.used == Correspondence::index ? "index" : "arc length") << ", start "
            << job.align << "\n";
  std::cout << "  surface      degree " << S.degree_u << " x " << S.degree_v << ", control net "
            << S.num_u << " x " << S.num_v << ", closed around (C" << S.degree_u - 1 << " seam)\n";
  std::cout << "  span         " << span_summary(loft.span) << "\n";
  std::cout << "  exactness    max |S(u_i,v_k) - P_i| = " << fmt(loft.max_deviation, 3) << " ("
            << fmt(loft.max_deviation / loft.bbox_diagonal, 3) << " x bbox diagonal "
            << fmt(loft.bbox_diagonal) << ")" << (job.with_guides() ? ", sections and guides" : "")
            << "\n";
  if (job.with_guides()) {
    const GuidedLoftResult& guided = run.guided;
    long inserted = 0;
    for (const PreparedSection& p : loft.sections)
      for (Eigen::Index src : p.source)
        inserted += src < 0;
    std::cout << "  guides       " << guided.guides.size() << " (";
    for (size_t l = 0; l < guided.guides.size(); ++l)
      std::cout << (l ? ", " : "") << guided.guides[l].id << " at u = " << fmt(guided.guides[l].u);
    std::cout << "), " << inserted << " crossing(s) inserted into sections\n";
    std::cout << "  guide fit    max |S(u_l,v) - G_l(v)| = " << fmt(guided.max_guide_deviation, 3)
              << " (points and curves); input guide points within "
              << fmt(guided.max_input_deviation, 3) << "\n";
    const ShapeSummary sh = summarize(shape_map(to_piecewise(loft.surface),
                                                Eigen::VectorXd::LinSpaced(401, 0, 1).head(400),
                                                Eigen::VectorXd::LinSpaced(41, 0, 1)));
    std::cout << "  shape        around: convex " << fmt(100 * sh.convex_u, 3) << "%, concave "
              << fmt(100 * sh.concave_u, 3) << "%, flat " << fmt(100 * sh.flat_u, 3)
              << "%; along the span: convex " << fmt(100 * sh.convex_v, 3) << "%, concave "
              << fmt(100 * sh.concave_v, 3) << "%, flat " << fmt(100 * sh.flat_v, 3) << "%\n";
  }
  if (job.study()) {
    const HoldoutResult& h = run.holdout;
    std::cout << "  hold-out     withheld section: max distance, rms distance\n";
    for (size_t t = 0; t < h.test.size(); ++t) {
      const Eigen::VectorXd& d = h.distance[t];
      std::cout << "               " << run.set.sections[h.test[t]].id << ": " << fmt(d.maxCoeff())
                << ", " << fmt(std::sqrt(d.squaredNorm() / static_cast<double>(d.size()))) << "\n";
    }
    std::cout << "  hold-out     all " << h.test.size() << " withheld sections: max " << fmt(h.max)
              << ", rms " << fmt(h.rms) << "\n";
  }
}

// Step 4: the mesh when an output needs it (its summary line; a capped mesh must be
// watertight), then every output through its format's writer.
void write_outputs(const LoftJob& job, const LoftRun& run, const Progress& progress,
                   std::vector<std::string>& written) {
  Mesh mesh;
  if (std::any_of(job.outputs.begin(), job.outputs.end(),
                  [](const std::string& o) { return output_format(o).needs_mesh; })) {
    progress("meshing " + std::to_string(job.nu) + " x " + std::to_string(job.nv) +
             (job.cap ? ", capped" : ""));
    SurfaceMeshOptions mo;
    mo.nu = job.nu;
    mo.nv = job.nv;
    mo.cap = job.cap;
    const Eigen::VectorXd& v = run.loft.section_v;
    mo.required_v.assign(v.data(), v.data() + v.size());
    surface_mesh(to_piecewise(run.loft.surface), mo, mesh.V, mesh.F);
    const MeshReport r = check_mesh(mesh.V, mesh.F);
    std::cout << "  mesh         " << r.vertices << " vertices, " << r.faces << " triangles, "
              << (job.cap ? (r.watertight() ? "watertight" : "NOT watertight")
                          : "open at hub and tip")
              << ", area " << fmt(r.area, 6);
    if (job.cap)
      std::cout << ", volume " << fmt(r.volume, 6);
    std::cout << ", min angle " << fmt(r.min_angle_deg, 3) << " deg\n";
    if (job.cap && !r.watertight())
      throw std::runtime_error("capped mesh is not watertight (boundary edges " +
                               std::to_string(r.boundary_edges) + ", non-manifold edges " +
                               std::to_string(r.nonmanifold_edges) + ")");
  }
  for (const std::string& o : job.outputs) {
    progress("writing " + o);
    output_format(o).write(o, job, run, mesh);
    written.push_back(o);
  }
}

// The body of `interlin loft` (run_command handles help, exit statuses and removal on failure).
void loft_main(const ParsedArgs& a, std::vector<std::string>& written) {
  const LoftJob job = parse_loft_job(a);
  const Progress progress{job.quiet};
  const LoftRun run = run_loft_job(job, progress);
  print_summary(job, run);
  write_outputs(job, run, progress, written);
  print_written(written);
  progress("done");
}

} // namespace

int run_loft(int argc, const char* const* argv) {
  return run_command("loft", kLoftHelp, argc, argv,
                     {{"output", 'o', true, true},
                      {"samples", 0, true, false},
                      {"cap", 0, false, false},
                      {"degree", 0, true, false},
                      {"span-degree", 0, true, false},
                      {"align", 0, true, false},
                      {"match", 0, true, false},
                      {"param", 0, true, false},
                      {"span", 0, true, false},
                      {"units", 0, true, false},
                      {"holdout", 0, true, false},
                      {"withhold", 0, true, false},
                      {"view", 0, true, false},
                      {"guides", 0, true, false},
                      {"guide-tolerance", 0, true, false},
                      {"max-triangles", 0, true, false},
                      {"mesh-precision", 0, true, false}},
                     loft_main);
}

} // namespace interlin::cli
