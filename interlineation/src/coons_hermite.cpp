// digest 001 §5.2 [SUPPLEMENT]: C1 Hermite Coons, composite on a line grid.
#include "interlin/interlineation/coons_hermite.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::VectorXd;

void hermite_cardinals(const VectorXd& nodes, double x, int d, VectorXd& H, VectorXd& K) {
  const Index n = nodes.size();
  if (n < 2)
    throw std::invalid_argument("Hermite Coons: at least 2 lines per family");
  const double a = nodes(0), b = nodes(n - 1), slack = 1e-12 * (b - a);
  if (!(x >= a - slack && x <= b + slack))
    throw std::invalid_argument("Hermite Coons: " + std::to_string(x) + " lies outside [" +
                                std::to_string(a) + ", " + std::to_string(b) + "]");
  const Index c = std::clamp<Index>(
      std::upper_bound(nodes.data(), nodes.data() + n, x) - nodes.data() - 1, 0, n - 2);
  const double h = nodes(c + 1) - nodes(c), s = (x - nodes(c)) / h;
  // Derivatives in s of the four cubics, then d/dx = (1/h) d/ds.
  double h0, h1, k0, k1;
  switch (d) {
  case 0:
    h0 = 1 - 3 * s * s + 2 * s * s * s, h1 = 3 * s * s - 2 * s * s * s;
    k0 = s - 2 * s * s + s * s * s, k1 = s * s * s - s * s;
    break;
  case 1:
    h0 = -6 * s + 6 * s * s, h1 = 6 * s - 6 * s * s, k0 = 1 - 4 * s + 3 * s * s,
    k1 = 3 * s * s - 2 * s;
    break;
  case 2:
    h0 = -6 + 12 * s, h1 = 6 - 12 * s, k0 = -4 + 6 * s, k1 = 6 * s - 2;
    break;
  case 3:
    h0 = 12, h1 = -12, k0 = 6, k1 = 6;
    break;
  default:
    h0 = h1 = k0 = k1 = 0;
  }
  const double scale = std::pow(h, -d);
  H = VectorXd::Zero(n);
  K = VectorXd::Zero(n);
  H(c) = h0 * scale, H(c + 1) = h1 * scale;
  K(c) = k0 * h * scale, K(c + 1) = k1 * h * scale; // K_i = h k_i(s)
}

HermiteCoons coons_hermite(const HermiteTraces& t, double tol) {
  const LineTraces& v = t.values;
  const Index nx = v.x.size(), ny = v.y.size();
  if (nx < 2 || ny < 2)
    throw std::invalid_argument("Hermite Coons: at least 2 lines per family");
  if (static_cast<Index>(t.dx_on_x.size()) != nx || static_cast<Index>(t.dy_on_y.size()) != ny)
    throw std::invalid_argument(
        "Hermite Coons: one normal-derivative trace per line (dx_on_x, dy_on_y)");
  HermiteCoons O;
  O.traces = t;
  O.f = crossing_values(v, tol);
  O.dim = O.f.cols();
  O.fx = crossing_values(t.dx_on_x, v.y, 0, v.on_y, v.x, 1, tol, "f_x");
  O.fy = crossing_values(v.on_x, v.y, 1, t.dy_on_y, v.x, 0, tol, "f_y");
  const MatrixXd twist = crossing_values(t.dx_on_x, v.y, 1, t.dy_on_y, v.x, 1, tol, "twist f_xy");
  if (t.twists.size() == 0) {
    O.fxy = twist;
  } else {
    if (t.twists.rows() != nx * ny || t.twists.cols() != O.dim)
      throw std::invalid_argument("Hermite Coons: twists must be (#x * #y) by dim");
    for (Index r = 0; r < twist.rows(); ++r) {
      const double gap = (t.twists.row(r) - twist.row(r)).cwiseAbs().maxCoeff();
      if (gap > tol * std::max(1.0, twist.row(r).cwiseAbs().maxCoeff()))
        throw std::invalid_argument("Hermite Coons: the given twist at crossing (" +
                                    std::to_string(r % nx) + ", " + std::to_string(r / nx) +
                                    ") differs from the traces' cross derivative by " +
                                    std::to_string(gap));
    }
    O.fxy = t.twists;
  }
  return O;
}

RowVectorXd evaluate(const HermiteCoons& O, double x, double y, int dx, int dy) {
  if (dx < 0 || dy < 0)
    throw std::invalid_argument("derivative orders must be >= 0");
  const HermiteTraces& t = O.traces;
  const LineTraces& v = t.values;
  const Index nx = v.x.size(), ny = v.y.size();
  VectorXd Hx, Kx, Hy, Ky;
  hermite_cardinals(v.x, x, dx, Hx, Kx);
  hermite_cardinals(v.y, y, dy, Hy, Ky);
  RowVectorXd out = RowVectorXd::Zero(O.dim);
  // Only the two lines of the cell carry weight; skip the zero terms.
  for (Index i = 0; i < nx; ++i)
    if (Hx(i) != 0 || Kx(i) != 0)
      out += Hx(i) * v.on_x[static_cast<size_t>(i)](y, dy) +
             Kx(i) * t.dx_on_x[static_cast<size_t>(i)](y, dy);
  for (Index j = 0; j < ny; ++j)
    if (Hy(j) != 0 || Ky(j) != 0)
      out += Hy(j) * v.on_y[static_cast<size_t>(j)](x, dx) +
             Ky(j) * t.dy_on_y[static_cast<size_t>(j)](x, dx);
  for (Index j = 0; j < ny; ++j)
    for (Index i = 0; i < nx; ++i) {
      const Index r = i + nx * j;
      out -= Hx(i) * Hy(j) * O.f.row(r) + Hx(i) * Ky(j) * O.fy.row(r) +
             Kx(i) * Hy(j) * O.fx.row(r) + Kx(i) * Ky(j) * O.fxy.row(r);
    }
  return out;
}

} // namespace interlin
