// The far field's tricubic interpolant (operators/cubic_grid.h): nodes reproduced, linear
// functions reproduced (natural ends), gradient consistent, fourth order inside.
#include "interlin/interflatation/operators/cubic_grid.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <random>

using namespace interlin;
using Eigen::Vector3d;

namespace {

CubicGrid sample(const std::function<double(const Vector3d&)>& f, double h, Eigen::Array3i n,
                 const Vector3d& origin = Vector3d(-0.3, 0.1, 0.2)) {
  std::vector<double> v;
  for (int k = 0; k < n(2); ++k)
    for (int j = 0; j < n(1); ++j)
      for (int i = 0; i < n(0); ++i)
        v.push_back(f(origin + h * Vector3d(i, j, k)));
  return cubic_grid(v, origin, h, n);
}

double smooth(const Vector3d& p) {
  return std::sin(2 * p(0) + p(1)) * std::exp(0.5 * p(2)) + p(0) * p(1) * p(2);
}

} // namespace

TEST_CASE("Cubic grid: nodes and linear functions exactly, gradient by differences",
          "[cubic_grid]") {
  const Eigen::Array3i n(7, 5, 6);
  const CubicGrid G = sample(smooth, 0.17, n);
  for (int k = 0; k < n(2); ++k)
    for (int j = 0; j < n(1); ++j)
      for (int i = 0; i < n(0); ++i) {
        const Vector3d p = G.origin + G.h * Vector3d(i, j, k);
        CHECK(evaluate(G, p) == Approx(smooth(p)).epsilon(0).margin(1e-13));
      }
  const auto linear = [](const Vector3d& p) { return 0.3 + 2 * p(0) - p(1) + 0.5 * p(2); };
  const CubicGrid L = sample(linear, 0.25, Eigen::Array3i(4, 3, 5));
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> U(-1, 2);
  for (int t = 0; t < 200; ++t) {
    const Vector3d p(U(rng), U(rng), U(rng)); // also outside: the end cells' polynomials
    Vector3d g;
    // Round-off inside the node box; outside, the end cells' cubics extrapolated up to 7 cells
    // amplify their coefficients' round-off by up to 7^3 (measured 2.6e-11).
    const bool inside =
        ((p - L.origin).array() >= 0).all() && (p.array() <= grid_max(L).array()).all();
    CHECK(evaluate(L, p, &g) == Approx(linear(p)).epsilon(0).margin(inside ? 1e-14 : 1e-10));
    CHECK((g - Vector3d(2, -1, 0.5)).norm() < 1e-9);
    // Gradient against central differences inside the node box.
    const Vector3d q =
        G.origin + (grid_max(G) - G.origin).cwiseProduct((p.array() + 1).matrix() / 3);
    Vector3d gs;
    const double h = 1e-6;
    evaluate(G, q, &gs);
    for (int a = 0; a < 3; ++a)
      CHECK((evaluate(G, q + h * Vector3d::Unit(a)) - evaluate(G, q - h * Vector3d::Unit(a))) /
                (2 * h) ==
            Approx(gs(a)).epsilon(0).margin(1e-6));
  }
  CHECK((grid_max(G) - (G.origin + 0.17 * Vector3d(6, 4, 5))).norm() < 1e-15);
  CHECK_THROWS_AS(cubic_grid({1, 2}, Vector3d::Zero(), 1, Eigen::Array3i(2, 1, 1)),
                  std::invalid_argument);
  CHECK_THROWS_AS(cubic_grid({1, 2, 3}, Vector3d::Zero(), 1, Eigen::Array3i(2, 2, 2)),
                  std::invalid_argument);
}

TEST_CASE("Cubic grid: fourth order away from the natural ends", "[cubic_grid]") {
  // Error measured in the central cube [0.4, 0.6]^3 of [0, 1]^3, where the natural end
  // conditions' O(h^2) boundary error has decayed (it falls off like (2 - sqrt 3)^k per node).
  std::vector<double> hs, errs;
  for (int m : {10, 20, 40}) {
    const double h = 1.0 / m;
    const CubicGrid G = sample(smooth, h, Eigen::Array3i::Constant(m + 1), Vector3d::Zero());
    double e = 0;
    for (int i = 0; i <= 8; ++i)
      for (int j = 0; j <= 8; ++j)
        for (int k = 0; k <= 8; ++k) {
          const Vector3d p =
              Vector3d(0.4, 0.4, 0.4) + 0.2 / 8 * Vector3d(i, j, k) + Vector3d(0.013, 0.007, 0.011);
          e = std::max(e, std::abs(evaluate(G, p) - smooth(p)));
        }
    hs.push_back(h);
    errs.push_back(e);
  }
  const double order = test::fitted_order(hs, errs);
  INFO("errors " << errs[0] << " " << errs[1] << " " << errs[2] << ", order " << order);
  CHECK(order > 3.6);
}
