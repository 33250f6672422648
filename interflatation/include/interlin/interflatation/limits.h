#pragma once
// Resource limits: how much stack, memory and time one input file or one option may claim
// (README "Limits", docs/reliability.md). Every limit of the toolkit is named here. The stack
// limits are fixed (recursive passes over a model's expression need them); the others are
// defaults that a command-line option raises (--max-NAME, given in each limit's comment).
// Readers of the data files (sections, guides, points, IGES, surface JSON) need no limit: they
// use memory proportional to the file.

#include <stdexcept>
#include <string>

namespace interlin {

// A limit was reached. The message says what asked for how much and names the limit; `option`
// is the command-line option that raises it ("" for a fixed limit).
struct LimitError : std::runtime_error {
  LimitError(const std::string& what, std::string option_name)
      : std::runtime_error(what), option(std::move(option_name)) {}
  std::string option;
};

namespace limits {

// .rf models, stack: parentheses, calls and lists nested in one expression.
inline constexpr int model_nesting = 500;
// .rf models, stack: the longest chain of operations below one value, e.g. a sum of that many
// terms; the passes over an expression (differentiation, substitution, compilation) recurse
// along it.
inline constexpr int expression_depth = 20000;
// .rf models, stack: user functions expanded inside user functions.
inline constexpr int call_depth = 200;
// .rf models, memory and time: expression nodes built, function calls expanded and Bezier
// sampling work (segments x control points^2) while reading one model (a node is about 100
// bytes; the seed models need 276 to 72 276); --max-model-size.
inline constexpr long long model_size = 5'000'000;
// interlin loft and interlin mesh, memory: triangles of the mesh (the commands peak at about
// 220 bytes per triangle, so about 4.5 GB); --max-triangles.
inline constexpr long long mesh_triangles = 20'000'000;
// interlin mesh, time: nodes of the sampling grid, each one evaluation of the model (a cube
// box at --resolution 1024 fits); --max-grid-nodes.
inline constexpr long long grid_nodes = 1'100'000'000;
// interlin mesh --volume, memory: elements the grid's cells could hold (12 tetrahedra on the BCC
// lattice, 6 on Kuhn's, or 1 hexahedron per cell; an upper bound, checked before any work). The
// command peaks at about 120-130 bytes per tetrahedron on either lattice (a box-filling cuboid at
// resolutions 32 to 64; 160 before session 18) and 720-810 per hexahedron (resolutions 64 to 96,
// pillowed or projected: the coverage measurement clips 6 tetrahedra per cell), so both defaults
// mean about 4 GB when the body fills the grid (30 M tetrahedra: BCC at the default resolution
// 128 asks for up to 25.8 M); --max-elements.
inline constexpr long long volume_tetrahedra = 30'000'000;
inline constexpr long long volume_hexahedra = 5'000'000;
// interlin implicit, memory: nodes of the model's grid, counted before any work as for a cube
// box, (resolution + 5)^3 (the grid reaches two cells beyond the box). Building a section body
// peaks at about 1 KB per node (resolutions 32 to 128), so about 4 GB; --max-grid-nodes.
inline constexpr long long implicit_grid_nodes = 4'000'000;
// interlin profile, memory and time: profile points written, stations x points per profile;
// --max-points.
inline constexpr long long profile_points = 10'000'000;

} // namespace limits
} // namespace interlin
