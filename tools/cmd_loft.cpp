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
#include "interlin/reconstruction/io/surface_json.h"
#include "interlin/reconstruction/loft/guided_loft.h"
#include "interlin/reconstruction/loft/holdout.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include <cstdlib>
#include <iostream>
#include <map>
#include <sstream>

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
  .json                 the surface: degrees, knots, control points (+ metadata)
  .png                  shaded 3/4 preview with the input sections drawn on it
  .csv                  per-point report: exactness deviation (or hold-out distance)

Options:
  -o, --output FILE          output file (repeatable)
  --samples NU,NV            mesh samples around x along the span (default 400,120);
                             the rows at the input sections are always included
  --cap                      close hub and tip: a watertight solid (3D printing)
  --degree P                 spline degree around the sections (default 3)
  --span-degree Q            spline degree along the span (default 3)
  --align first|le|te        section start: keep the first point (default), or start at
                             the leading / trailing edge detected geometrically
  --match auto|index|arclength
                             point correspondence between sections (default auto: index
                             when the sections have equal point counts)
  --param chord|centripetal  parameters along each section (default chord)
  --span-param chord|centripetal|uniform
                             spacing of the sections' parameters (default centripetal)
  --units mm|cm|m|in         unit label written to IGES (coordinates are not scaled)
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

Examples:
  interlin loft data/rotor37/sections.csv -o out/rotor37.stl -o out/rotor37.igs --units cm
  interlin loft blade.csv -o blade.stl --cap --samples 600,200 --align le
  interlin loft data/rotor37/sections.csv --holdout 2 -o holdout.csv
  interlin loft data/rotor37/sections.csv --guides edges.csv -o blade.igs --units cm
  interlin loft data/rotor37/sections.csv --guides edges.csv --holdout 2
)";

namespace {

enum class Kind { mesh, iges, json, png, report };

Kind output_kind(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off")
    return Kind::mesh;
  if (ext == ".igs" || ext == ".iges")
    return Kind::iges;
  if (ext == ".json")
    return Kind::json;
  if (ext == ".png")
    return Kind::png;
  if (ext == ".csv")
    return Kind::report;
  throw UsageError("output '" + path +
                   "': unknown extension (use .stl .obj .ply .off .igs .iges .json .png .csv)");
}

LengthUnit unit_of(const std::string& u) {
  static const std::map<std::string, LengthUnit> m = {{"mm", LengthUnit::mm},
                                                      {"cm", LengthUnit::cm},
                                                      {"m", LengthUnit::m},
                                                      {"in", LengthUnit::inch}};
  return m.at(u);
}

// Per-point report: the deviation of the surface from each input point (loft) or the distance of
// each withheld point (hold-out).
void write_report(const std::string& path, const std::vector<Section>& all, const LoftResult& loft,
                  const HoldoutResult* h, const GuidedLoftResult* guided, const GuideSet* gs) {
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
      for (size_t k = 0; k < loft.sections.size(); ++k) {
        const PreparedSection& p = loft.sections[k];
        for (Eigen::Index i = 0; i < p.points.rows(); ++i) // report in input order
          if (p.source[static_cast<size_t>(i)] >= 0)       // not a crossing inserted by a guide
            row(all[k], p.source[static_cast<size_t>(i)], loft.deviation[k](i));
      }
    }
    if (guided) // the guides' own points, section column "guide:ID"
      for (size_t l = 0; l < guided->guides.size(); ++l) {
        const Guide& g = gs->guides[l];
        for (Eigen::Index j = 0; j < g.points.rows(); ++j)
          out << "guide:" << g.id << ',' << j << ',' << g.lines[static_cast<size_t>(j)] << ','
              << g.points(j, 0) << ',' << g.points(j, 1) << ',' << g.points(j, 2) << ','
              << guided->guides[l].input_deviation(j) << '\n';
      }
  });
}

// The body of `interlin loft` (run_command handles help, exit statuses and removal on failure).
void loft_main(const ParsedArgs& a, std::vector<std::string>& written) {
  const std::string input = single_input(a, "section file");
  LoftOptions opt;
  opt.degree = parse_int("degree", a.get("degree", "3"), 1, 9);
  opt.span_degree = parse_int("span-degree", a.get("span-degree", "3"), 1, 9);
  const std::string align = parse_choice("align", a.get("align", "first"), {"first", "le", "te"});
  opt.align = align == "le"   ? StartAlign::leading_edge
              : align == "te" ? StartAlign::trailing_edge
                              : StartAlign::first;
  const std::string match =
      parse_choice("match", a.get("match", "auto"), {"auto", "index", "arclength"});
  opt.match = match == "index"       ? Correspondence::index
              : match == "arclength" ? Correspondence::arc_length
                                     : Correspondence::automatic;
  opt.section_exponent =
      parse_choice("param", a.get("param", "chord"), {"chord", "centripetal"}) == "chord" ? 1.0
                                                                                          : 0.5;
  const std::string sp = parse_choice("span-param", a.get("span-param", "centripetal"),
                                      {"chord", "centripetal", "uniform"});
  opt.span_exponent = sp == "chord" ? 1.0 : sp == "centripetal" ? 0.5 : 0.0;
  const LengthUnit unit =
      unit_of(parse_choice("units", a.get("units", "mm"), {"mm", "cm", "m", "in"}));
  const auto [nu, nv] = parse_int_pair("samples", a.get("samples", "400,120"), 3, 1000000000);
  const long long max_triangles = limit_option(a, "max-triangles", limits::mesh_triangles);
  if (2LL * nu * nv > max_triangles) // two per sample cell; the section rows add a few
    options_exceed("--samples " + a.get("samples", "400,120"),
                   std::to_string(2LL * nu * nv) + " triangles", max_triangles, "max-triangles");
  const auto [azimuth, elevation] = parse_int_pair("view", a.get("view", "45,25"), -360, 360);
  const MeshPrecision precision = mesh_precision(a);
  const bool cap = a.has("cap"), quiet = a.has("quiet"), with_guides = a.has("guides");
  double guide_tolerance = 1e-3;
  if (a.has("guide-tolerance")) {
    const std::string t = a.get("guide-tolerance");
    char* end = nullptr;
    guide_tolerance = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0' || !(guide_tolerance > 0) || !(guide_tolerance < 1))
      throw UsageError("--guide-tolerance: expected a number in (0, 1), got '" + t + "'");
    if (!with_guides)
      throw UsageError("--guide-tolerance needs --guides");
  }
  if (a.has("holdout") && a.has("withhold"))
    throw UsageError("--holdout and --withhold exclude each other");
  const bool study = a.has("holdout") || a.has("withhold");
  const std::vector<std::string> outputs = a.all("output");
  if (outputs.empty() && !study)
    throw UsageError("nothing to do: give -o FILE (or --holdout K for a study)");
  std::map<std::string, Kind> kinds;
  for (const std::string& o : outputs)
    kinds[o] = output_kind(o);
  check_outputs(with_guides ? std::vector{input, a.get("guides")} : std::vector{input}, outputs);

  const Progress progress{quiet};
  progress("reading " + input);
  const SectionSet set = read_sections(input);
  if (!quiet)
    for (const std::string& w : set.warnings)
      std::cerr << "warning: " << w << "\n";
  const std::vector<Section>& all = set.sections;
  GuideSet guide_set;
  if (with_guides) {
    progress("reading guides " + a.get("guides"));
    guide_set = read_guides(a.get("guides"));
  }
  GuidedLoftOptions gopt;
  gopt.loft = opt;
  gopt.guide_tolerance = guide_tolerance;
  GuidedLoftResult guided;
  // The loft of a set of sections: with guides the Gordon surface, else the section loft.
  const auto loft_of = [&](const std::vector<Section>& secs) {
    if (!with_guides)
      return loft_sections(secs, opt);
    guided = guided_loft(secs, guide_set, gopt);
    return guided.loft;
  };

  HoldoutResult h;
  LoftResult loft;
  try {
    if (study) {
      const std::vector<size_t> out =
          a.has("holdout")
              ? withheld_every(all.size(), parse_int("holdout", a.get("holdout"), 2, 1000000))
              : [&] {
                  std::vector<size_t> v;
                  for (int i : parse_int_list("withhold", a.get("withhold"), 0))
                    v.push_back(static_cast<size_t>(i));
                  return v;
                }();
      progress("hold-out study: lofting " + std::to_string(all.size() - out.size()) +
               " sections, measuring " + std::to_string(out.size()));
      h = holdout_study(all, out, loft_of);
      loft = h.loft;
    } else {
      progress("lofting " + std::to_string(all.size()) + " sections" +
               (with_guides ? " with " + std::to_string(guide_set.guides.size()) + " guides" : ""));
      loft = loft_of(all);
    }
  } catch (const std::invalid_argument& e) {
    throw_input_error(input, 0, e.what()); // a property of the file's sections
  }
  if (!quiet)
    for (const std::string& n : loft.notes)
      std::cerr << "note: " << n << "\n";

  // Summary.
  const BSplineSurface& S = loft.surface;
  long points = 0;
  for (const PreparedSection& s : loft.sections)
    points += s.points.rows();
  std::cout << "interlin loft " << input << "\n";
  std::cout << "  sections     " << loft.sections.size() << " (" << points
            << " points), correspondence "
            << (loft.used == Correspondence::index ? "index" : "arc length") << ", start " << align
            << "\n";
  std::cout << "  surface      degree " << S.degree_u << " x " << S.degree_v << ", control net "
            << S.num_u << " x " << S.num_v << ", closed around (C" << S.degree_u - 1 << " seam)\n";
  std::cout << "  exactness    max |S(u_i,v_k) - P_i| = " << fmt(loft.max_deviation, 3) << " ("
            << fmt(loft.max_deviation / loft.bbox_diagonal, 3) << " x bbox diagonal "
            << fmt(loft.bbox_diagonal) << ")" << (with_guides ? ", sections and guides" : "")
            << "\n";
  if (with_guides) {
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
  if (study) {
    std::cout << "  hold-out     withheld section: max distance, rms distance\n";
    for (size_t t = 0; t < h.test.size(); ++t) {
      const Eigen::VectorXd& d = h.distance[t];
      std::cout << "               " << all[h.test[t]].id << ": " << fmt(d.maxCoeff()) << ", "
                << fmt(std::sqrt(d.squaredNorm() / static_cast<double>(d.size()))) << "\n";
    }
    std::cout << "  hold-out     all " << h.test.size() << " withheld sections: max " << fmt(h.max)
              << ", rms " << fmt(h.rms) << "\n";
  }

  // Outputs: mesh first when a mesh or preview is wanted.
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  bool need_mesh = false;
  for (const auto& [o, k] : kinds)
    need_mesh = need_mesh || k == Kind::mesh || k == Kind::png;
  if (need_mesh) {
    progress("meshing " + std::to_string(nu) + " x " + std::to_string(nv) +
             (cap ? ", capped" : ""));
    SurfaceMeshOptions mo;
    mo.nu = nu;
    mo.nv = nv;
    mo.cap = cap;
    mo.required_v.assign(loft.section_v.data(), loft.section_v.data() + loft.section_v.size());
    surface_mesh(to_piecewise(S), mo, V, F);
    const MeshReport r = check_mesh(V, F);
    std::cout << "  mesh         " << r.vertices << " vertices, " << r.faces << " triangles, "
              << (cap ? (r.watertight() ? "watertight" : "NOT watertight") : "open at hub and tip")
              << ", area " << fmt(r.area, 6);
    if (cap)
      std::cout << ", volume " << fmt(r.volume, 6);
    std::cout << ", min angle " << fmt(r.min_angle_deg, 3) << " deg\n";
    if (cap && !r.watertight())
      throw std::runtime_error("capped mesh is not watertight (boundary edges " +
                               std::to_string(r.boundary_edges) + ", non-manifold edges " +
                               std::to_string(r.nonmanifold_edges) + ")");
  }
  for (const std::string& o : outputs) {
    progress("writing " + o);
    switch (kinds.at(o)) {
    case Kind::mesh:
      write_mesh(o, V, F, precision);
      break;
    case Kind::iges: {
      IgesOptions io;
      io.unit = unit;
      io.description = "interlin loft of " + input;
      write_iges(o, S, io);
      break;
    }
    case Kind::json: {
      std::ostringstream v;
      v.precision(17);
      for (Eigen::Index k = 0; k < loft.section_v.size(); ++k)
        v << (k ? "," : "") << loft.section_v(k);
      std::map<std::string, std::string> meta = {{"source", input},
                                                 {"units", a.get("units", "mm")},
                                                 {"section_v", v.str()},
                                                 {"max_deviation", fmt(loft.max_deviation, 17)}};
      if (with_guides) {
        std::ostringstream ids, us;
        us.precision(17);
        for (size_t l = 0; l < guided.guides.size(); ++l) {
          ids << (l ? "," : "") << guided.guides[l].id;
          us << (l ? "," : "") << guided.guides[l].u;
        }
        meta["guides"] = a.get("guides");
        meta["guide_ids"] = ids.str();
        meta["guide_u"] = us.str();
      }
      write_surface_json(o, S, meta);
      break;
    }
    case Kind::png: {
      std::vector<Eigen::MatrixXd> lines;
      for (const PreparedSection& s : loft.sections) {
        Eigen::MatrixXd L(s.points.rows() + 1, 3);
        L << s.points, s.points.row(0);
        lines.push_back(L);
      }
      for (const GuideFit& g : guided.guides)
        lines.push_back(g.points);
      PreviewOptions po;
      po.azimuth_deg = azimuth;
      po.elevation_deg = elevation;
      po.up = (loft.sections.back().points.colwise().mean() -
               loft.sections.front().points.colwise().mean())
                  .transpose();
      write_preview_png(o, V, F, lines, po);
      break;
    }
    case Kind::report:
      write_report(o, all, loft, study ? &h : nullptr, with_guides ? &guided : nullptr, &guide_set);
      break;
    }
    written.push_back(o);
  }
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
                      {"span-param", 0, true, false},
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
