// Study: floating-point accuracy of seed 001 Theorem 1 on nonuniform knots (docs/formulas.md).
// For random knot vectors whose spans are spread over a factor R, prints
//   - max |N_explicit(x) - N_CoxdeBoor(x)| over random x: the explicit per-span form as built
//     (y* by the derivative recurrence, integration (2) in extended precision) against the
//     Cox–de Boor triangular recursion on the same knots;
//   - the largest relative error of the seed's own route to y* (theorem1_y_solve: y_1 = 1 and a
//     linear solve of the conditions (3)) and of the closed form (digest §2.1.3), both against
//     the derivative recurrence (theorem1_y).
// Usage: theorem1_conditioning [trials]   (deterministic: fixed seed)
#include "interlin/splines/explicit_bspline.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

using namespace interlin;
using Eigen::VectorXd;

namespace {

// N_{0,n}(x; X) by the Cox–de Boor triangular recursion (half-open spans).
double cox_de_boor(const VectorXd& X, int n, double x) {
  std::vector<double> N(static_cast<size_t>(n) + 1);
  for (int i = 0; i <= n; ++i)
    N[static_cast<size_t>(i)] = (X(i) <= x && x < X(i + 1)) ? 1.0 : 0.0;
  for (int p = 1; p <= n; ++p)
    for (int i = 0; i + p <= n; ++i) {
      double v = 0;
      if (X(i + p) > X(i))
        v += (x - X(i)) / (X(i + p) - X(i)) * N[static_cast<size_t>(i)];
      if (X(i + p + 1) > X(i + 1))
        v += (X(i + p + 1) - x) / (X(i + p + 1) - X(i + 1)) * N[static_cast<size_t>(i) + 1];
      N[static_cast<size_t>(i)] = v;
    }
  return N[0];
}

} // namespace

int main(int argc, char** argv) {
  const int trials = argc > 1 ? std::atoi(argv[1]) : 200;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> unit(0, 1);
  std::printf("| span ratio R | degree | explicit form vs Cox-de Boor | seed's solve of (3) | "
              "closed-form y_k |\n|---|---|---|---|---|\n");
  for (double R : {1.0, 10.0, 1e3, 1e5})
    for (int n : {2, 3, 5, 7}) {
      double e_val = 0, e_solve = 0, e_closed = 0;
      for (int t = 0; t < trials; ++t) {
        VectorXd X(n + 2);
        X(0) = 0;
        for (int i = 1; i < n + 2; ++i)
          X(i) = X(i - 1) + std::pow(R, unit(rng)); // spans spread over [1, R]
        const ExplicitBSpline N = explicit_bspline(X, n);
        for (int s = 0; s < 50; ++s) {
          const double x = X(n + 1) * unit(rng);
          e_val = std::max(e_val, std::abs(evaluate(N, x) - cox_de_boor(X, n, x)));
        }
        const VectorXd y = theorem1_y(X, n), ys = theorem1_y_solve(X, n),
                       yc = theorem1_y_closed_form(X, n);
        const double scale = y.cwiseAbs().maxCoeff();
        e_solve = std::max(e_solve, (ys - y).cwiseAbs().maxCoeff() / scale);
        e_closed = std::max(e_closed, (yc - y).cwiseAbs().maxCoeff() / scale);
      }
      std::printf("| %g | %d | %.1e | %.1e | %.1e |\n", R, n, e_val, e_solve, e_closed);
    }
}
