// interlin mesh --volume: implicit solid -> tetrahedral or hexahedral mesh for analysis.
#include "cmd_mesh_volume.h"

#include "interlin/interflatation/limits.h"
#include "interlin/interflatation/load_implicit.h"
#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/io/preview.h"
#include "interlin/reconstruction/io/volume_mesh_io.h"
#include "interlin/reconstruction/meshing/adaptive_refinement.h"
#include "interlin/reconstruction/meshing/boundary_mesh.h"
#include "interlin/reconstruction/meshing/facet_sag.h"
#include "interlin/reconstruction/meshing/hexahedral_refinement.h"
#include "interlin/reconstruction/meshing/volume_mesh.h"
#include "interlin/reconstruction/meshing/volume_quality.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <stdexcept>
#include <thread>

namespace interlin::cli {

namespace {

bool surface_output(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off";
}

// The boundary surface as a triangle mesh of its own nodes (quadrilaterals split along their
// shorter diagonal).
void boundary_surface(const VolumeMesh& m, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  std::vector<int> index(size_t(m.V.rows()), -1);
  int n = 0;
  for (long v = 0; v < m.V.rows(); ++v)
    if (m.boundary[size_t(v)])
      index[size_t(v)] = n++;
  V.resize(n, 3);
  for (long v = 0; v < m.V.rows(); ++v)
    if (index[size_t(v)] >= 0)
      V.row(index[size_t(v)]) = m.V.row(v);
  F = m.B.cols() == 4 ? triangulate_quads(m.V, m.B) : m.B;
  for (long i = 0; i < F.size(); ++i)
    F.data()[i] = index[size_t(F.data()[i])];
}

VolumeMeshOptions volume_options_of(const ParsedArgs& a, const VolumeRequest& r) {
  VolumeMeshOptions o;
  const std::string kind = parse_choice("volume", a.get("volume"), {"tet", "hex"});
  o.elements = kind == "hex" ? VolumeElements::hexahedra : VolumeElements::tetrahedra;
  o.box = r.box;
  o.resolution = r.resolution;
  o.cell = r.cell;
  o.threads = r.threads;
  o.surface_sweeps = r.smooth;
  if (a.has("sweeps"))
    o.interior_sweeps = parse_int("sweeps", a.get("sweeps"), 0, 1000);
  if (a.has("seed-rule") && a.has("margin"))
    throw UsageError("--seed-rule and --margin exclude each other");
  if (a.has("margin")) {
    o.margin = parse_double("margin", a.get("margin"));
    if (!(o.margin >= 0 && o.margin < 1))
      throw UsageError("--margin: expected a number in [0, 1), got " + a.get("margin"));
  }
  if (a.has("boundary")) {
    const bool hex = o.elements == VolumeElements::hexahedra;
    const std::string b =
        hex ? parse_choice("boundary", a.get("boundary"), {"projected", "dual", "pillow"})
            : parse_choice("boundary", a.get("boundary"), {"cut", "projected"});
    o.boundary = boundary_named(b);
  }
  if (a.has("lattice")) {
    if (o.elements == VolumeElements::hexahedra || o.boundary != VolumeBoundary::cut)
      throw UsageError("--lattice applies to --volume tet with --boundary cut");
    o.lattice = lattice_named(parse_choice("lattice", a.get("lattice"), {"bcc", "kuhn"}));
  }
  if (a.has("margin") &&
      (o.boundary == VolumeBoundary::dual || o.boundary == VolumeBoundary::pillow))
    throw UsageError("--margin applies to the projected layer, not --boundary " +
                     a.get("boundary"));
  if (a.has("margin") && o.boundary == VolumeBoundary::cut)
    throw UsageError("--margin applies to the projected layer (--boundary projected)");
  if (a.has("seed-rule")) { // seed 003's published configurations
    if (a.has("boundary") && o.boundary != VolumeBoundary::projected)
      throw UsageError("--seed-rule uses the projected layer, not --boundary " + a.get("boundary"));
    o.boundary = VolumeBoundary::projected;
    o.margin = 0;
    o.rule = o.elements == VolumeElements::hexahedra ? ZeroRule::inclusive : ZeroRule::strict;
  }
  return o;
}

// --adapt N [--adapt-delta D] [--adapt-var NAME], checked (and the variable loaded) before any
// meshing, so a usage error costs no mesh.
struct AdaptRequest {
  int passes = 0;         // 0: no refinement
  double delta = 0.2;     // indicator threshold, a fraction of its range
  ImplicitFunction field; // the nodal quantity: --adapt-var of the model, or F
  long max_elements = 0;  // --max-elements, the limit of the refined mesh too
};

AdaptRequest adapt_request_of(const ParsedArgs& a, const ImplicitFunction& f,
                              const VolumeRequest& r) {
  AdaptRequest q{0, 0.2, f, 0};
  if (!a.has("adapt")) {
    for (const char* only : {"adapt-delta", "adapt-var"})
      if (a.has(only))
        throw UsageError(std::string("--") + only + " needs --adapt N");
    return q;
  }
  q.passes = parse_int("adapt", a.get("adapt"), 1, 10);
  q.max_elements = long(volume_element_limit(a));
  q.delta = parse_double("adapt-delta", a.get("adapt-delta", "0.2"));
  if (!(q.delta >= 0 && q.delta < 1))
    throw UsageError("--adapt-delta: expected a number in [0, 1), got " + a.get("adapt-delta"));
  if (a.has("adapt-var")) {
    if (lower_extension(r.input) != ".rf")
      throw UsageError("--adapt-var names a variable of an .rf model");
    ModelOptions mo = r.model;
    mo.output = a.get("adapt-var");
    q.field = load_implicit(r.input, mo);
  }
  return q;
}

// q.passes passes of refine_tetrahedra or refine_hexahedra on q.field, then the interior of
// tetrahedra smoothed again (the templates' children are valid but uneven). Hexahedra are not:
// functional (15) with one t for children a third and a ninth the size of their neighbours
// undoes the grading (ball at 10 cells, 2 passes, 8 sweeps: mean scaled Jacobian 0.82 -> 0.26,
// 6 elements folded at their centres). Returns the reports of the passes kept; a hexahedral pass
// that left children folded and was undone goes to `undone`.
std::vector<RefinementReport> adapt(const AdaptRequest& q, const ImplicitFunction& f,
                                    const VolumeMeshOptions& o, const Progress& progress,
                                    VolumeMesh& m, RefinementReport& undone) {
  progress("adaptive refinement, " + std::to_string(q.passes) + " passes (delta " +
           fmt(q.delta, 3) + ")");
  const auto values = [&](const Eigen::MatrixXd& V, const Eigen::MatrixXi&) {
    Eigen::VectorXd v(V.rows());
    q.field.value(V, v);
    if (!v.allFinite())
      throw std::runtime_error("--adapt: the nodal quantity is not finite at a node");
    return v;
  };
  std::vector<RefinementReport> reports;
  try {
    reports =
        m.C.cols() == 8
            ? adapt_hexahedra(m.V, m.C, m.boundary, values, q.delta, q.passes, f, q.max_elements)
            : adapt_tetrahedra(m.V, m.C, m.boundary, values, q.delta, q.passes, f, q.max_elements);
  } catch (const std::length_error& e) {
    const std::string what = e.what();
    throw std::runtime_error("--adapt: " + what.substr(what.find(": ") + 2) +
                             " (--max-elements; or fewer passes, a larger --adapt-delta)");
  }
  if (!reports.empty() && reports.back().undone)
    undone = reports.back(), reports.pop_back();
  m.B = boundary_facets(m.C, o.threads);
  VolumeSmoothingOptions so;
  so.sweeps = m.C.cols() == 8 ? 0 : interior_sweeps_of(o);
  so.threads = o.threads;
  if (so.sweeps > 0)
    smooth_volume(m.V, m.C, m.boundary, so);
  return reports;
}

// The largest |F| at the boundary nodes the refinement added (from node `first` on) but those it
// held short of F = 0 (they stay flagged, so that smoothing keeps them); 0 when there is none.
double max_new_boundary_f(const ImplicitFunction& f, const VolumeMesh& m, long first,
                          const std::vector<RefinementReport>& passes) {
  std::vector<char> on(m.boundary.begin() + first, m.boundary.end());
  for (const RefinementReport& p : passes)
    for (long n : p.held_nodes)
      on[size_t(n - first)] = 0;
  Points3 P(std::count(on.begin(), on.end(), char(1)), 3);
  for (size_t k = 0, r = 0; k < on.size(); ++k)
    if (on[k])
      P.row(long(r++)) = m.V.row(first + long(k));
  Eigen::VectorXd F(P.rows());
  f.value(P, F);
  return F.size() > 0 ? F.cwiseAbs().maxCoeff() : 0;
}

// The summary on stdout; `on_zero` counts the boundary nodes on F = 0 (after any refinement).
void print_summary(const VolumeRequest& r, const VolumeMesh& m, const VolumeMeshInfo& info,
                   const VolumeQuality& q, const VolumeMeshOptions& o, long on_zero,
                   const std::string& grid_note) {
  const RegularGrid& g = info.grid;
  const bool tets = m.C.cols() == 4;
  const long boundary_nodes = std::count(m.boundary.begin(), m.boundary.end(), char(1));
  std::cout << "interlin mesh " << r.input << " --volume " << (tets ? "tet" : "hex") << "\n";
  std::cout << "  grid         " << g.nodes(0) << " x " << g.nodes(1) << " x " << g.nodes(2)
            << " nodes, cell " << fmt(g.spacing(0)) << grid_note << ", "
            << (o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency())))
            << " threads\n";
  std::cout << "  elements     " << m.C.rows() << (tets ? " tetrahedra" : " hexahedra") << " ("
            << info.inner_cells << " inner cells, " << info.layer_elements
            << " in the boundary layer"
            << (info.inner_cells + info.layer_elements != m.C.rows() ? " before refinement" : "")
            << "), " << m.V.rows() << " nodes, " << m.B.rows()
            << (tets ? " boundary triangles" : " boundary quadrilaterals") << "\n";
  if (tets && info.boundary == VolumeBoundary::cut)
    std::cout << "  lattice      " << lattice_name(o.lattice) << "\n";
  if (!tets) {
    std::cout << "  layer        " << boundary_name(info.boundary);
    if (info.offset_grid > 0)
      std::cout << " (on the grid offset by " << (info.offset_grid == 0.5 ? "half" : "a quarter of")
                << " a cell: on the grid the pillows kept " << info.folded_pillows
                << " folded elements)";
    else if (info.folded_pillows > 0)
      std::cout << " (the pillow meshes kept " << info.folded_pillows << " folded elements)";
    std::cout << "\n";
  }
  std::cout << "  quality      dihedral angles " << fmt(q.min_dihedral_deg, 3) << " .. "
            << fmt(q.max_dihedral_deg, 4) << " deg (" << q.outside_10_170
            << " elements outside 10 .. 170), scaled Jacobian min " << fmt(q.min_scaled_jacobian, 3)
            << " mean " << fmt(q.mean_scaled_jacobian, 3);
  if (tets)
    std::cout << ", radius ratio min " << fmt(q.min_radius_ratio, 3) << " mean "
              << fmt(q.mean_radius_ratio, 3);
  std::cout << ", inverted " << q.inverted << "\n";
  std::cout << "  boundary     " << boundary_nodes << " nodes, " << on_zero << " on F = 0 ("
            << fmt(boundary_nodes > 0 ? 100.0 * double(on_zero) / double(boundary_nodes) : 0, 3)
            << (on_zero > 0 ? " %, max |F| " + fmt(info.max_boundary_f, 3) : std::string(" %"))
            << "), " << info.unprojected << " not projected, " << info.held
            << " held short of it to keep their elements valid\n";
  std::cout << "  geometry     volume " << fmt(q.volume, 7) << "\n";
  if (info.coverage.body > 0)
    std::cout << "  coverage     " << fmt(100 * info.lost_fraction(), 3)
              << " % of the body's volume left out (" << fmt(info.coverage.lost, 4) << " of "
              << fmt(info.coverage.body, 7) << " on the grid clipped at F = 0)\n";
}

// x > 0 rounded down to 2 significant digits: a suggested cell must not grow by rounding.
double two_digits_down(double x) {
  const double unit = std::pow(10.0, std::floor(std::log10(x)) - 1);
  return std::floor(x / unit) * unit;
}

// The fix for a mesh that leaves out more than kLostVolumeWarning of the body: a cell at which
// walls as thick as the lost ones keep inner cells (dual hexahedra: grid nodes), or the clipped
// grid.
std::string lost_volume_fix(const VolumeMeshInfo& info, const VolumeMeshOptions& o) {
  const bool tets = o.elements == VolumeElements::tetrahedra;
  return "walls about " + fmt(info.coverage.thickness(), 3) +
         (info.boundary == VolumeBoundary::dual || info.boundary == VolumeBoundary::pillow
              ? " thick (walls with no grid node, slivers under "
                "held boundary points)"
              : " thick have no inner cell under the boundary "
                "layer") +
         ": use --cell " + fmt(two_digits_down(info.suggested_cell), 2) + " or smaller, or " +
         (tets ? "--boundary cut" : "--volume tet");
}

} // namespace

SagCheck check_sag(const ImplicitFunction& f, const Eigen::MatrixXd& V, const Eigen::MatrixXi& B,
                   double volume, double h, int threads, const Progress& progress) {
  SagCheck c;
  c.h = h;
  if (B.rows() == 0 || !(std::abs(volume) > 0))
    return c;
  progress("measuring the facets' distance to F = 0");
  c.sag = facet_sag(f, V, B, threads);
  c.fraction = c.sag.volume / volume;
  return c;
}

std::string refine_for_sag(SagCheck& last, const std::function<bool(double cell)>& allowed,
                           const std::function<SagCheck(double cell)>& remesh,
                           const Progress& progress) {
  constexpr int kPasses = 2;
  constexpr double kMaxRefinement = 4; // per axis, over the default cell
  const SagCheck first = last;
  SagCheck before;
  for (int pass = 0; pass < kPasses && std::abs(last.fraction) > kLostVolumeWarning; ++pass) {
    double order = 2; // observed on the second pass
    if (pass > 0 && before.fraction * last.fraction > 0 && before.h > last.h)
      order = std::clamp(std::log(before.fraction / last.fraction) / std::log(before.h / last.h),
                         0.5, 2.0);
    const double cell = std::max(cell_for_sag(last.h, last.fraction, kLostVolumeWarning, order),
                                 first.h / kMaxRefinement);
    if (!(cell < 0.99 * last.h) || !allowed(cell))
      break;
    progress(std::string("the facets ") + (last.fraction > 0 ? "leave out " : "add ") +
             fmt(100 * std::abs(last.fraction), 2) +
             " % of the body's volume: meshing again at cell " + fmt(cell, 4));
    before = last;
    last = remesh(cell);
  }
  if (!(last.h < first.h))
    return "";
  return " (the default cell " + fmt(first.h, 4) + " refined: its facets " +
         (first.fraction > 0 ? "left out " : "added ") + fmt(100 * std::abs(first.fraction), 2) +
         " % of the body's volume)";
}

void print_sag(const SagCheck& c, bool quiet) {
  const FacetSag& s = c.sag;
  const double total = s.area + s.skipped_area;
  if (!(total > 0))
    return;
  std::cout << "  sag          facets up to " << fmt(s.max_distance, 3) << " from F = 0 ("
            << fmt(s.max_distance / c.h, 2) << " cells); the body's volume about "
            << fmt(100 * std::abs(c.fraction), 3) << " % " << (c.fraction >= 0 ? "above" : "below")
            << " the mesh's (the facets' chords, measured along their normals; "
            << fmt(100 * s.skipped_area / total, 2)
            << " % of their area not measured: sharp edges)\n";
  if (!quiet && std::abs(c.fraction) > kLostVolumeWarning)
    std::cerr << "warning: the facets, chords of a surface that bends within a few cells, "
              << (c.fraction > 0 ? "leave out about " : "add about ")
              << fmt(100 * std::abs(c.fraction), 2) << " % of the body's volume: use --cell "
              << fmt(two_digits_down(cell_for_sag(c.h, c.fraction, kLostVolumeWarning)), 2)
              << " or smaller\n";
}

long long volume_element_limit(const ParsedArgs& a) {
  return limit_option(a, "max-elements",
                      a.get("volume") == "hex" ? limits::volume_hexahedra
                                               : limits::volume_tetrahedra);
}

bool volume_output_ok(const std::string& path) {
  return is_volume_mesh_path(path) || surface_output(path) || lower_extension(path) == ".png";
}

std::vector<OptionSpec> volume_options() {
  return {{"volume", 0, true, false},     {"margin", 0, true, false},
          {"boundary", 0, true, false},   {"sweeps", 0, true, false},
          {"seed-rule", 0, false, false}, {"max-elements", 0, true, false},
          {"adapt", 0, true, false},      {"adapt-delta", 0, true, false},
          {"adapt-var", 0, true, false},  {"lattice", 0, true, false}};
}

void mesh_volume(const ParsedArgs& a, const ImplicitFunction& f, const VolumeRequest& r,
                 const Progress& progress, std::vector<std::string>& written) {
  VolumeMeshOptions o = volume_options_of(a, r);
  const AdaptRequest adapt_request = adapt_request_of(a, f, r);
  o.progress = progress;
  VolumeMeshInfo info;
  VolumeMesh m = volume_mesh(f, o, &info);
  if (m.C.rows() == 0)
    throw_input_error(r.input, 0,
                      "no volume mesh: no grid cell lies inside the body (" +
                          (info.coverage.body > 0
                               ? lost_volume_fix(info, o)
                               : std::string("refine the grid with --resolution or --cell, or "
                                             "check the box")) +
                          ")");
  std::vector<ElementQuality> per;
  VolumeQuality q;
  SagCheck sag;
  std::string grid_note;
  if (r.default_grid) {
    progress("checking the elements");
    q = volume_quality(m.V, m.C, r.threads, &per);
    sag = check_sag(f, m.V, m.B, q.volume, info.grid.spacing(0), r.threads, progress);
    grid_note = refine_for_sag(
        sag, r.grid_allowed,
        [&](double cell) {
          o.cell = cell;
          info = VolumeMeshInfo{};
          m = volume_mesh(f, o, &info);
          progress("checking the elements");
          q = volume_quality(m.V, m.C, r.threads, &per);
          return check_sag(f, m.V, m.B, q.volume, info.grid.spacing(0), r.threads, progress);
        },
        progress);
  }
  const long before = m.C.rows(), first_new = m.V.rows();
  RefinementReport undone;
  const std::vector<RefinementReport> passes = adapt_request.passes > 0
                                                   ? adapt(adapt_request, f, o, progress, m, undone)
                                                   : std::vector<RefinementReport>{};
  if (!passes.empty())
    info.max_boundary_f =
        std::max(info.max_boundary_f, max_new_boundary_f(f, m, first_new, passes));
  if (!r.default_grid || !passes.empty()) { // else checked above, and unchanged since (an undone
    // pass restores the mesh it started from)
    progress("checking the elements");
    q = volume_quality(m.V, m.C, r.threads, &per);
    sag = check_sag(f, m.V, m.B, q.volume, info.grid.spacing(0), r.threads, progress);
  }
  long on_zero = info.on_zero;
  for (const RefinementReport& p : passes) // the refinement's new boundary nodes, held or not
    on_zero += p.projected - p.held, info.held += p.held;
  print_summary(r, m, info, q, o, on_zero, grid_note);
  print_sag(sag, r.quiet);
  warn_body_reaches_box(info.clipped, r.quiet);
  if (!r.quiet && info.lost_fraction() > kLostVolumeWarning)
    std::cerr << "warning: the mesh leaves out " << fmt(100 * info.lost_fraction(), 2)
              << " % of the body's volume (" << lost_volume_fix(info, o) << ")\n";
  if (a.has("adapt")) {
    const bool hex = m.C.cols() == 8;
    std::cout << "  adapted      " << passes.size() << " passes, " << before << " -> " << m.C.rows()
              << (hex ? " hexahedra (flagged" : " tetrahedra (flagged");
    for (const RefinementReport& p : passes)
      std::cout << " " << p.flagged;
    if (hex) { // refined nodes the closure added so that every element has a template
      std::cout << "; nodes added by the closure";
      for (const RefinementReport& p : passes)
        std::cout << " " << p.widened;
      std::cout << "; folded children untangled";
      for (const RefinementReport& p : passes)
        std::cout << " " << p.folded - p.still_folded << " of " << p.folded;
    }
    std::cout << "; new boundary nodes on F = 0";
    for (const RefinementReport& p : passes)
      std::cout << " " << p.projected - p.held;
    std::cout << ", held short of it to keep their elements valid";
    for (const RefinementReport& p : passes)
      std::cout << " " << p.held;
    if (undone.undone)
      std::cout << "; pass " << passes.size() + 1 << " undone: " << undone.still_folded
                << " children stayed folded";
    std::cout << ")\n";
    if (undone.undone && !r.quiet)
      std::cerr << "warning: --adapt: pass " << passes.size() + 1 << " left " << undone.still_folded
                << " children folded (walls thinner than its cells) and "
                << "was undone; "
                << (passes.empty() ? std::string("the unrefined mesh")
                                   : "the mesh after pass " + std::to_string(passes.size()))
                << " is written (a finer --cell, or fewer passes)\n";
  }
  if (q.inverted > 0)
    throw std::runtime_error(
        std::to_string(q.inverted) +
        (o.boundary == VolumeBoundary::pillow
             ? " inverted elements (pillows the untangling could not open at sharp edges or "
               "creases: use --boundary dual or --volume tet)"
             : " inverted elements (features thinner than a few cells: refine the grid with "
               "--cell or --resolution)"));
  VolumeMeshFields fields;
  Eigen::VectorXd sj(m.C.rows()), dmin(m.C.rows());
  for (long e = 0; e < m.C.rows(); ++e)
    sj(e) = per[size_t(e)].scaled_jacobian, dmin(e) = per[size_t(e)].min_dihedral_deg;
  fields.element = {{"scaled_jacobian", sj}, {"min_dihedral_deg", dmin}};
  Eigen::MatrixXd SV;
  Eigen::MatrixXi SF;
  boundary_surface(m, SV, SF);
  for (const std::string& out : r.outputs) {
    progress("writing " + out);
    if (is_volume_mesh_path(out)) {
      write_volume_mesh(out, m.V, m.C, m.B, fields);
    } else if (surface_output(out)) {
      warn_single_precision(out, SV, MeshPrecision::float64, r.quiet);
      write_mesh(out, SV, SF);
    } else {
      PreviewOptions po;
      po.azimuth_deg = r.azimuth;
      po.elevation_deg = r.elevation;
      po.up = Eigen::Vector3d::UnitZ();
      write_preview_png(out, SV, SF, {}, po);
    }
    written.push_back(out);
  }
  print_written(written);
  progress("done");
}

} // namespace interlin::cli
