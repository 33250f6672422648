// Interlineation on a family of lines v = v_k: exact on every line, spline-accurate between.
#include "interlin/interlineation/interlinate_curves.h"

#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// f(u, v) = sum_i N_i(u) P_i(v): a clamped cubic in u whose control points move smoothly
// (non-polynomially) with v. Its sections are exactly B-spline curves, so any error of the
// interlinated surface comes from the blending in v alone.
BSplineCurve section(double v) {
  BSplineCurve c;
  c.degree = 3;
  c.knots.resize(12);
  c.knots << 0, 0, 0, 0, 0.2, 0.35, 0.5, 0.8, 1, 1, 1, 1;
  c.ctrl.resize(8, 3);
  for (Index i = 0; i < 8; ++i) {
    const double a = 2 * M_PI * i / 8 + 0.6 * v * v;
    c.ctrl.row(i) << (1 + 0.3 * std::sin(3 * v)) * std::cos(a), std::exp(0.4 * v) * std::sin(a), v;
  }
  return c;
}

} // namespace

TEST_CASE("Interlinated surface reproduces every section curve exactly", "[interlineation]") {
  std::vector<BSplineCurve> cs;
  VectorXd v(5);
  v << 0, 0.1, 0.45, 0.7, 1;
  for (Index k = 0; k < v.size(); ++k)
    cs.push_back(section(v(k)));
  for (int q : {1, 2, 3, 4}) {
    const PiecewiseSurface S = to_piecewise(interlinate_curves(cs, v, q, false));
    for (Index k = 0; k < v.size(); ++k) {
      const VectorXd u = VectorXd::LinSpaced(301, 0, 1);
      const MatrixXd C = evaluate(cs[k], u);
      for (Index i = 0; i < u.size(); ++i)
        // One solve with a collocation matrix of condition ~10: round-off of O(1) coordinates.
        CHECK((evaluate(S, u(i), v(k)).transpose() - C.row(i)).norm() < 1e-13);
    }
  }
}

TEST_CASE("Cubic interlineation converges with order 4 between the lines", "[interlineation]") {
  std::vector<double> h, err;
  for (Index K : {5, 9, 17, 33}) {
    std::vector<BSplineCurve> cs;
    const VectorXd v = VectorXd::LinSpaced(K, 0, 1);
    for (Index k = 0; k < K; ++k)
      cs.push_back(section(v(k)));
    const PiecewiseSurface S = to_piecewise(interlinate_curves(cs, v, 3, false));
    double e = 0;
    for (double vv : VectorXd::LinSpaced(401, 0, 1)) {
      const BSplineCurve exact = section(vv);
      const VectorXd u = VectorXd::LinSpaced(41, 0, 1);
      const MatrixXd C = evaluate(exact, u);
      for (Index i = 0; i < u.size(); ++i)
        e = std::max(e, (evaluate(S, u(i), vv).transpose() - C.row(i)).norm());
    }
    h.push_back(1.0 / (K - 1));
    err.push_back(e);
  }
  const double order = test::fitted_order(h, err);
  INFO("max errors " << err[0] << " " << err[1] << " " << err[2] << " " << err[3]);
  CHECK(order == Approx(4.0).epsilon(0).margin(0.3)); // cubic spline interpolation in v: O(h^4)
}

TEST_CASE("Incompatible curves are rejected", "[interlineation]") {
  std::vector<BSplineCurve> cs = {section(0), section(1)};
  cs[1].knots(5) = 0.3;
  CHECK_THROWS_WITH(interlinate_curves(cs, Eigen::Vector2d(0, 1), 3, false),
                    Catch::Contains("not compatible"));
  CHECK_THROWS(interlinate_curves({section(0)}, VectorXd::Zero(1), 3, false));
}
