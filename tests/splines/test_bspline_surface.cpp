// Explicit per-patch surface form against the tensor sum of Cox–de Boor basis functions.
#include "interlin/splines/bspline_surface.h"
#include "interlin/splines/cox_de_boor.h"
#include "interlin/splines/knots.h"

#include "support/test_surfaces.h"

#include <catch2/catch.hpp>
#include <limits>
#include <random>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

TEST_CASE("Surface explicit form equals the Cox–de Boor tensor sum (values and derivatives)",
          "[splines][surface][cox]") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0, 1);
  for (auto [pu, pv] : {std::pair{3, 3}, std::pair{2, 5}, std::pair{1, 3}, std::pair{4, 1}}) {
    BSplineSurface s;
    s.degree_u = pu;
    s.degree_v = pv;
    s.num_u = pu + 5;
    s.num_v = pv + 3;
    s.knots_u = test::random_clamped_knots(rng, pu, s.num_u, -0.5, 2.0);
    s.knots_v = test::random_clamped_knots(rng, pv, s.num_v, -0.5, 2.0);
    s.ctrl = MatrixXd::Random(s.num_u * s.num_v, 3);
    const PiecewiseSurface ps = to_piecewise(s);
    for (int k = 0; k < 100; ++k) {
      const double u = -0.5 + 2.5 * unit(rng), v = -0.5 + 2.5 * unit(rng);
      Index ku, kv;
      const MatrixXd Nu = cox_de_boor_derivatives(s.knots_u, pu, s.num_u, u, 2, &ku);
      const MatrixXd Nv = cox_de_boor_derivatives(s.knots_v, pv, s.num_v, v, 2, &kv);
      for (int du = 0; du <= std::min(2, pu); ++du)
        for (int dv = 0; dv <= std::min(2, pv); ++dv) {
          Eigen::Vector3d ref = Eigen::Vector3d::Zero();
          for (int r = 0; r <= pu; ++r)
            for (int q = 0; q <= pv; ++q)
              ref += Nu(du, r) * Nv(dv, q) *
                     s.ctrl.row((ku - pu + r) + s.num_u * (kv - pv + q)).transpose();
          // Second derivatives with knot spans down to ~0.05 reach ~1e3; relative round-off.
          CHECK((evaluate(ps, u, v, du, dv) - ref).norm() <= 1e-11 * std::max(1.0, ref.norm()));
        }
    }
    const Eigen::Vector4d d = domain(ps);
    CHECK(d(0) == -0.5);
    CHECK(d(3) == 2.0);
  }
}

TEST_CASE("A NaN parameter evaluates to NaN inside the coefficient array", "[splines][surface]") {
  // Fuzz find (a damaged .ifl): v = NaN located one span past the last and read beyond the
  // coefficients (ASan: heap-buffer-overflow). One span in v makes any such read leave the array.
  std::mt19937 rng(5);
  for (const bool closed : {false, true}) {
    BSplineSurface s;
    s.degree_u = 3;
    s.degree_v = 1;
    s.num_u = 6;
    s.num_v = 2;
    s.knots_u = test::random_clamped_knots(rng, 3, s.num_u, 0.0, 1.0);
    s.knots_v = Eigen::Vector4d(0, 0, 1, 1);
    s.ctrl = MatrixXd::Random(s.num_u * s.num_v, 3);
    s.closed_u = closed;
    const PiecewiseSurface ps = to_piecewise(s);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [u, v] : {std::pair{0.5, nan}, std::pair{nan, 0.5}, std::pair{nan, nan}}) {
      CHECK(!evaluate(ps, u, v).allFinite());
      CHECK(!evaluate_jet(ps, u, v).S.allFinite());
    }
  }
}

TEST_CASE("evaluate_grid layout and closed_u wrapping", "[splines][surface]") {
  BSplineSurface s;
  s.degree_u = 1;
  s.degree_v = 1;
  s.num_u = 2;
  s.num_v = 2;
  s.knots_u = Eigen::Vector4d(0, 0, 1, 1);
  s.knots_v = Eigen::Vector4d(0, 0, 1, 1);
  s.ctrl.resize(4, 3);
  s.ctrl << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1; // bilinear: S = (u, v, u v)
  PiecewiseSurface ps = to_piecewise(s);
  const MatrixXd G = evaluate_grid(ps, Eigen::Vector3d(0, 0.5, 1), Eigen::Vector2d(0.25, 1));
  REQUIRE(G.rows() == 6);
  CHECK(G.row(1 + 3 * 1).isApprox(Eigen::RowVector3d(0.5, 1, 0.5)));
  CHECK(G.row(2 + 3 * 0).isApprox(Eigen::RowVector3d(1, 0.25, 0.25)));
  ps.closed_u = true;
  CHECK(evaluate(ps, 1.25, 0.5).isApprox(evaluate(ps, 0.25, 0.5)));
  BSplineSurface bad = s;
  bad.ctrl(0, 0) = std::nan("");
  CHECK_THROWS_WITH(to_piecewise(bad), Catch::Contains("finite"));
}
