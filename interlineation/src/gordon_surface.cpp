// digest 001 §5.1 [SUPPLEMENT]: Gordon / spline-blended Boolean sum; seed 001 Theorem 3 (Coons).
#include "interlin/interlineation/gordon_surface.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::VectorXd;

namespace {

CardinalSplines blending(const VectorXd& nodes, int degree, bool periodic, double period,
                         const char* name) {
  if (nodes.size() == 0)
    return {};
  if (periodic)
    return periodic_cardinal_splines(nodes, nodes(0), period, degree);
  if (nodes.size() < 2)
    throw std::invalid_argument(std::string("Gordon surface: an open direction needs at least 2 "
                                            "lines ") +
                                name);
  return cardinal_splines(nodes, degree);
}

void check_inside(const CardinalSplines& c, double s, const char* name) {
  if (c.nodes.size() == 0 || c.periodic)
    return;
  const double a = c.nodes(0), b = c.nodes(c.nodes.size() - 1), slack = 1e-12 * (b - a);
  if (!(s >= a - slack && s <= b + slack))
    throw std::invalid_argument(std::string("Gordon surface: ") + name + " = " + std::to_string(s) +
                                " lies outside the grid [" + std::to_string(a) + ", " +
                                std::to_string(b) + "]");
}

} // namespace

GordonSurface gordon_surface(const LineTraces& t, const GordonOptions& o) {
  if (t.on_x.empty() && t.on_y.empty())
    throw std::invalid_argument("Gordon surface: no traces");
  GordonSurface O;
  O.traces = t;
  O.corners = crossing_values(t, o.tolerance);
  O.alpha = blending(t.x, o.degree_x, o.periodic_x, o.period_x, "x = x_i");
  O.beta = blending(t.y, o.degree_y, o.periodic_y, o.period_y, "y = y_j");
  // Dimension from any trace: on a line of the present family, at its first crossing coordinate
  // or at 0 (one family only).
  const double probe_y = t.y.size() ? t.y(0) : 0.0, probe_x = t.x.size() ? t.x(0) : 0.0;
  O.dim = t.on_x.empty() ? t.on_y[0](probe_x, 0).size() : t.on_x[0](probe_y, 0).size();
  return O;
}

GordonSurface coons_bilinear(const LineTraces& cell, double tolerance) {
  if (cell.x.size() != 2 || cell.y.size() != 2)
    throw std::invalid_argument("bilinear Coons: a cell has exactly two lines x = x_0, x_1 and "
                                "two lines y = y_0, y_1");
  return coons_composite(cell, tolerance);
}

GordonSurface coons_composite(const LineTraces& grid, double tolerance) {
  GordonOptions o;
  o.degree_x = o.degree_y = 1;
  o.tolerance = tolerance;
  return gordon_surface(grid, o);
}

RowVectorXd evaluate(const GordonSurface& O, double x, double y, int dx, int dy) {
  if (dx < 0 || dy < 0)
    throw std::invalid_argument("derivative orders must be >= 0");
  check_inside(O.alpha, x, "x");
  check_inside(O.beta, y, "y");
  const LineTraces& t = O.traces;
  const Index nx = t.x.size(), ny = t.y.size();
  RowVectorXd out = RowVectorXd::Zero(O.dim);
  MatrixXd a, b;
  if (nx > 0) {
    a = evaluate(O.alpha, x, dx); // row dx = alpha^(dx)
    for (Index i = 0; i < nx; ++i)
      out += a(dx, i) * t.on_x[static_cast<size_t>(i)](y, dy);
  }
  if (ny > 0) {
    b = evaluate(O.beta, y, dy);
    for (Index j = 0; j < ny; ++j)
      out += b(dy, j) * t.on_y[static_cast<size_t>(j)](x, dx);
  }
  if (nx > 0 && ny > 0)
    for (Index j = 0; j < ny; ++j)
      for (Index i = 0; i < nx; ++i)
        out -= a(dx, i) * b(dy, j) * O.corners.row(i + nx * j);
  return out;
}

} // namespace interlin
