#pragma once
// interlin mesh --volume tet|hex: the volume-mesh half of `interlin mesh` (seed 003's solid
// elements), called by cmd_mesh.cpp once the model and the grid options are read.

#include "cli_common.h"

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/reconstruction/meshing/facet_sag.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <functional>
#include <string>
#include <vector>

namespace interlin::cli {

// What cmd_mesh.cpp has already parsed and checked.
struct VolumeRequest {
  std::string input;                // model file (for the summary and errors)
  Eigen::AlignedBox3d box;          // region (the model's box unless --box)
  int resolution = 128;             // --resolution ...
  double cell = 0;                  // ... or --cell
  int threads = 0;                  // --threads
  int smooth = 0;                   // --smooth: functional (12) sweeps on the boundary
  std::vector<std::string> outputs; // -o files (extensions checked by volume_output_ok)
  int azimuth = 45, elevation = 25; // --view of the .png preview
  bool quiet = false;
  ModelOptions model; // how the model was read (--set, --var), for --adapt-var
  // Neither --resolution nor --cell given: the grid is refined where the mesh's facets leave
  // out more than kLostVolumeWarning of the volume, if grid_allowed(cell) (the limits).
  bool default_grid = false;
  std::function<bool(double cell)> grid_allowed;
};

// Whether `path` is an output `interlin mesh --volume` can write (.vtu .msh .inp for the
// elements, .stl .obj .ply .off for the boundary surface, .png for its preview).
bool volume_output_ok(const std::string& path);

// --max-elements: the element limit of the grid and of --adapt's refined mesh (default
// limits::volume_hexahedra with --volume hex, else limits::volume_tetrahedra).
long long volume_element_limit(const ParsedArgs& a);

// The volume options of `interlin mesh` (--volume, --boundary, --margin, --sweeps, --seed-rule,
// --adapt, --adapt-delta, --adapt-var, --max-elements) for the parser.
std::vector<OptionSpec> volume_options();

// A mesh's boundary facets B (#B by 3 or 4) against F = 0 (facet_sag), the sag as a fraction of
// the mesh's volume, at cell h.
struct SagCheck {
  FacetSag sag;
  double fraction = 0;
  double h = 0;
};
SagCheck check_sag(const ImplicitFunction& f, const Eigen::MatrixXd& V, const Eigen::MatrixXi& B,
                   double volume, double h, int threads, const Progress& progress);

// A mesh on a default grid whose check `last` misses (or adds) more than kLostVolumeWarning of
// the body's volume is made again, up to twice, at a finer cell (cell_for_sag's h^2, on the second
// pass the order observed between the two meshes, clamped to [0.5, 2]; at most 4 times finer than
// the first), while allowed(cell) (the grid limits): remesh(cell) meshes at that cell and returns
// the new mesh's check, which becomes `last`. Returns the summary's grid-line note on the
// refinement ("" for none).
std::string refine_for_sag(SagCheck& last, const std::function<bool(double cell)>& allowed,
                           const std::function<SagCheck(double cell)>& remesh,
                           const Progress& progress);

// The sag line of the summary on stdout and, above kLostVolumeWarning of the volume, a warning
// on stderr naming the cell at which it would be within.
void print_sag(const SagCheck& c, bool quiet);

// Parses the volume options, meshes, prints the summary, writes the outputs (appending each to
// `written`). Throws UsageError for bad options, InputError for a model without a body in the
// box, std::runtime_error for a mesh that fails its checks (inverted elements).
void mesh_volume(const ParsedArgs& a, const ImplicitFunction& f, const VolumeRequest& r,
                 const Progress& progress, std::vector<std::string>& written);

} // namespace interlin::cli
