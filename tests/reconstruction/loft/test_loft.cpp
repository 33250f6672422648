// The loft: exact on every input section, correct correspondence, spanwise order of accuracy.
#include "interlin/reconstruction/io/section_csv.h"
#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/holdout.h"
#include "interlin/reconstruction/loft/loft.h"

#include "support/test_sections.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;
using test::body_section;
using test::rotor37;

TEST_CASE("Rotor 37: the surface reproduces all 2574 input points to round-off", "[loft][heavy]") {
  for (StartAlign align : {StartAlign::first, StartAlign::leading_edge, StartAlign::trailing_edge})
    for (Correspondence m : {Correspondence::automatic, Correspondence::arc_length}) {
      LoftOptions o;
      o.align = align;
      o.match = m;
      const LoftResult r = loft_sections(rotor37(), o);
      INFO("align " << int(align) << " match " << int(m));
      // The bound is 1e-9 x diagonal; the construction achieves round-off (~1e-15).
      CHECK(r.max_deviation <= 1e-13 * r.bbox_diagonal);
      CHECK(r.surface.closed_u);
      CHECK(r.section_v.size() == 13);
      // Independent evaluation path: the explicit surface form at (u_i, v_k).
      const PiecewiseSurface S = to_piecewise(r.surface);
      for (size_t k = 0; k < r.sections.size(); k += 4)
        for (Index i = 0; i < r.sections[k].points.rows(); i += 7)
          CHECK((evaluate(S, r.point_u[k](i), r.section_v(Index(k))) -
                 r.sections[k].points.row(i).transpose())
                    .norm() < 1e-12 * r.bbox_diagonal);
    }
  const LoftResult r = loft_sections(rotor37());
  CHECK(r.used == Correspondence::index); // equal counts -> one shared knot vector
  CHECK(r.surface.num_u == 198 + 3);
}

TEST_CASE("Sections with different point counts, spacing and start points", "[loft]") {
  std::vector<Section> in;
  const Index counts[] = {40, 73, 55, 90, 61};
  for (int k = 0; k < 5; ++k)
    in.push_back(body_section(0.4 * k, counts[k], 0.7 * k));
  for (StartAlign align : {StartAlign::first, StartAlign::leading_edge}) {
    LoftOptions o;
    o.align = align;
    const LoftResult r = loft_sections(in, o);
    CHECK(r.used == Correspondence::arc_length);
    CHECK(r.max_deviation <= 1e-12 * r.bbox_diagonal);
  }
  LoftOptions idx;
  idx.match = Correspondence::index;
  CHECK_THROWS_WITH(loft_sections(in, idx), Catch::Contains("equal point counts"));
}

TEST_CASE("Degree options: exact for degrees 2..5, span degree reduced for few sections",
          "[loft]") {
  std::vector<Section> in;
  for (int k = 0; k < 3; ++k)
    in.push_back(body_section(0.5 * k, 30));
  for (int p : {2, 3, 4, 5}) {
    LoftOptions o;
    o.degree = p;
    o.span_degree = 5;
    const LoftResult r = loft_sections(in, o);
    CHECK(r.surface.degree_u == p);
    CHECK(r.surface.degree_v == 2); // 3 sections allow at most degree 2
    CHECK(r.max_deviation <= 1e-12 * r.bbox_diagonal);
  }
  CHECK_THROWS_WITH(loft_sections({in[0]}), Catch::Contains("at least 2 sections"));
  CHECK_THROWS_WITH(loft_sections({in[0], in[0]}), Catch::Contains("coincide"));
}

TEST_CASE("Spanwise accuracy on a smooth body: hold-out distance converges with order 4 (cubic), "
          "faster by default",
          "[loft][convergence]") {
  // Sections densely sampled (section curves accurate to ~1e-10), spans halved: the withheld
  // mid-sections measure the spanwise interpolation error alone, O(h^4) for cubic blending.
  LoftOptions cubic;
  cubic.span_degree = 3;
  std::vector<double> h, err, err_default;
  for (int K : {5, 9, 17}) {
    std::vector<Section> all;
    for (int k = 0; k < 2 * K - 1; ++k)
      all.push_back(body_section(2.0 * k / (2 * K - 2), 400));
    h.push_back(2.0 / (K - 1));
    err.push_back(holdout_study(all, withheld_every(all.size(), 2), cubic).max);
    err_default.push_back(holdout_study(all, withheld_every(all.size(), 2)).max);
  }
  const double order = test::fitted_order(h, err);
  INFO("max hold-out distances, cubic " << err[0] << " " << err[1] << " " << err[2] << "; default "
                                        << err_default[0] << " " << err_default[1] << " "
                                        << err_default[2]);
  CHECK(order == Approx(4.0).epsilon(0).margin(0.5));
  // The default (span model by leave-one-out) takes higher degrees on this analytic body:
  // never worse than cubic, and converging faster than O(h^6) (measured order ~11).
  for (size_t i = 0; i < h.size(); ++i)
    CHECK(err_default[i] <= err[i]);
  CHECK(test::fitted_order(h, err_default) > 6);
}

TEST_CASE("Rotor 37 hold-out (every second section withheld) matches the recorded study",
          "[loft][holdout]") {
  const HoldoutResult r = holdout_study(rotor37(), withheld_every(13, 2));
  REQUIRE(r.test == std::vector<size_t>({1, 3, 5, 7, 9, 11}));
  // Values of docs/benchmarks.md (the 7 sections' span model by leave-one-out: uniform cubic;
  // index correspondence); the OpenCASCADE ThruSections loft of the same 7 sections gives max
  // 0.0199, rms 0.0054. Every fixed span model lies within max 0.0190 to 0.0195 and rms 0.0055
  // to 0.0063 here (the data's own section-to-section irregularity, docs/benchmarks.md).
  CHECK(r.max == Approx(0.01899).epsilon(0).margin(5e-5));
  CHECK(r.rms == Approx(0.006315).epsilon(0).margin(5e-5));
  CHECK(r.max < 0.0199);
}
