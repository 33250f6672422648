// Sections -> implicit body (interlin implicit SECTIONS.csv): omega = 0 on the loft and its caps,
// the sign of an independent inside test, normalisation, the .ifl round trip.
#include "interlin/interflatation/models/ifl_registry.h"
#include "interlin/reconstruction/implicit/body_projection.h"
#include "interlin/reconstruction/implicit/section_body_build.h"
#include "interlin/reconstruction/meshing/ray_cast.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"
#include "section_body_checks.h"
#include "support/test_blades.h"
#include "support/test_sections.h"

#include <catch2/catch.hpp>
#include <map>
#include <random>
#include <sstream>

using namespace interlin;
using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using test::boundary_points;
using test::capped_mesh;
using test::omega;

namespace {

SectionBodyBuild build(const std::vector<Section>& s, int resolution, LoftOptions loft = {}) {
  SectionBodyOptions o;
  o.loft = loft;
  o.resolution = resolution;
  return build_section_body(s, o);
}

// The body of test family f at resolution 32, built once for all test cases.
const SectionBodyBuild& family(size_t f) {
  static std::map<size_t, SectionBodyBuild> built;
  auto it = built.find(f);
  if (it == built.end())
    it = built.emplace(f, build(test::blade_sections(test::blade_families()[f]), 32)).first;
  return it->second;
}

} // namespace

TEST_CASE("Section body: omega = 0 on every input point, the loft and the caps", "[implicit]") {
  for (size_t k = 0; k < test::blade_families().size(); ++k) {
    const std::vector<Section> s = test::blade_sections(test::blade_families()[k]);
    const SectionBodyBuild& b = family(k);
    const double diag = b.report.bbox_diagonal;
    const ImplicitFunction f = section_body_function(b.model);
    // The builder's own check (input points and dense samples) ...
    CHECK(b.report.max_surface_omega <= 1e-12 * diag);
    // ... and independent ones: every input point, random points of side and caps.
    for (const Section& sec : s)
      CHECK(omega(f, sec.points).cwiseAbs().maxCoeff() <= 1e-12 * diag);
    const BodyPatches B = body_patches(b.model.side, b.model.edge_u);
    CHECK(omega(f, boundary_points(B, 3000, 11)).cwiseAbs().maxCoeff() <= 1e-12 * diag);
  }
}

TEST_CASE("Section body: sign agrees with ray parity on the capped loft mesh", "[implicit]") {
  for (size_t k = 0; k < test::blade_families().size(); ++k) {
    const SectionBodyBuild& b = family(k);
    const ImplicitFunction f = section_body_function(b.model);
    MatrixXd V;
    Eigen::MatrixXi F;
    capped_mesh(b, V, F);
    std::mt19937 rng(5);
    MatrixXd P(4000, 3);
    for (Index i = 0; i < P.rows(); ++i)
      P.row(i) = b.model.box.sample().transpose();
    const Eigen::VectorXd w = omega(f, P);
    const std::vector<char> in = inside_by_ray_parity(V, F, P);
    // Near the surface the mesh's chords differ from it: within 1e-3 x diagonal (the mesh's sag
    // is below 1e-4 x diagonal here) the exact distance decides instead.
    const BodyProjection proj(body_patches(b.model.side, b.model.edge_u));
    const std::vector<BodyDistance> d = proj.distances(P);
    int checked = 0, wrong = 0;
    for (Index i = 0; i < P.rows(); ++i) {
      const bool near =
          std::abs(d[static_cast<size_t>(i)].distance) < 1e-3 * b.report.bbox_diagonal;
      if (!near) {
        ++checked;
        wrong += (w(i) > 0) != (in[static_cast<size_t>(i)] != 0);
      } else {
        CHECK((w(i) > 0) == (d[static_cast<size_t>(i)].distance > 0));
      }
    }
    CHECK(checked > 3900);
    CHECK(wrong == 0);
  }
}

TEST_CASE("Section body: |omega| / delta in [0.9, 1.1] on normal offsets", "[implicit][heavy]") {
  for (size_t k = 0; k < test::blade_families().size(); ++k) {
    const test::BladeFamily fam = test::blade_families()[k];
    const SectionBodyBuild& b = family(k);
    const double diag = b.report.bbox_diagonal;
    const ImplicitFunction f = section_body_function(b.model);
    const BodyPatches B = body_patches(b.model.side, b.model.edge_u);
    MatrixXd V;
    Eigen::MatrixXi F;
    capped_mesh(b, V, F);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> U(0, 1), L(std::log(1e-3), std::log(5e-2));
    const int n = 300;
    MatrixXd foot(n, 3), normal(n, 3);
    Eigen::VectorXd delta(n);
    for (int i = 0; i < n; ++i) {
      // Side points away from the ends (z in the middle 70 % of the span, farther from the caps
      // than any offset), where a normal offset's nearest feature is its foot.
      const double dl = diag * std::exp(L(rng));
      SurfaceJet J;
      do
        J = evaluate_jet(B.patches[0], U(rng), U(rng));
      while (J.S(2) < 0.15 * fam.span || J.S(2) > 0.85 * fam.span);
      foot.row(i) = J.S.transpose();
      normal.row(i) = (B.orientation[0] * J.Su.cross(J.Sv)).normalized().transpose();
      delta(i) = dl;
    }
    // Outside: delta from 0.1 % to 5 % of the diagonal.
    const Eigen::VectorXd out =
        omega(f, foot + (normal.array().colwise() * delta.array()).matrix());
    for (int i = 0; i < n; ++i) {
      CHECK(-out(i) / delta(i) >= 0.9);
      CHECK(-out(i) / delta(i) <= 1.1);
    }
    // Inside: up to a quarter of the local thickness (the ray's exit through the capped mesh);
    // offsets past the medial surface against the exact distance.
    const Eigen::VectorXd thick = ray_hit_distance(V, F, foot - 1e-9 * diag * normal, -normal);
    std::uniform_real_distribution<double> Q(0.02, 0.25);
    Eigen::VectorXd inner(n);
    for (int i = 0; i < n; ++i)
      inner(i) = Q(rng) * thick(i);
    const test::InsideOffsetRatios in = test::inside_offset_ratios(
        f, BodyProjection(B), foot - (normal.array().colwise() * inner.array()).matrix(), inner);
    for (int i = 0; i < n; ++i) {
      CHECK(in.ratio(i) >= 0.9);
      CHECK(in.ratio(i) <= 1.1);
    }
    CHECK(in.by_exact <= n / 20); // most offsets stay normal offsets (else the test tests little)
  }
}

TEST_CASE("Section body: the .ifl file reads back to the same function", "[implicit][ifl]") {
  const SectionBodyBuild& b = family(1);
  std::ostringstream out;
  write_ifl(out, to_ifl(b.model));
  const IflBlock back = parse_ifl(out.str(), "mem.ifl");
  CHECK(back.kind == "section_body");
  const ImplicitFunction f = section_body_function(b.model), g = load_ifl_model(back, "mem.ifl");
  CHECK(g.box.isApprox(f.box, 0));
  MatrixXd P(500, 3);
  for (Index i = 0; i < P.rows(); ++i)
    P.row(i) = f.box.sample().transpose();
  Eigen::VectorXd a(P.rows()), c(P.rows());
  Points3 ga(P.rows(), 3), gc(P.rows(), 3);
  f.gradient(Points3(P), a, ga);
  g.gradient(Points3(P), c, gc);
  CHECK((a - c).cwiseAbs().maxCoeff() == 0);
  CHECK((ga - gc).cwiseAbs().maxCoeff() == 0);
}

TEST_CASE("Section body: gradient matches central differences", "[implicit]") {
  const SectionBodyBuild& b = family(0);
  const ImplicitFunction f = section_body_function(b.model);
  std::mt19937 rng(3);
  const double h = 1e-6 * b.report.bbox_diagonal;
  int compared = 0;
  for (int i = 0; i < 300; ++i) {
    const Vector3d p = b.model.box.sample();
    Points3 P(7, 3);
    P.row(0) = p.transpose();
    for (int a = 0; a < 3; ++a) {
      P.row(1 + 2 * a) = (p + h * Vector3d::Unit(a)).transpose();
      P.row(2 + 2 * a) = (p - h * Vector3d::Unit(a)).transpose();
    }
    Eigen::VectorXd w(7);
    Points3 G(7, 3);
    f.gradient(P, w, G);
    // Skip the medial surface inside (the distance's kink) and the blend band's edges.
    Vector3d fd;
    for (int a = 0; a < 3; ++a)
      fd(a) = (w(1 + 2 * a) - w(2 + 2 * a)) / (2 * h);
    const Vector3d g = G.row(0).transpose();
    if ((G.bottomRows(6).rowwise() - G.row(0)).rowwise().norm().maxCoeff() > 1e-3)
      continue;
    ++compared;
    CHECK((fd - g).norm() <= 1e-5 * std::max(1.0, g.norm()));
  }
  CHECK(compared > 250);
}

TEST_CASE("Section body: Rotor 37, every input point exact", "[implicit][rotor37]") {
  // The default spanwise model (station parameters on Rotor 37's stream surfaces) and the
  // centripetal cubic one, whose tip span spline folds back by 5e-4 cm (sections 12 and 13 are
  // 0.035 cm apart): the sign logic must treat that fold as the tip edge.
  LoftOptions folding;
  folding.span = SpanParameters::centripetal;
  folding.span_degree = 3;
  for (const bool folds : {false, true}) {
    const SectionBodyBuild b = build(test::rotor37(), 40, folds ? folding : LoftOptions{});
    const double diag = b.report.bbox_diagonal;
    const ImplicitFunction f = section_body_function(b.model);
    double worst = 0;
    for (const Section& s : test::rotor37())
      worst = std::max(worst, omega(f, s.points).cwiseAbs().maxCoeff());
    CHECK(worst <= 1e-12 * diag);
    const BodyPatches B = body_patches(b.model.side, b.model.edge_u);
    CHECK(omega(f, boundary_points(B, 5000, 3)).cwiseAbs().maxCoeff() <= 1e-12 * diag);
    CHECK((B.fold_zone[1] > 0) == folds);
    CHECK(B.fold_zone[1] < 1e-2);
  }
}
