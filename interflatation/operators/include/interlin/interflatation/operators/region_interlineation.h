#pragma once
// Theorem 4 of seed 001 (§2.7): the interlineation operator of a plane region G with grid lines
// x = x_k, y = y_l, and from it the implicit equation Ou = 0 of dG.
//
// Cells [x_i, x_i+1] x [y_j, y_j+1] are cut by dG into pieces; each piece is a cell of the seed's
// classification, written in mapped form (digest §5.3 [SUPPLEMENT], the mapping of the curved
// quadrangle R(1) generalised): along the mapping axis m (y for the quadrangles with a curved top
// or bottom, x for a curved left or right side) every point lies on the chord [lo, hi] of its
// line inside the piece, t = (p_m - lo) / (hi - lo), and along the other axis the piece spans
// [a, b], s = (p_q - a) / (b - a):
//   Ou = (1-s) L(t) + s R(t) + (1-t) B(p_q) + t T(p_q)
//        - [(1-s)(1-t) L(0) + s(1-t) R(0) + (1-s) t L(1) + s t R(1)],
// bilinear Coons in (s, t). L, R are the traces on the chords of the lines p_q = a and p_q = b
// (a degenerate chord - a triangle's apex - gives 0); B, T are the trace of the grid line where
// lo / hi is a grid line, and 0 where lo / hi is on dG. At t = 1 on dG, Ou = T = 0 whatever L, R
// and B are: Ou vanishes on dG for any free traces (the theorem's claim; T19). Pieces are
// rectangles (both chord ends on grid lines), curved quadrangles (one end on dG), curved
// triangles (a degenerate side), or lenses (both ends on dG); a cell whose chord structure
// changes inside it (dG crosses a grid line inside the cell, or turns) is split there.
//
// Traces: the restrictions of one function u to the lines, with the seed's zero substitution on
// dG: on a chord [c0, c1] of a line in G, trace = u - (the linear interpolant of u's values at
// c0 and c1), which is 0 at both ends and equals u when u = 0 on dG. Traces of one function are
// compatible at every crossing of grid lines when u = 0 on dG, so Ou is continuous and equals u
// on every grid line (Ou = u on GXY). Outside G, Ou = 0 (as the theorem states).
//
// Free traces: choosing u = w (the target: the distance to dG or an R-function) is the criterion
// used here - Ou interpolates w on every grid line; max |Ou - w| is then the interpolation error
// of the cells (T16, T17).

#include "interlin/interflatation/operators/plane_boundary.h"

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

namespace interlin {

// The seed's cell kinds (per piece).
enum class CellKind {
  rectangle,
  curved_top,
  curved_bottom,
  curved_left,
  curved_right,
  triangle,
  lens
};

// One piece of a cell: its span [a, b] along the piece axis, the mapping axis (1: chords along y,
// 0: along x), which chord of the lines it is (0 = lowest chord of the cell), whether its side
// at a / b is an apex (the chord shrinks to a point of dG there: trace 0) and its kind.
struct CellPiece {
  int mapping_axis = 1;
  double a = 0, b = 0;
  int chord = 0;
  bool apex_a = false, apex_b = false;
  CellKind kind = CellKind::rectangle;
};

struct RegionInterlineation {
  PlaneBoundary boundary;
  Eigen::VectorXd x, y;
  std::function<double(const Eigen::Vector2d&)> u;
  // Per cell (i + (#x - 1) j), its pieces in increasing a (then chord).
  std::vector<std::vector<CellPiece>> pieces;
};

// Inputs:
//   boundary  the region (plane_boundary.h)
//   x, y      increasing grid lines covering boundary.box (x_0 <= box min, x_last >= box max)
//   u         the function whose restrictions are the traces (finite in G)
//   samples   positions per cell at which the chord structure is probed to find where it
//             changes (then refined by bisection)
// Throws std::invalid_argument for fewer than 2 lines per axis, non-increasing lines or lines
// that do not cover the box.
RegionInterlineation region_interlineation(const PlaneBoundary& boundary, const Eigen::VectorXd& x,
                                           const Eigen::VectorXd& y,
                                           std::function<double(const Eigen::Vector2d&)> u,
                                           int samples = 16);

// Ou at p (0 outside G and outside the grid).
double evaluate(const RegionInterlineation& O, const Eigen::Vector2d& p);

// Where p lies in its piece (the mapped frame of the Coons formula above):
//   piece          the piece holding p; q = 1 - piece.mapping_axis is the piece axis
//   y0, y1         the cell's range along the mapping axis
//   s, t           p's mapped coordinates in [0, 1]^2
//   chord          p's chord [lo, hi] on the line {p(q) = p(q)} and whether its ends are grid lines
//   side[0], [1]   the chords of the piece's sides p(q) = a and p(q) = b; apex when the side
//                  shrinks to a point
// False when p is outside G or outside the grid. Used by the 3-D operators (Theorem 5) to
// parametrise cross-sections of their cells.
struct PieceFrame {
  struct Chord {
    bool apex = false;
    double lo = 0, hi = 0;
    bool lo_grid = true, hi_grid = true;
  };
  CellPiece piece;
  double y0 = 0, y1 = 0, s = 0, t = 0;
  Chord chord;
  std::array<Chord, 2> side;
};
bool piece_frame(const RegionInterlineation& O, const Eigen::Vector2d& p, PieceFrame& frame);

// The trace of line {p(axis) = c} at the point whose other coordinate is s: u minus the linear
// interpolant of u at the ends of the chord holding s (0 off the chords).
double line_trace(const RegionInterlineation& O, int axis, double c, double s);

} // namespace interlin
