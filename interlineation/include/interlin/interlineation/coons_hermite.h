#pragma once
// C1 (Hermite) Coons interlineation, digest 001 §5.2 [SUPPLEMENT]: on a cell [x_0,x_1] x [y_0,y_1]
// with h = x_1 - x_0, s = (x - x_0)/h,
//   H_0 = 1 - 3s^2 + 2s^3, H_1 = 3s^2 - 2s^3, K_0 = h (s - 2s^2 + s^3), K_1 = h (s^3 - s^2),
//   P_x f = H_0 f(x_0,y) + H_1 f(x_1,y) + K_0 f_x(x_0,y) + K_1 f_x(x_1,y),  P_y likewise,
//   O = P_x + P_y - P_x P_y  (the twist term needs f, f_x, f_y, f_xy at the corners).
// On a grid the cells share value and normal-derivative traces, so the composite operator is C1;
// O reproduces f and its normal derivative on every line, and f - O f = (I - P_x)(I - P_y) f.

#include "interlin/interlineation/line_traces.h"

namespace interlin {

// Value traces on both families plus normal-derivative traces:
//   dx_on_x[i](y, d) = d^d/dy^d f_x(x_i, y),   dy_on_y[j](x, d) = d^d/dx^d f_y(x, y_j).
// twists (optional, (#x * #y) by dim, row i + #x * j): f_xy at the crossings; when empty they
// are taken from the traces (d/dy of dx_on_x and d/dx of dy_on_y, which must agree).
struct HermiteTraces {
  LineTraces values;
  std::vector<Trace> dx_on_x, dy_on_y;
  Eigen::MatrixXd twists;
};

// The operator with its corner data, each (#x * #y) by dim, row i + #x * j.
struct HermiteCoons {
  HermiteTraces traces;
  Eigen::MatrixXd f, fx, fy, fxy;
  Eigen::Index dim = 0;
};

// Inputs: >= 2 lines per family. The traces must be compatible at every crossing: values,
// f_x (dx_on_x against d/dx of on_y), f_y (dy_on_y against d/dy of on_x) and the twist, to
// within tolerance * max(1, |value|); std::invalid_argument names the first violation.
HermiteCoons coons_hermite(const HermiteTraces& traces, double tolerance = 1e-10);

// d^(dx+dy) (O f) / dx^dx dy^dy at (x, y) inside the grid, dx, dy <= 3 within a cell.
Eigen::RowVectorXd evaluate(const HermiteCoons& O, double x, double y, int dx = 0, int dy = 0);

// The cubic Hermite cardinal functions of the nodes at x and their derivative of order d:
// H(i) (value cardinal, H_i(x_k) = delta_ik, H_i'(x_k) = 0) and K(i) (slope cardinal,
// K_i(x_k) = 0, K_i'(x_k) = delta_ik). x must lie in [nodes(0), nodes(end)].
void hermite_cardinals(const Eigen::VectorXd& nodes, double x, int d, Eigen::VectorXd& H,
                       Eigen::VectorXd& K);

} // namespace interlin
