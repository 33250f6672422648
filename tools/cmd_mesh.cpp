// interlin mesh: implicit model (.rf or .ifl) -> closed triangle mesh (marching cubes in parallel
// sub-boxes, vertices projected onto F = 0), optional smoothing and edge flips, mesh files and a
// preview.
#include "cli_common.h"
#include "cmd_mesh_volume.h"
#include "commands.h"

#include "interlin/interflatation/load_implicit.h"

#include "interlin/reconstruction/io/input_error.h"
#include "interlin/reconstruction/io/mesh_io.h"
#include "interlin/reconstruction/io/preview.h"
#include "interlin/reconstruction/meshing/edge_flips.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"
#include "interlin/reconstruction/meshing/surface_smoothing.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <thread>

namespace interlin::cli {

const char* const kMeshHelp =
    R"(interlin mesh - implicit model -> closed triangle mesh of the body F > 0

Usage: interlin mesh MODEL -o OUT [-o OUT ...] [options]
       interlin mesh MODEL -o OUT.msh --volume tet|hex [options]

MODEL      an R-function model MODEL.rf (docs/formats.md, "R-function model files"), e.g.
           data/models/*.rf, or an implicit model file MODEL.ifl (`interlin implicit`)

Outputs (-o, repeatable, format by extension):
  .stl .obj .ply .off   triangle mesh (binary STL/PLY), closed and outward oriented
  .png                  shaded 3/4 preview (z up)

Method: the box is cut into a regular grid of cubic cells and into sub-boxes that share their
boundary planes (seed 002); each sub-box is sampled and triangulated by marching cubes
(asymptotic decider) on its own thread; the sub-box meshes are merged exactly along the shared
planes and every vertex is moved onto F = 0 along its grid edge (seed 003). The body is cut by
the box: where it reaches the box the mesh closes along the box faces.

Options:
  -o, --output FILE      output file (repeatable)
  --resolution N         cells along the longest side of the box (default 128; for the
                         surface of a point cloud's .ifl: cells of half the cloud's point
                         spacing, of the spacing for a smoothed noisy scan; 32 to 1024 along
                         the longest side)
  --cell H               cell size instead of --resolution
  --box X0,Y0,Z0,X1,Y1,Z1
                         region to mesh (default: the model's box)
  --threads T            worker threads (default: all cores)
  --subboxes K|KX,KY,KZ  sub-boxes per axis (default: at most 64 cells per sub-box, 16 for
                         point-cloud models, whose sub-boxes without surface are skipped)
  --no-project           keep the vertices at the linear interpolation of the grid values
  --smooth K             K sweeps of seed 003's smoothing functional (vertices slide over the
                         surface onto creases; costs about 3000 evaluations per vertex and sweep)
  --flip                 edge flips that raise the smallest angle (after smoothing)
  --set NAME=VALUE       .rf: override a 'param NAME = ...;' of the model (repeatable)
  --var NAME             .rf: mesh the variable NAME instead of res
  --view AZ,EL           preview camera azimuth and elevation in degrees (default 45,25)
  --mesh-precision double|single
                         coordinates in .ply and .obj files (default double: exact; .stl
                         is single precision by definition, .off too)
  --max-grid-nodes N     largest grid --resolution or --cell may ask for (default 1100000000,
                         each node one evaluation of the model)
  --max-triangles N      largest mesh (default 20000000, about 4.5 GB of memory)
  --max-model-size N     work the model may expand to: expression nodes, function calls,
                         Bezier samples (default 5000000)
  -q, --quiet            no progress or warnings on stderr
  -h, --help             this help

Examples:
  interlin mesh data/models/impeller.rf -o impeller.stl --resolution 256
  interlin mesh data/models/uav.rf -o uav.ply -o uav.png --cell 0.02
  interlin mesh data/models/valve.rf -o valve.obj --resolution 96 --smooth 4 --flip
  interlin mesh data/models/car.rf -o car_fig5.stl --var fig5 --set xs=7
  interlin mesh blade.ifl -o blade.stl --resolution 256

Volume meshes (--volume tet|hex; seed 003's solid elements, for finite-element analysis):
  outputs .vtu (ParaView), .msh (Gmsh 4.1), .inp (Abaqus/CalculiX), plus .stl .obj .ply .off
  (the boundary surface) and .png. Tetrahedra: the BCC lattice (grid nodes and cube centres,
  12 tetrahedra per cube with dihedral angles of 60 and 90 degrees; Labelle & Shewchuk's
  isosurface stuffing), those crossing F = 0 clipped at the roots of F on their edges (lattice
  nodes within 0.25 (axis edges) or 0.41 (centre edges) of an edge from F = 0 moved onto it);
  no element is inverted, walls from 1.5 cells thick are kept.
  Hexahedra: one per inside grid node (dual to the grid) as a core inside the body, and one
  pillow hexahedron from each of its boundary faces out to F = 0: the boundary nodes on
  F = 0 but the few held short of it where a pillow would fold, walls down to a node layer
  kept; where pillows stay folded after untangling (walls under a cell thick, oblique), the
  dual hexahedra alone (the summary's "layer" line says which). --boundary projected: seed
  003's layer: the grid cells wholly inside the body (nodes nearer to F = 0 than the margin
  count as outside) are kept and each boundary facet and its projection onto F = 0 make one
  hexahedron or a prism of 3 tetrahedra (walls thinner than about 4 cells are lost). Then
  the interior nodes minimise seed 003's corner functional (15), never folding an element
  further (not on the BCC lattice, whose angles it would only spoil).
  --volume tet|hex       tetrahedra or hexahedra
  --boundary B           tetrahedra: cut (the clipped lattice, default) or projected (seed 003's
                         layer); hexahedra: pillow (default, dual where pillows stay folded,
                         which --boundary pillow refuses instead), dual or projected
  --lattice L            tetrahedra, cut: bcc (default) or kuhn (the grid's cubes cut into 6
                         Kuhn tetrahedra, nodes within 0.2 of an edge moved: 0.55-0.8x the
                         elements, poorer angles)
  --margin M             projected layer: nodes nearer to F = 0 than M cells are outside
                         (default 0.35)
  --sweeps K             sweeps of the interior functional (default 8, none for BCC
                         tetrahedra, which it distorts; seed 003: 8-10)
  --seed-rule            seed 003's own classification (projected layer, margin 0; F > 0
                         for tetrahedra, F >= 0 for hexahedra): reproduces its published
                         counts
  --smooth K             K sweeps of functional (12) over the boundary nodes
  --adapt N              N passes of seed 003's adaptive refinement (§7.2): elements where
                         the nodal quantity changes by more than --adapt-delta of its range,
                         and their vertex neighbours, are split by conforming templates
                         (tetrahedra: 2, 4 or 8 children; hexahedra: 3-refinement, 5, 13 or
                         27 children, the refined nodes widened until every element has a
                         template; new boundary nodes onto F = 0), then the interior is
                         smoothed again
  --adapt-delta D        indicator threshold in [0, 1) (default 0.2)
  --adapt-var NAME       the nodal quantity: variable NAME of the .rf model (a stress estimate,
                         a distance to a load, ...); default the body function F itself
  --max-elements N       most elements the grid may hold, 12 tetrahedra (6 with --lattice
                         kuhn) or 1 hexahedron per cell, and the refined mesh of --adapt
                         (checked before each pass) (default 30000000 tetrahedra,
                         5000000 hexahedra: about 4 GB of memory when the body fills the grid)
  The summary gives the dihedral angles, scaled Jacobian, radius ratio (tetrahedra),
  inverted elements (an error unless 0), the boundary nodes on F = 0 (all but those held
  short of it or not projected) with max |F| there, and the volume; a body that reaches the
  box is warned about as for surface meshes.
  interlin mesh data/models/body11.rf -o body11.msh -o body11.vtu --volume tet --resolution 40
  interlin mesh data/models/body11.rf -o body11.inp --volume hex --resolution 20 --seed-rule
  interlin mesh data/models/body11.rf -o body11.vtu --volume tet --resolution 20 --adapt 2
  interlin mesh data/models/body11.rf -o body11.vtu --volume hex --resolution 20 --adapt 1
)";

namespace {

enum class Kind { mesh, png };

Kind output_kind(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".stl" || ext == ".obj" || ext == ".ply" || ext == ".off")
    return Kind::mesh;
  if (ext == ".png")
    return Kind::png;
  throw UsageError("output '" + path + "': unknown extension (use .stl .obj .ply .off .png)");
}

// The nodes of the grid that grid_with_resolution / grid_with_cell make for `box`, in floating
// point (the options may ask for more than any integer type holds).
double grid_node_estimate(const Eigen::AlignedBox3d& box, const ImplicitMeshOptions& o) {
  const Eigen::Array3d side = box.sizes().array();
  const double h = o.cell > 0 ? o.cell : side.maxCoeff() / o.resolution;
  return ((side / h - 1e-9).ceil().max(1.0) + 1).prod(); // as grid_with_step rounds
}

// Grid limits are usage errors (the options asked for them), checked before any work: the grid's
// nodes (time) and with --volume the elements its cells could hold (memory: 12 tetrahedra on the
// BCC lattice, 6 on Kuhn's, or 1 hexahedron per cell, and there are fewer cells than nodes).
void check_grid_limits(const ParsedArgs& a, const Eigen::AlignedBox3d& box,
                       const ImplicitMeshOptions& o) {
  const std::string asked = a.has("cell")         ? "--cell " + a.get("cell")
                            : a.has("resolution") ? "--resolution " + a.get("resolution")
                            : o.cell > 0
                                ? "the default cell " + fmt(o.cell, 4)
                                : "the default --resolution " + std::to_string(o.resolution);
  const double n = grid_node_estimate(box, o);
  const long long max_nodes = limit_option(a, "max-grid-nodes", limits::grid_nodes);
  if (n > double(max_nodes))
    options_exceed(asked, "a grid of " + fmt(n, 3) + " nodes", max_nodes, "max-grid-nodes");
  if (!a.has("volume"))
    return;
  const bool hex = a.get("volume") == "hex";
  const double elements = n * (hex ? 1 : a.get("lattice", "bcc") == "kuhn" ? 6 : 12);
  const long long max_elements = volume_element_limit(a);
  if (elements > double(max_elements))
    options_exceed(asked, "up to " + fmt(elements, 3) + " volume elements", max_elements,
                   "max-elements");
}

// The grid and sub-box options of `interlin mesh` (usage errors for bad values).
ImplicitMeshOptions grid_options(const ParsedArgs& a) {
  if (a.has("resolution") && a.has("cell"))
    throw UsageError("--resolution and --cell exclude each other");
  ImplicitMeshOptions o;
  o.resolution = parse_int("resolution", a.get("resolution", "128"), 1, 1000000000);
  o.max_triangles = limit_option(a, "max-triangles", limits::mesh_triangles);
  if (a.has("cell")) {
    o.cell = parse_double("cell", a.get("cell"));
    if (!(o.cell > 0))
      throw UsageError("--cell: the cell size must be > 0");
  }
  if (a.has("box")) {
    const std::vector<double> b = parse_double_list("box", a.get("box"));
    if (b.size() != 6)
      throw UsageError("--box: expected X0,Y0,Z0,X1,Y1,Z1 (6 numbers), got " +
                       std::to_string(b.size()));
    o.box =
        Eigen::AlignedBox3d(Eigen::Vector3d(b[0], b[1], b[2]), Eigen::Vector3d(b[3], b[4], b[5]));
    if (!(b[3] > b[0] && b[4] > b[1] && b[5] > b[2]))
      throw UsageError("--box: each upper bound must exceed its lower bound");
  }
  o.threads = parse_int("threads", a.get("threads", "0"), 0, 4096);
  if (a.has("subboxes")) {
    const std::vector<int> k = parse_int_list("subboxes", a.get("subboxes"), 1);
    if (k.size() != 1 && k.size() != 3)
      throw UsageError("--subboxes: expected K or KX,KY,KZ");
    o.subboxes = k.size() == 1 ? Eigen::Array3i::Constant(k[0]) : Eigen::Array3i(k[0], k[1], k[2]);
  }
  o.project = !a.has("no-project");
  return o;
}

// Options that belong to one of surface or volume meshes, and the outputs' kinds (surface meshes;
// empty for --volume): usage errors before any work.
std::map<std::string, Kind> checked_outputs(const ParsedArgs& a,
                                            const std::vector<std::string>& outputs) {
  if (outputs.empty())
    throw UsageError("nothing to do: give -o FILE");
  const bool volume = a.has("volume");
  for (const char* only : {"margin", "boundary", "sweeps", "seed-rule", "max-elements", "adapt",
                           "adapt-delta", "adapt-var", "lattice"})
    if (!volume && a.has(only))
      throw UsageError(std::string("--") + only + " needs --volume tet|hex");
  if (volume && (a.has("subboxes") || a.has("no-project") || a.has("flip")))
    throw UsageError("--subboxes, --no-project and --flip apply to surface meshes, not --volume");
  std::map<std::string, Kind> kinds;
  for (const std::string& out : outputs) {
    if (volume && !volume_output_ok(out))
      throw UsageError("output '" + out +
                       "': unknown extension for --volume (use .vtu .msh .inp .stl .obj .ply .off "
                       ".png)");
    if (!volume)
      kinds[out] = output_kind(out);
  }
  return kinds;
}

// The grid the options ask for on `box` exists and can hold the sub-boxes (usage errors).
void check_grid(const ParsedArgs& a, const Eigen::AlignedBox3d& box, const ImplicitMeshOptions& o) {
  check_grid_limits(a, box, o);
  try {
    const RegularGrid g =
        o.cell > 0 ? grid_with_cell(box, o.cell) : grid_with_resolution(box, o.resolution);
    for (int ax = 0; ax < 3; ++ax)
      if (o.subboxes(ax) > g.nodes(ax) - 1)
        throw std::invalid_argument("--subboxes: " + std::to_string(o.subboxes(ax)) +
                                    " sub-boxes along axis " + std::to_string(ax) + " but only " +
                                    std::to_string(g.nodes(ax) - 1) + " cells");
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// Whether the options' grid limits allow meshing `box` at `cell` (a default grid refined).
bool grid_allowed(const ParsedArgs& a, const Eigen::AlignedBox3d& box, ImplicitMeshOptions o,
                  double cell) {
  o.cell = cell;
  try {
    check_grid(a, box, o);
    return true;
  } catch (const UsageError&) {
    return false;
  }
}

// Surface mesh: marching cubes, then the optional smoothing and edge flips; warnings on stderr.
void surface_mesh(const ImplicitFunction& f, const std::string& input, ImplicitMeshOptions& o,
                  int smooth, bool flip, bool quiet, const Progress& progress, Eigen::MatrixXd& V,
                  Eigen::MatrixXi& F, ImplicitMeshInfo& info) {
  o.progress = progress;
  implicit_mesh(f, o, V, F, &info);
  if (!quiet && info.nonfinite > 0)
    std::cerr << "warning: " << info.nonfinite
              << " sampled values were NaN or infinite (taken as outside, +inf as inside)\n";
  warn_body_reaches_box(info.clipped, quiet);
  if (F.rows() == 0)
    throw_input_error(input, 0,
                      "no surface in the box: F > 0 at none of the " +
                          std::to_string(info.grid.size()) +
                          " grid nodes (refine the grid or "
                          "check the box)");
  if (smooth > 0) {
    progress("smoothing, " + std::to_string(smooth) + " sweeps (seed 003 functional)");
    SurfaceSmoothingOptions so;
    so.iterations = smooth;
    so.threads = o.threads;
    smooth_on_surface(f, V, F, so);
  }
  if (flip) {
    progress("edge flips");
    const long n = flip_edges(V, F);
    progress(std::to_string(n) + " edges flipped");
  }
}

// The box's side along `axis` as "[lo, hi]", with 4 significant digits of its length however far
// it lies from the origin.
std::string interval(const Eigen::AlignedBox3d& box, int axis) {
  const double lo = box.min()(axis), hi = box.max()(axis);
  const double far = std::max(std::abs(lo), std::abs(hi)), side = hi - lo;
  const int digits = side > 0 && far > side ? 4 + int(std::ceil(std::log10(far / side))) : 4;
  return "[" + fmt(lo, digits) + ", " + fmt(hi, digits) + "]";
}

// The surface mesh's summary on stdout; an error when it is not watertight.
void print_surface_summary(const std::string& input, const Eigen::AlignedBox3d& box,
                           const ImplicitMeshOptions& o, const ImplicitMeshInfo& info,
                           const MeshReport& r, const std::string& grid_note) {
  const RegularGrid& g = info.grid;
  std::cout << "interlin mesh " << input << "\n";
  std::cout << "  box          " << interval(box, 0) << " x " << interval(box, 1) << " x "
            << interval(box, 2) << "\n";
  std::cout << "  grid         " << g.nodes(0) << " x " << g.nodes(1) << " x " << g.nodes(2)
            << " nodes, cell " << fmt(g.spacing(0)) << grid_note << ", " << info.subboxes(0)
            << " x " << info.subboxes(1) << " x " << info.subboxes(2) << " sub-boxes"
            << (info.skipped > 0 ? " (" + std::to_string(info.skipped) + " without surface skipped)"
                                 : std::string())
            << ", "
            << (o.threads > 0 ? o.threads : int(std::max(1u, std::thread::hardware_concurrency())))
            << " threads\n";
  std::cout << "  mesh         " << r.vertices << " vertices, " << r.faces << " triangles, "
            << (r.watertight() ? "watertight" : "NOT watertight") << ", Euler " << r.euler
            << ", genus " << r.genus << ", " << r.components << " component"
            << (r.components == 1 ? "" : "s") << "\n";
  std::cout << "  geometry     volume " << fmt(r.volume, 7) << ", area " << fmt(r.area, 7) << "\n";
  std::cout << "  quality      min angle " << fmt(r.min_angle_deg, 3) << " deg, max aspect ratio "
            << fmt(r.max_aspect_ratio, 4)
            << (o.project ? ", vertices on F = 0" : ", vertices interpolated") << "\n";
  if (!r.watertight())
    throw std::runtime_error("the mesh is not watertight (boundary edges " +
                             std::to_string(r.boundary_edges) + ", non-manifold edges " +
                             std::to_string(r.nonmanifold_edges) + ", degenerate faces " +
                             std::to_string(r.degenerate_faces) + ")");
}

// The body of `interlin mesh` (run_command handles help, exit statuses and removal on failure).
void mesh_main(const ParsedArgs& a, std::vector<std::string>& written) {
  const std::string input = single_input(a, "model file");
  ImplicitMeshOptions o = grid_options(a);
  const int smooth = parse_int("smooth", a.get("smooth", "0"), 0, 1000);
  const bool flip = a.has("flip"), quiet = a.has("quiet");
  const auto [azimuth, elevation] = parse_int_pair("view", a.get("view", "45,25"), -360, 360);
  const MeshPrecision precision = mesh_precision(a);
  const std::vector<std::string> outputs = a.all("output");
  const std::map<std::string, Kind> kinds = checked_outputs(a, outputs);
  check_outputs({input}, outputs);
  const ModelOptions mo = model_file_options(a, input, SettingLabel::name);

  const Progress progress{quiet};
  progress("reading " + input);
  const ImplicitFunction f = load_implicit(input, mo);
  const Eigen::AlignedBox3d box = o.box.isEmpty() ? f.box : o.box;
  const bool default_grid = !a.has("resolution") && !a.has("cell");
  // a surface of a model fitted to points: cells of half the detail it resolves by default
  if (default_grid && !a.has("volume") && f.sample_spacing > 0)
    o.cell = default_mesh_cell(f, box);
  check_grid(a, box, o);
  if (a.has("volume")) {
    VolumeRequest r;
    r.input = input;
    r.box = box;
    r.resolution = o.resolution;
    r.cell = o.cell;
    r.threads = o.threads;
    r.smooth = smooth;
    r.outputs = outputs;
    r.quiet = quiet;
    r.azimuth = azimuth;
    r.elevation = elevation;
    r.model = mo;
    r.default_grid = default_grid;
    r.grid_allowed = [&](double cell) { return grid_allowed(a, box, o, cell); };
    mesh_volume(a, f, r, progress, written);
    return;
  }
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  ImplicitMeshInfo info;
  surface_mesh(f, input, o, smooth, flip, quiet, progress, V, F, info);
  progress("checking the mesh");
  MeshReport report = check_mesh(V, F);
  SagCheck sag = check_sag(f, V, F, report.volume, info.grid.spacing(0), o.threads, progress);
  std::string grid_note;
  if (default_grid && report.watertight())
    grid_note = refine_for_sag(
        sag, [&](double cell) { return grid_allowed(a, box, o, cell); },
        [&](double cell) {
          o.cell = cell;
          surface_mesh(f, input, o, smooth, flip, quiet, progress, V, F, info);
          progress("checking the mesh");
          report = check_mesh(V, F);
          return check_sag(f, V, F, report.volume, info.grid.spacing(0), o.threads, progress);
        },
        progress);
  print_surface_summary(input, box, o, info, report, grid_note);
  print_sag(sag, quiet);
  for (const std::string& out : outputs) {
    progress("writing " + out);
    if (kinds.at(out) == Kind::mesh) {
      warn_single_precision(out, V, precision, quiet);
      write_mesh(out, V, F, precision);
    } else {
      PreviewOptions po;
      po.azimuth_deg = azimuth;
      po.elevation_deg = elevation;
      po.up = Eigen::Vector3d::UnitZ();
      write_preview_png(out, V, F, {}, po);
    }
    written.push_back(out);
  }
  print_written(written);
  progress("done");
}

} // namespace

int run_mesh(int argc, const char* const* argv) {
  std::vector<OptionSpec> spec = volume_options();
  spec.insert(spec.end(), {{"output", 'o', true, true},
                           {"resolution", 0, true, false},
                           {"cell", 0, true, false},
                           {"box", 0, true, false},
                           {"threads", 0, true, false},
                           {"subboxes", 0, true, false},
                           {"no-project", 0, false, false},
                           {"smooth", 0, true, false},
                           {"flip", 0, false, false},
                           {"set", 0, true, true},
                           {"var", 0, true, false},
                           {"view", 0, true, false},
                           {"max-grid-nodes", 0, true, false},
                           {"max-triangles", 0, true, false},
                           {"mesh-precision", 0, true, false},
                           {"max-model-size", 0, true, false}});
  return run_command("mesh", kMeshHelp, argc, argv, spec, mesh_main);
}

} // namespace interlin::cli
