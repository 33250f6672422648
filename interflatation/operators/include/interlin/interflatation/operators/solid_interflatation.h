#pragma once
// Theorem 5 of seed 001 (§2.8): the interflatation operator of a body G with grid planes
// x = x_i, y = y_j, z = z_k, and from it the implicit equation Ou = 0 of dG.
//
// Cells [x_i, x_i+1] x [y_j, y_j+1] x [z_k, z_k+1] are cut by dG into pieces, each written in
// mapped form (digest §5.3-5.4 [SUPPLEMENT], the mapping of the curved cells generalised to 3-D):
// along the cell's mapping axis m every point lies on the chord [lo, hi] of its line inside the
// cell, t3 = (p_m - lo) / (hi - lo); the chord's ends are on the cell's planes z_k / z_k+1
// ("grid") or on dG. The cross-section D of the piece (the points of the cell's face rectangle
// whose chords have the same ends, grid or dG) is a plane region, mapped by the operator of
// Theorem 4 (region_interlineation.h) to (s, t2) in [0, 1]^2. In (s, t2, t3) the cell operator
// is the trilinear Boolean sum (T14, digest §5 item 4)
//   O = P1 + P2 + P3 - P1P2 - P1P3 - P2P3 + P1P2P3,
// exact on the six faces of the mapped cube: the two chord-end surfaces (a grid plane or dG), the
// two sides s = 0, 1 (grid planes, or planes where D's chord structure changes) and t2 = 0, 1
// (grid planes, or surfaces where the chord structure changes or the chord shrinks to a point
// of dG). The seed's cells are the pieces whose D is the whole face rectangle: boxes (both
// chord ends on grid planes) and boxes with one curved face (one end on dG; 6 orientations:
// mapping axis x 2 ends), and the pieces with one end on dG whose D is bounded by dG itself:
// pyramids with a curved face (D has a curved side, the chord shrinks to a point there).
//
// Traces: the restrictions of one function u to the planes, with the seed's zero substitution
// on dG: on a chord [lo, hi] of the mapping axis, trace = u - (the linear interpolant of u's
// values at the chord's ends on dG), which is 0 on dG and equals u when u = 0 on dG. With
// u = 0 on dG the traces are compatible (they agree where planes cross), Ou is continuous and
// Ou = u on every grid plane (Ou = u on GXYZ, Theorem 5); for any u, Ou = 0 on dG (the
// theorem's independence claim; T19 in 3-D). Outside G, Ou = 0.
//
// Free traces: as in 2-D, taking u = w (the target: the distance to dG or an R-function) makes
// Ou interpolate w on every grid plane.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <functional>
#include <memory>
#include <vector>

namespace interlin {

// A body G inside `box`.
//   chords(axis, p, lo, hi)  the intervals of the line through p along `axis` (p(axis) is
//                            ignored) that lie in G, clipped to [lo, hi]: increasing, disjoint
//                            pairs (lo_0, hi_0, lo_1, hi_1, ...); their ends are on dG or at
//                            lo / hi
struct SolidBoundary {
  Eigen::AlignedBox3d box;
  std::function<std::vector<double>(int axis, const Eigen::Vector3d& p, double lo, double hi)>
      chords;
};

// G = {g > 0} in `box`. Chords are the runs of g > 0 among `samples` equally spaced points of
// [lo, hi] (one cell when the operators ask), their ends refined by bisection to round-off; a
// run shorter than the sample spacing can be missed. Throws std::invalid_argument for
// samples < 2 or an empty box.
SolidBoundary implicit_solid(std::function<double(const Eigen::Vector3d&)> g,
                             const Eigen::AlignedBox3d& box, int samples = 8);

// The seed's cell kinds (per piece); `split` is any other piece (a cell whose chord structure
// changes inside it, or chords with both ends on dG).
enum class SolidCellKind { box, curved_box, pyramid, split };

struct SolidInterflatation {
  SolidBoundary boundary;
  std::array<Eigen::VectorXd, 3> nodes;
  std::function<double(const Eigen::Vector3d&)> u;
  // The mapping axis of every cell, or -1: per cell, chosen on first use.
  int mapping_axis = -1;
  int samples = 12;
  // The cells' mapping axes and the cross-sections D of the pieces, found on first use (shared
  // by copies; thread-safe).
  struct Cache;
  std::shared_ptr<Cache> cache;
};

// Inputs:
//   boundary      the body
//   nodes         per axis, increasing plane positions covering boundary.box (>= 2 each)
//   u             the function whose restrictions are the traces (finite in G)
//   mapping_axis  0, 1, 2: the mapping axis of every cell; -1: per cell, the axis whose
//                 cross-section has the fewest distinct chord structures (probed on 5 x 5 points)
//   samples       probes per cell side for the cross-sections (region_interlineation samples)
// Throws std::invalid_argument for fewer than 2 planes per axis, non-increasing planes, planes
// that do not cover the box or a mapping axis outside -1..2.
SolidInterflatation solid_interflatation(const SolidBoundary& boundary,
                                         const std::array<Eigen::VectorXd, 3>& nodes,
                                         std::function<double(const Eigen::Vector3d&)> u,
                                         int mapping_axis = -1, int samples = 12);

// Ou at p (0 outside G and outside the grid).
double evaluate(const SolidInterflatation& O, const Eigen::Vector3d& p);

// The kind of the piece holding p (split when p is outside G).
SolidCellKind cell_kind(const SolidInterflatation& O, const Eigen::Vector3d& p);

} // namespace interlin
