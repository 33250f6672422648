// Study: convergence of interlineation operators on an n x n grid of lines as the grid is
// refined (docs/benchmarks.md, "Gordon vs Coons vs tensor-product interpolation").
// For smooth test functions on [0,1]^2 and n = 2, 4, ..., 64 cells per direction, prints the
// max error on a 201 x 201 sample of
//   - composite bilinear Coons (Gordon with linear blending, seed 001 Theorem 3 operator),
//   - Gordon with C1 quadratic and C2 cubic cardinal splines (digest 001 §5.1),
//   - composite C1 Hermite Coons (digest 001 §5.2; also uses the normal-derivative traces),
//   - tensor-product spline interpolation of the grid-point values only (bilinear, bicubic),
// and the order fitted to the errors from n = 4 on that lie above the round-off floor 1e-13
// (least squares of log e against log h).
// The transfinite operators use the whole traces on the lines (continuum data), the tensor
// products only the (n+1)^2 crossing values: the table compares methods, not equal data.
// Usage: gordon_convergence   (deterministic, ~1 min)
#include "interlin/interlineation/coons_hermite.h"
#include "interlin/interlineation/gordon_surface.h"
#include "interlin/splines/interpolate_curve.h"
#include "interlin/splines/spline_basis.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::RowVectorXd;
using Eigen::VectorXd;

namespace {

// f(x, y, dx, dy) for dx, dy <= 1 (the Hermite operator needs first derivatives and the twist).
using Field = std::function<double(double, double, int, int)>;

struct TestFunction {
  const char* name;
  Field f;
};

double d_sin(double a, double x, int d) {
  return d == 0 ? std::sin(a * x) : a * std::cos(a * x);
}
double d_cos(double a, double x, int d) {
  return d == 0 ? std::cos(a * x) : -a * std::sin(a * x);
}
double d_pow3(double x, int d) {
  return d == 0 ? x * x * x : 3 * x * x;
}
double d_exp(double a, double x, int d) {
  return (d == 0 ? 1 : a) * std::exp(a * x);
}

LineTraces traces_of(const Field& f, const VectorXd& g) {
  LineTraces t;
  t.x = t.y = g;
  for (Index i = 0; i < g.size(); ++i) {
    t.on_x.push_back([f, a = g(i)](double s, int d) -> RowVectorXd {
      return RowVectorXd::Constant(1, f(a, s, 0, d));
    });
    t.on_y.push_back([f, b = g(i)](double s, int d) -> RowVectorXd {
      return RowVectorXd::Constant(1, f(s, b, d, 0));
    });
  }
  return t;
}

// Tensor-product interpolation of the grid values f(x_i, y_j), degree p in both directions:
// rows interpolated along x, then the control points along y (interlineation of the rows).
struct Tensor {
  SplineBasis bx, by;
  MatrixXd c; // #bx by #by
};

Tensor tensor_interpolant(const Field& f, const VectorXd& g, int p) {
  const Index n = g.size();
  MatrixXd F(n, n);
  for (Index j = 0; j < n; ++j)
    for (Index i = 0; i < n; ++i)
      F(i, j) = f(g(i), g(j), 0, 0);
  const BSplineCurve rows = interpolate_open(F, g, p);                     // columns: y_j
  const BSplineCurve cols = interpolate_open(rows.ctrl.transpose(), g, p); // along y
  return {explicit_basis(rows.knots, rows.degree), explicit_basis(cols.knots, cols.degree),
          cols.ctrl.transpose()};
}

double evaluate(const Tensor& T, double x, double y) {
  Index sx, sy;
  const MatrixXd Nx = basis_derivatives(T.bx, x, 0, &sx), Ny = basis_derivatives(T.by, y, 0, &sy);
  const int px = T.bx.degree, py = T.by.degree;
  return (Nx.row(0) * T.c.block(sx - px, sy - py, px + 1, py + 1) * Ny.row(0).transpose())(0, 0);
}

// Least-squares slope of log e against log h over the rows from n = 4 on (n = 2 is
// pre-asymptotic: 3 lines reduce the cubic blending to quadratic) with e above the floor.
double fitted_order(const std::vector<double>& h, const std::vector<double>& e, double floor) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;
  for (size_t i = 1; i < h.size(); ++i)
    if (e[i] > floor) {
      const double a = std::log(h[i]), b = std::log(e[i]);
      sx += a, sy += b, sxx += a * a, sxy += a * b, m += 1;
    }
  return m >= 2 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : NAN;
}

} // namespace

int main() {
  const std::vector<TestFunction> functions = {
      {"sin(3x) cos(2y) + x^3 y^3 (digest T13)",
       [](double x, double y, int dx, int dy) {
         return d_sin(3, x, dx) * d_cos(2, y, dy) + d_pow3(x, dx) * d_pow3(y, dy);
       }},
      {"exp(x - 2y) + sin(4x + 3y)",
       [](double x, double y, int dx, int dy) {
         // exact first derivatives and twist of both terms
         const double s = 4 * x + 3 * y;
         const double trig = (dx == 0 && dy == 0)   ? std::sin(s)
                             : (dx == 1 && dy == 0) ? 4 * std::cos(s)
                             : (dx == 0 && dy == 1) ? 3 * std::cos(s)
                                                    : -12 * std::sin(s);
         return d_exp(1, x, dx) * d_exp(-2, y, dy) + trig;
       }},
  };
  const std::vector<int> ns = {2, 4, 8, 16, 32, 64};
  const VectorXd sample = VectorXd::LinSpaced(201, 0, 1);
  const char* methods[] = {"composite Coons (linear blending, C0)",
                           "Gordon, quadratic (C1)",
                           "Gordon, cubic (C2)",
                           "Hermite Coons (C1, + normal derivatives)",
                           "tensor product, bilinear (grid values)",
                           "tensor product, bicubic (grid values)"};
  for (const TestFunction& tf : functions) {
    std::vector<std::vector<double>> err(6);
    std::vector<double> h;
    for (int n : ns) {
      const VectorXd g = VectorXd::LinSpaced(n + 1, 0, 1);
      h.push_back(1.0 / n);
      const LineTraces t = traces_of(tf.f, g);
      std::vector<GordonSurface> gordon;
      for (int p : {1, 2, 3}) {
        GordonOptions o;
        o.degree_x = o.degree_y = p;
        gordon.push_back(gordon_surface(t, o));
      }
      HermiteTraces ht;
      ht.values = t;
      for (Index i = 0; i < g.size(); ++i) {
        ht.dx_on_x.push_back([f = tf.f, a = g(i)](double s, int d) -> RowVectorXd {
          return RowVectorXd::Constant(1, f(a, s, 1, d));
        });
        ht.dy_on_y.push_back([f = tf.f, b = g(i)](double s, int d) -> RowVectorXd {
          return RowVectorXd::Constant(1, f(s, b, d, 1));
        });
      }
      const HermiteCoons hermite = coons_hermite(ht);
      const Tensor t1 = tensor_interpolant(tf.f, g, 1), t3 = tensor_interpolant(tf.f, g, 3);
      std::vector<double> e(6, 0.0);
      for (double x : sample)
        for (double y : sample) {
          const double fv = tf.f(x, y, 0, 0);
          for (int m = 0; m < 3; ++m)
            e[m] = std::max(e[m], std::abs(evaluate(gordon[m], x, y)(0) - fv));
          e[3] = std::max(e[3], std::abs(evaluate(hermite, x, y)(0) - fv));
          e[4] = std::max(e[4], std::abs(evaluate(t1, x, y) - fv));
          e[5] = std::max(e[5], std::abs(evaluate(t3, x, y) - fv));
        }
      for (int m = 0; m < 6; ++m)
        err[m].push_back(e[m]);
    }
    std::printf("### f = %s\n\n| method |", tf.name);
    for (int n : ns)
      std::printf(" n = %d |", n);
    std::printf(" fitted order |\n|---|");
    for (size_t i = 0; i <= ns.size(); ++i)
      std::printf("---|");
    std::printf("\n");
    for (int m = 0; m < 6; ++m) {
      std::printf("| %s |", methods[m]);
      for (double e : err[m])
        std::printf(" %.2e |", e);
      // Errors below 1e-13 are round-off (values O(1)) and left out of the fit.
      std::printf(" %.2f |\n", fitted_order(h, err[m], 1e-13));
    }
    std::printf("\n");
  }
  return 0;
}
