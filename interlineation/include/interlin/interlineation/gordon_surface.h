#pragma once
// Gordon (spline-blended) interlineation on a line grid, digest 001 §5.1 [SUPPLEMENT]:
//   O f = P_x f + P_y f - P_x P_y f,
//   P_x f(x, y) = sum_i alpha_i(x) f(x_i, y),   P_y f(x, y) = sum_j beta_j(y) f(x, y_j),
// with cardinal blending functions alpha_i(x_k) = delta_ik, beta_j(y_l) = delta_jl. O reproduces
// every trace exactly (interlineation) and f - O f = (I - P_x)(I - P_y) f. With degree-1 blending
// O is the bilinearly blended Coons operator on every cell (seed 001 Theorem 3, composite Coons).
// Coons' and Gordon's methods are special cases of interlineation (seed 001 §2.5).

#include "interlin/interlineation/cardinal_splines.h"
#include "interlin/interlineation/line_traces.h"

namespace interlin {

// Blending of the Boolean sum. Degrees 1 (C0), 2 (C1), 3 (C2); a periodic direction blends with
// periodic cardinal splines (degree 1 or 3) over [first line, first line + period).
struct GordonOptions {
  int degree_x = 3, degree_y = 3;
  bool periodic_x = false, periodic_y = false;
  double period_x = 0, period_y = 0;
  double tolerance = 1e-10; // compatibility of the traces at the crossings (crossing_values)
};

// The operator with its data. alpha/beta are empty (no nodes) when that family has no lines.
//   corners  f(x_i, y_j), (#x * #y) by dim, row i + #x * j
struct GordonSurface {
  LineTraces traces;
  CardinalSplines alpha, beta;
  Eigen::MatrixXd corners;
  Eigen::Index dim = 0;
};

// Inputs: traces on at least one family (>= 2 lines in an open direction, >= 1 in a periodic
// one), compatible at the crossings. Throws std::invalid_argument for incompatible traces (the
// message names the crossing), bad options or too few lines.
GordonSurface gordon_surface(const LineTraces& traces, const GordonOptions& options = {});

// seed 001 Theorem 3 operator on one cell [x_0, x_1] x [y_0, y_1]: exactly two lines per family,
// linear blending (x - x_1)/(x_0 - x_1), ...
GordonSurface coons_bilinear(const LineTraces& cell, double tolerance = 1e-10);

// Composite bilinear Coons: linear (hat) blending on any grid, i.e. coons_bilinear on every cell
// [x_i, x_{i+1}] x [y_j, y_{j+1}] with the shared traces; C0, O(h_x^2 h_y^2) (digest T13).
GordonSurface coons_composite(const LineTraces& grid, double tolerance = 1e-10);

// d^(dx+dy) (O f) / dx^dx dy^dy at (x, y): a row of dim values. Open directions must be
// evaluated inside [first line, last line] (std::invalid_argument otherwise); a direction
// without lines is unbounded (the traces' own domain).
Eigen::RowVectorXd evaluate(const GordonSurface& O, double x, double y, int dx = 0, int dy = 0);

} // namespace interlin
