// The partition-of-unity implicit of unstructured clouds (Ohtake et al. 2003): accuracy against
// exact surfaces over families of shapes, noise levels and densities; sign; gradient; batch
// independence; far field; model validation.

#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/prepare_cloud.h"
#include "interlin/reconstruction/clouds/sample_mesh.h"
#include "interlin/reconstruction/loft/closest_point.h"
#include "interlin/reconstruction/loft/loft.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/surface_mesh.h"

#include "exterior_side.h"
#include "nearest_neighbours.h"
#include "support/test_clouds.h"
#include "support/test_sections.h"
#include "winding_number.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <utility>

using namespace interlin;

namespace {

struct Fitted {
  std::shared_ptr<CloudImplicit> model;
  ImplicitFunction F;
  CloudFitInfo info;
};

Fitted fit(const PointCloud& c, double sigma) {
  CloudFitOptions o;
  o.noise = sigma;
  Fitted f;
  f.model = std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &f.info));
  f.F = cloud_implicit_function(f.model);
  return f;
}

Eigen::VectorXd values(const ImplicitFunction& F, const Eigen::MatrixX3d& P) {
  Eigen::VectorXd v(P.rows());
  F.value(P, v);
  return v;
}

// The cloud fitted with the default options, with the flood fill (exterior_side) and without
// it (and without the slab split when split_slabs is false): each fit's info and the number of
// probes (outside the body) where its F >= 0.
struct WithAndWithoutFill {
  CloudFitInfo on, off;
  long spurious_on = 0, spurious_off = 0;
};

WithAndWithoutFill fit_with_and_without_fill(const PointCloud& c, const Points3& probes,
                                             bool split_slabs = true) {
  WithAndWithoutFill r;
  CloudFitOptions o;
  const ImplicitFunction F =
      cloud_implicit_function(std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &r.on)));
  o.exterior_side = false;
  o.split_slabs = split_slabs;
  const ImplicitFunction G =
      cloud_implicit_function(std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &r.off)));
  r.spurious_on = (values(F, probes).array() >= 0).count();
  r.spurious_off = (values(G, probes).array() >= 0).count();
  return r;
}

// n points sampled (seed) by area from the capped mesh of the blade's loft S, each coordinate
// moved by Gaussian noise sigma (noise_seed).
Points3 noisy_blade_scan(const PiecewiseSurface& S, int n, unsigned seed, double sigma,
                         unsigned noise_seed) {
  SurfaceMeshOptions mo;
  mo.nu = 600;
  mo.nv = 150;
  mo.cap = true;
  Eigen::MatrixXd V;
  Eigen::MatrixXi T;
  surface_mesh(S, mo, V, T);
  Points3 P = sample_mesh(V, T, n, seed).points;
  std::mt19937 rng(noise_seed);
  std::normal_distribution<double> G(0, sigma);
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    P.row(i) += Eigen::RowVector3d(G(rng), G(rng), G(rng));
  return P;
}

// Whether the leaf's support ball holds a point of the index.
bool ball_holds_a_point(const detail::NeighbourIndex& index, const LocalFit& leaf) {
  std::vector<int> nearest;
  std::vector<double> d2;
  index.knn(leaf.centre, 1, nearest, d2);
  return d2[0] < leaf.radius * leaf.radius;
}

// The points of an n x n x n lattice over the leaf's cube that lie in its support ball (the
// fit's own checks use n = 9 and 5).
std::vector<Eigen::Vector3d> ball_lattice(const LocalFit& leaf, int n) {
  std::vector<Eigen::Vector3d> X;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d t =
            Eigen::Vector3d(i, j, k) * (2.0 / (n - 1)) - Eigen::Vector3d::Ones();
        if (t.squaredNorm() <= 1)
          X.push_back(leaf.centre + leaf.radius * t);
      }
  return X;
}

} // namespace

TEST_CASE("cloud implicit: zero set within the noise of sphere, torus and thin ellipsoid",
          "[clouds][implicit][heavy]") {
  // Bound (measured margins 1.5x to 2x over the 18 cases): the zero set's rms distance to the
  // truth at the mesh vertices is at most kRms sigma (the fits average 20 to 80 points: measured
  // 0.3 to 0.55 sigma) plus the noise-free error, which falls like spacing^2 (measured 0.08 to
  // 0.27 spacing^2 for unit bodies, spacing = sqrt(4 pi / n)).
  constexpr double kRms = 0.6, kBias = 0.5;
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid})
    for (const int n : {4000, 12000})
      for (const double sigma : {0.0, 0.002, 0.006}) {
        const test::SampledShape truth{shape};
        const PointCloud c = test::sample_shape(truth, n, sigma, 17);
        INFO("shape " << int(shape) << " n " << n << " sigma " << sigma);
        const Fitted f = fit(c, sigma);
        CHECK_FALSE(f.info.flipped);
        if (sigma > 0)
          CHECK(f.info.within_3_sigma > 0.99);
        // inside positive, outside negative, at offsets along the exact normals
        const PointCloud clean = test::sample_shape(truth, 2000, 0, 18);
        const double delta = std::max(5 * sigma, 0.03);
        const Eigen::VectorXd in = values(f.F, clean.points - delta * clean.normals);
        const Eigen::VectorXd out = values(f.F, clean.points + delta * clean.normals);
        CHECK((in.array() > 0).count() >= 1995);
        CHECK((out.array() < 0).count() >= 1995);
        // the zero set (mesh vertices lie on F = 0) against the exact surface
        ImplicitMeshOptions mo;
        mo.resolution = 48;
        Eigen::MatrixXd V;
        Eigen::MatrixXi T;
        implicit_mesh(f.F, mo, V, T);
        double s2 = 0;
        for (Eigen::Index i = 0; i < V.rows(); ++i)
          s2 += std::pow(truth.distance(V.row(i).transpose()), 2);
        const double rms = std::sqrt(s2 / double(V.rows()));
        const double spacing = std::sqrt(4 * M_PI / n); // sphere-like area / n
        CAPTURE(rms, f.info.leaves);
        CHECK(rms <= kRms * sigma + kBias * spacing * spacing);
      }
}

TEST_CASE("cloud implicit: exact gradient, batch-independent values, far field",
          "[clouds][implicit]") {
  const PointCloud c = test::sample_shape({test::Shape::torus}, 6000, 0.002, 21);
  const Fitted f = fit(c, 0.002);
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> U(-1.6, 1.6);
  Points3 P(500, 3);
  for (int i = 0; i < 500; ++i)
    P.row(i) << U(rng), U(rng), 0.3 * U(rng);
  Eigen::VectorXd v(500);
  Points3 G(500, 3);
  f.F.gradient(P, v, G);
  CHECK(v == values(f.F, P)); // value and gradient paths agree exactly
  const double h = 1e-6;
  for (int i = 0; i < 500; ++i)
    for (int a = 0; a < 3; ++a) {
      Points3 Q(2, 3);
      Q.row(0) = P.row(i);
      Q.row(1) = P.row(i);
      Q(0, a) += h;
      Q(1, a) -= h;
      const Eigen::VectorXd q = values(f.F, Q);
      // central difference error ~ h^2 F''' + round-off 1e-16 / h
      CHECK(G(i, a) ==
            Approx((q(0) - q(1)) / (2 * h)).epsilon(0).margin(1e-6 * (1 + G.row(i).norm())));
    }
  // the same point gives the same bits alone or in any batch
  for (int i = 0; i < 500; i += 7)
    CHECK(values(f.F, P.row(i))(0) == v(i));
  // far away: finite, negative, continuous across the root cube (F(x') - |x - x'|)
  Points3 far(3, 3);
  far << 100, 0, 0, 0, -1e6, 3, 2, 2, 2;
  const Eigen::VectorXd fv = values(f.F, far);
  CHECK((fv.array() < 0).all());
  CHECK(fv(1) < -9e5);
  const double edge = f.model->origin(0) + f.model->size;
  Points3 across(2, 3);
  across << edge - 1e-9, 0.1, 0.2, edge + 1e-9, 0.1, 0.2;
  const Eigen::VectorXd a = values(f.F, across);
  CHECK(a(1) == Approx(a(0)).epsilon(0).margin(1e-8));
}

TEST_CASE("cloud implicit: inward normals are detected and F negated", "[clouds][implicit]") {
  PointCloud c = test::sample_shape({test::Shape::sphere}, 3000, 0, 23);
  c.normals *= -1;
  const Fitted f = fit(c, 0);
  CHECK(f.info.flipped);
  Points3 P(2, 3);
  P << 0, 0, 0, 0, 0, 2;
  const Eigen::VectorXd v = values(f.F, P);
  CHECK(v(0) > 0.5);
  CHECK(v(1) < -0.5);
}

TEST_CASE("cloud implicit: a model that does not tile its cube is refused", "[clouds][implicit]") {
  const PointCloud c = test::sample_shape({test::Shape::sphere}, 3000, 0, 24);
  const Fitted f = fit(c, 0);
  auto bad = std::make_shared<CloudImplicit>(*f.model);
  bad->fits.pop_back();
  CHECK_THROWS_AS(cloud_implicit_function(bad), std::invalid_argument);
  bad = std::make_shared<CloudImplicit>(*f.model);
  bad->fits[0].cell(0) = 1 << bad->fits[0].level; // outside the cube
  CHECK_THROWS_AS(cloud_implicit_function(bad), std::invalid_argument);
  bad = std::make_shared<CloudImplicit>(*f.model);
  bad->fits[0].radius *= 0.5; // no longer covers its cell
  CHECK_THROWS_AS(cloud_implicit_function(bad), std::invalid_argument);
  CHECK_THROWS_AS(fit_cloud_implicit(PointCloud{c.points}, {}), std::invalid_argument);
}

TEST_CASE("cloud implicit: no spurious sheets beside and beyond thin walls",
          "[clouds][implicit][heavy]") {
  // Ellipsoids 0.1, 0.04 and 0.02 thick (semi-axes 1, 0.6, c) with rims of radius c^2 = 0.0025
  // to 0.0001 (blade edges): the tangent planes of both sides say "inside" past the rim, where
  // far cells used to put zero sheets (docs/benchmarks.md, run 1). A spurious sheet is measured
  // as F >= 0 at a probe outside the body: the exact offsets p + t n of 4000 clean samples (the
  // distance to a convex body is exactly t), t = kProbeSpacings point spacings plus kProbeSigmas
  // sigma, which reach beside the walls and past the rims; none may be non-negative (measured:
  // none from t = 0.05 for 12,000 points and t = 0.1 for 4000). A hole is F <= 0 on the
  // mid-plane inside 0.9 of the rim: at most kHoles of 2000 (measured 0 to 3; the noise is up to
  // a fifth of the wall).
  constexpr double kProbeSpacings = 3, kProbeSigmas = 5;
  constexpr long kHoles = 10;
  Points3 mid(2000, 3);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int i = 0; i < 2000;) {
    const double x = U(rng), y = 0.6 * U(rng);
    if (x * x + y * y / 0.36 <= 0.9 * 0.9)
      mid.row(i++) << x, y, 0;
  }
  for (const double c : {0.05, 0.02, 0.01})
    for (const double sigma : {0.0, 0.002})
      for (const int n : {4000, 12000}) {
        const test::SampledShape truth{test::Shape::ellipsoid, 1, c};
        const Fitted f = fit(test::sample_shape(truth, n, sigma, 25), sigma);
        const PointCloud clean = test::sample_shape(truth, 4000, 0, 26);
        const double spacing = std::sqrt(2 * M_PI * 0.6 / n); // the two faces' area / n
        const double t = kProbeSpacings * spacing + kProbeSigmas * sigma;
        const Eigen::VectorXd out = values(f.F, clean.points + t * clean.normals);
        const Eigen::VectorXd in = values(f.F, mid);
        INFO("thickness " << 2 * c << ", sigma " << sigma << ", n " << n << ", probes at " << t
                          << ", leaves " << f.info.leaves);
        CHECK((out.array() >= 0).count() == 0);
        CHECK((in.array() <= 0).count() <= kHoles);
      }
}

TEST_CASE("cloud implicit: the noise-aware neighbourhood, no worse with noise, no change without",
          "[clouds][implicit]") {
  // Over sigma / spacing from 0 to 0.5 (the blade scans: 0.13 and 0.42): the
  // scan noise estimate is sigma within 30 % (measured 0.86 to 1.0 sigma on the blade scans) and
  // ~0 without noise; the noise-aware zero set's rms distance to the truth is at most the fixed
  // rule's (the Cramer-Rao count averages more points) on noisy clouds, and the same to 1 %
  // without noise (rho ~ 0 leaves the clean count of 10 and the thresholds as they are).
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::ellipsoid})
    for (const double sigma : {0.0, 0.005, 0.01, 0.02}) {
      const test::SampledShape truth{shape};
      const PointCloud c = test::sample_shape(truth, 4000, sigma, 23);
      INFO("shape " << int(shape) << " sigma " << sigma);
      double rms[2] = {0, 0};
      CloudFitInfo info[2];
      for (int aware = 0; aware < 2; ++aware) {
        CloudFitOptions o;
        o.noise_aware = aware == 1;
        o.smooth_points = false; // the octree's rule alone (test_smooth_scan_points: both)
        const auto model = std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &info[aware]));
        ImplicitMeshOptions mo;
        mo.resolution = 48;
        Eigen::MatrixXd V;
        Eigen::MatrixXi T;
        implicit_mesh(cloud_implicit_function(model), mo, V, T);
        double s2 = 0;
        for (Eigen::Index i = 0; i < V.rows(); ++i)
          s2 += std::pow(truth.distance(V.row(i).transpose()), 2);
        rms[aware] = std::sqrt(s2 / double(V.rows()));
      }
      CAPTURE(rms[0], rms[1], info[1].scan_noise, info[1].spacing, info[1].min_points,
              info[1].acceptance);
      if (sigma > 0) {
        CHECK(info[1].scan_noise == Approx(sigma).epsilon(0.3));
        CHECK(rms[1] <= rms[0]);
      } else {
        CHECK(info[1].scan_noise < 0.01 * info[1].spacing);
        CHECK(info[1].min_points == 10);
        CHECK(rms[1] == Approx(rms[0]).epsilon(0.01));
      }
    }
}

TEST_CASE("cloud implicit: the sign on a box is a bound, and the narrow band meshes the same",
          "[clouds][implicit]") {
  // Random boxes of three sizes over sphere, torus and thin ellipsoid fits: wherever sign_on_box
  // claims a sign, F has it at every one of 64 random points of the box and at its 8 corners.
  for (const test::Shape shape :
       {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid}) {
    const PointCloud c = test::sample_shape({shape}, 5000, 0.003, 31);
    const Fitted f = fit(c, 0.003);
    REQUIRE(f.F.sign_on_box);
    std::mt19937 rng(32);
    std::uniform_real_distribution<double> U(0, 1);
    const Eigen::Vector3d lo = f.model->box.min(), size = f.model->box.sizes();
    long decided = 0;
    for (const double side : {0.02, 0.1, 0.4})
      for (int b = 0; b < 300; ++b) {
        const Eigen::Vector3d corner =
            lo + size.cwiseProduct(Eigen::Vector3d(U(rng), U(rng), U(rng)));
        const Eigen::AlignedBox3d B(corner, corner + Eigen::Vector3d::Constant(side));
        const int sign = f.F.sign_on_box(B);
        if (sign == 0)
          continue;
        ++decided;
        Points3 P(72, 3);
        for (int i = 0; i < 64; ++i)
          P.row(i) = (corner + side * Eigen::Vector3d(U(rng), U(rng), U(rng))).transpose();
        for (int i = 0; i < 8; ++i)
          P.row(64 + i) = B.corner(Eigen::AlignedBox3d::CornerType(i)).transpose();
        const Eigen::VectorXd v = values(f.F, P);
        INFO("shape " << int(shape) << " side " << side << " sign " << sign);
        CHECK((sign * v.array() > 0).all());
      }
    CHECK(decided > 300); // the bound decides most boxes away from the surface
    // The narrow band skips sub-boxes but gives the mesh of the full grid, triangle for triangle.
    ImplicitFunction full = f.F;
    full.sign_on_box = nullptr;
    ImplicitMeshOptions mo;
    mo.resolution = 64;
    mo.subboxes = Eigen::Array3i::Constant(8);
    Eigen::MatrixXd V1, V2;
    Eigen::MatrixXi T1, T2;
    ImplicitMeshInfo i1, i2;
    implicit_mesh(f.F, mo, V1, T1, &i1);
    implicit_mesh(full, mo, V2, T2, &i2);
    CHECK(i1.skipped > 0);
    CHECK(i2.skipped == 0);
    CHECK(i1.samples < i2.samples);
    CHECK(V1 == V2);
    CHECK(T1 == T2);
    // Inside one sub-box, blocks down to 4 cells with a sign are not sampled either (before
    // session 23 every node was): the same triangles from a fraction of the nodes. Measured:
    // sphere 0.31, torus 0.50, thin ellipsoid 0.62 of the nodes (at 64 cells the band of 4-cell
    // blocks is much of a thin body's box); bound 0.7.
    mo.subboxes = Eigen::Array3i::Ones();
    Eigen::MatrixXd V3;
    Eigen::MatrixXi T3;
    ImplicitMeshInfo i3;
    implicit_mesh(f.F, mo, V3, T3, &i3);
    CHECK(double(i3.samples) < 0.7 * double(i3.grid.size()));
    CHECK(T3.rows() == T1.rows());
  }
}

TEST_CASE("cloud implicit: 10 points per fit on clean clouds, and no dents in sampling gaps",
          "[clouds][implicit]") {
  // A clean cloud (rho < 0.002) gets 10 points per fit: its leaves stop only at min_points, and
  // smaller patches follow the curvature. The rms distance of the zero set to the truth at the
  // vertices of the default mesh (cell spacing / 2), 12,000 noise-free points: torus 0.90 x and
  // thin ellipsoid 0.84 x the rms with 20 points (the mean two-sided distance gains more: 0.68 to
  // 0.78 x, docs/benchmarks.md); bound 0.95 x. The sphere, a quadric everywhere, loses a little
  // (1.09 x measured; bound 1.15 x). Random sampling leaves holes wider than the support ball of a
  // leaf with 10 points; such a leaf takes its parent's fit when that fit is smooth there
  // (before, the far plane, normal to a direction along the surface, dented the zero set of this
  // sphere by 0.8 spacings, of a 50,000-point one by 4): the largest first-order distance
  // |F| / |grad F| of the zero set from 20,000 exact surface points is at most kGap spacings or
  // kLargest x the 20-point fit's (measured: sphere 0.025, torus 0.13, thin ellipsoid 0.25
  // spacings, 1.2 x the 20-point fit's).
  constexpr double kGap = 0.2, kLargest = 1.5;
  for (const test::Shape shape :
       {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid}) {
    const test::SampledShape truth{shape};
    const PointCloud c = test::sample_shape(truth, 12000, 0, 41);
    double rms[2] = {0, 0};
    CloudFitInfo info[2];
    ImplicitFunction F[2];
    for (int k = 0; k < 2; ++k) {
      CloudFitOptions o;
      o.min_points = k == 0 ? 20 : 0;
      const auto model = std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &info[k]));
      F[k] = cloud_implicit_function(model);
      ImplicitMeshOptions mo;
      mo.cell = info[k].spacing / 2; // the default cell (default_mesh_cell)
      Eigen::MatrixXd V;
      Eigen::MatrixXi T;
      implicit_mesh(F[k], mo, V, T);
      double s2 = 0;
      for (Eigen::Index i = 0; i < V.rows(); ++i)
        s2 += std::pow(truth.distance(V.row(i).transpose()), 2);
      rms[k] = std::sqrt(s2 / double(V.rows()));
    }
    const PointCloud exact = test::sample_shape(truth, 20000, 0, 42);
    double largest[2];
    for (int k = 0; k < 2; ++k) {
      Eigen::VectorXd v(exact.points.rows());
      Points3 G(exact.points.rows(), 3);
      F[k].gradient(exact.points, v, G);
      largest[k] = (v.array().abs() / G.rowwise().norm().array()).maxCoeff();
    }
    INFO("shape " << int(shape) << " rms 20 points " << rms[0] << ", automatic " << rms[1]
                  << ", spacing " << info[1].spacing << ", largest distance " << largest[0]
                  << ", automatic " << largest[1]);
    CHECK(info[1].min_points == 10);
    CHECK(rms[1] <= (shape == test::Shape::sphere ? 1.15 : 0.95) * rms[0]);
    CHECK(largest[1] <= std::max(kLargest * largest[0], kGap * info[1].spacing));
  }
}

namespace {

// The box [-1, 1] x [-1, 1] x [-0.1, 0.1]: its faces are planes that coarse cells can fit
// within the noise.
PointCloud slab_cloud(int n, double sigma, unsigned seed) {
  return test::box_cloud(Eigen::Vector3d(1, 1, 0.1), n, sigma, seed);
}

} // namespace

TEST_CASE("cloud implicit: coarse cells split on a sample give the full fits' model",
          "[clouds][implicit][heavy]") {
  // Cells whose fit ball holds 256 or more of every 16th point are split on those alone when
  // their fit misses them by more than 4 x the acceptance rms (info.sampled_splits). The claim:
  // the model is the one full fits give. The slab's faces are planes that cells of 4,000 points
  // and more fit within the noise, accepted at coarse levels: deciding on the sample at 0.5 x
  // the acceptance rms splits some of them and fails this test (measured; 0.8 x passes); the
  // curved shapes are split at every coarse level.
  const test::SampledShape sphere{test::Shape::sphere}, torus{test::Shape::torus},
      ellipsoid{test::Shape::ellipsoid};
  const std::pair<std::string, PointCloud> clouds[] = {
      {"slab", slab_cloud(60000, 0, 51)},
      {"noisy slab", slab_cloud(60000, 0.002, 52)},
      {"sphere", test::sample_shape(sphere, 20000, 0, 53)},
      {"noisy torus", test::sample_shape(torus, 20000, 0.006, 54)},
      {"ellipsoid", test::sample_shape(ellipsoid, 20000, 0, 55)}};
  for (const auto& [name, c] : clouds) {
    INFO(name);
    CloudFitOptions o;
    o.noise = name.rfind("noisy", 0) == 0 ? 0.002 + 0.004 * (name == "noisy torus") : 0;
    CloudFitInfo info[2];
    const CloudImplicit sampled = fit_cloud_implicit(c, o, &info[0]);
    o.sample_coarse = false;
    const CloudImplicit full = fit_cloud_implicit(c, o, &info[1]);
    CHECK(info[0].sampled_splits > 0);
    CHECK(info[1].sampled_splits == 0);
    CHECK(info[0].cells == info[1].cells);
    REQUIRE(sampled.fits.size() == full.fits.size());
    bool same = true; // the leaves' fits come from the same points: equal to the bit
    for (size_t i = 0; i < full.fits.size(); ++i) {
      const LocalFit &a = sampled.fits[i], &b = full.fits[i];
      same = same && a.level == b.level && (a.cell == b.cell).all() && a.sheets == b.sheets &&
             a.sheet[0].c == b.sheet[0].c && a.sheet[1].c == b.sheet[1].c;
    }
    CHECK(same);
  }
}

TEST_CASE("cloud implicit: leaves of wrong normals at a thin rim are negated to the flood fill's "
          "side, and an open cloud is left alone",
          "[clouds][implicit]") {
  // The ellipsoid 0.1 thick (semi-axes 1, 0.6, 0.05), its normals flipped on the rim's band
  // (x^2 + y^2 / 0.36 > r^2), as a noisy thin edge leaves them where neither the flood fill's
  // votes nor the winding number see a side. A spurious sheet is F >= 0 at an exact outside
  // probe p + t n of 4000 clean samples, t = 2 point spacings. Measured (bands 0.98, 0.95):
  // 73 and 126 such probes without the check, 3 and 6 with it; at 1 spacing 114 and 409
  // against 24 and 165; none at 5 either way.
  const test::SampledShape truth{test::Shape::ellipsoid, 1, 0.05};
  const PointCloud clean = test::sample_shape(truth, 4000, 0, 26);
  const int n = 12000;
  const double t = 2 * std::sqrt(2 * M_PI * 0.6 / n);
  for (const double r : {0.98, 0.95}) {
    PointCloud c = test::sample_shape(truth, n, 0, 25);
    long flipped = 0;
    for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
      const double x = c.points(i, 0), y = c.points(i, 1);
      if (x * x + y * y / 0.36 > r * r)
        c.normals.row(i) *= -1, ++flipped;
    }
    const auto [on, off, spurious_on, spurious_off] =
        fit_with_and_without_fill(c, clean.points + t * clean.normals);
    INFO("band " << r << ": " << flipped << " normals flipped, " << on.exterior_negated_leaves
                 << " leaves negated; probes F >= 0 with " << spurious_on << ", without "
                 << spurious_off);
    CHECK(off.exterior_negated_leaves == 0);
    CHECK(on.exterior_negated_leaves > 0);
    CHECK(spurious_off > 50);
    CHECK(10 * spurious_on < spurious_off);
  }
  // An open hemisphere: the fill reaches the inside through the opening, the winding number
  // disagrees with it, and no leaf is negated (the model is the one without the check).
  PointCloud cap = test::sample_shape({test::Shape::sphere, 1, 1}, 6000, 0, 27);
  std::vector<Eigen::Index> upper;
  for (Eigen::Index i = 0; i < cap.points.rows(); ++i)
    if (cap.points(i, 2) > 0)
      upper.push_back(i);
  cap.points = Points3(cap.points(upper, Eigen::all));
  cap.normals = Points3(cap.normals(upper, Eigen::all));
  CloudFitOptions o;
  CloudFitInfo info;
  const CloudImplicit with = fit_cloud_implicit(cap, o, &info);
  o.exterior_side = false;
  const CloudImplicit without = fit_cloud_implicit(cap, o);
  CHECK(info.exterior_negated_leaves == 0);
  const Points3 P = Points3::Random(500, 3);
  CHECK((values(cloud_implicit_function(std::make_shared<CloudImplicit>(with)), P) -
         values(cloud_implicit_function(std::make_shared<CloudImplicit>(without)), P))
            .cwiseAbs()
            .maxCoeff() == 0);
}

TEST_CASE("cloud implicit: leaves off the surface keep the flood fill's side over their ball",
          "[clouds][implicit][heavy]") {
  // A leaf whose support ball holds no point, on a trusted flood fill that labels the ball's
  // lattice points all one side, is off the surface; its Q must have that side's sign there.
  // Before far and gap leaves were checked against the fill, their side came from the winding
  // number or their parent's fit alone, and the thin ellipsoid (0.1 thick, clean and noisy) kept
  // one leaf that disagreed at 8 or more lattice points (on the Rotor 37 blade: blobs of F > 0
  // up to 0.77 cm off the tip corner; docs/benchmarks.md, "Far leaves on the flood fill's side").
  for (const test::SampledShape shape :
       {test::SampledShape{test::Shape::sphere}, test::SampledShape{test::Shape::torus},
        test::SampledShape{test::Shape::ellipsoid, 1, 0.05},
        test::SampledShape{test::Shape::ellipsoid}})
    for (const double sigma : {0.0, 0.003}) {
      const PointCloud c = test::sample_shape(shape, 12000, sigma, 31);
      const Fitted f = fit(c, sigma);
      const detail::ExteriorGrid g =
          detail::exterior_grid(c.points, detail::kVoxelSpacings * f.info.spacing);
      const detail::NeighbourIndex index(c.points);
      long empty = 0, one_sided = 0, disagreeing = 0;
      for (const LocalFit& leaf : f.model->fits) {
        if (ball_holds_a_point(index, leaf))
          continue;
        ++empty;
        int inside = 0, outside = 0, disagree = 0;
        for (const Eigen::Vector3d& x : ball_lattice(leaf, 9)) { // check_exterior's lattice
          const int side = detail::exterior_side(g, x);
          const double q = local_fit_value(leaf, x, nullptr);
          inside += side < 0;
          outside += side > 0;
          disagree += side != 0 && q != 0 && (q > 0) != (side < 0);
        }
        if (inside > 0 && outside > 0)
          continue;
        ++one_sided;
        disagreeing += disagree >= 8;
      }
      INFO("shape " << int(shape.shape) << " c " << shape.c << " sigma " << sigma << ": " << empty
                    << " empty leaves, " << one_sided << " one-sided, " << disagreeing
                    << " disagreeing");
      CHECK(one_sided > 100);
      CHECK(disagreeing == 0);
    }
}

TEST_CASE(
    "cloud implicit: where the flood fill leaks, no empty leaf has a zero set that a decisive "
    "winding number contradicts",
    "[clouds][implicit]") {
  // The Rotor 37 blade (its capped loft), 30,000 points, noise 0.005 cm, none within 0.75 cm of
  // S(0.25, 0.5): the hole goes through both faces, the flood fill leaks into the blade and is
  // not used. A leaf whose ball holds no point but whose Q changes sign in it puts a sheet of F
  // where no point is; where the winding number is decisive (below 0.02 or above 0.98 here,
  // within the fit's 0.05 with room for this test's winding number of the unsmoothed points), Q
  // must not contradict it at 2 or more lattice points (5^3 over the ball). Measured without
  // the check (check_sign's lattice branch): 2 such leaves of 5 with a sign change, a blob 0.5 cm
  // off the blade's tip corner (bench_clouds --points 30000: Chamfer 0.000699, with the check
  // 0.000618); with the slab split and this test's margin below, 1 of 1. A ball counts as empty
  // when no input point lies within its radius + a point spacing: the fit sees the points moved by
  // the smoothing, and a zero set within a spacing of the points is at the sampling's resolution.
  // Since the slab split (split_slabs) small leaves sit at the edges: 7 of radius 0.04 cm whose
  // nearest input point lies 1.00 to 1.14 radii away hold moved points, and a gap leaf of radius
  // 0.02 cm, 2.3 radii away, has Q > 0 where this test's winding number of the unsmoothed points is
  // below 0.02 at 2 lattice points.
  const PiecewiseSurface S = to_piecewise(loft_sections(test::rotor37()).surface);
  const Points3 scan = noisy_blade_scan(S, 30000, 3, 0.005, 10);
  const Eigen::RowVector3d centre = evaluate(S, 0.25, 0.5).transpose();
  std::vector<Eigen::Index> keep;
  for (Eigen::Index i = 0; i < scan.rows(); ++i)
    if ((scan.row(i) - centre).norm() > 0.75)
      keep.push_back(i);
  const PointCloud c = prepare_cloud("blade", PointCloud{scan(keep, Eigen::all)});
  CloudFitInfo info;
  const CloudImplicit m = fit_cloud_implicit(c, {}, &info);
  REQUIRE(info.exterior_negated_leaves + info.exterior_split_cells == 0); // the fill is not used
  const detail::NeighbourIndex index(c.points);
  const Eigen::VectorXd area =
      detail::point_areas(c.points, index.knn_all(detail::kAreaNeighbours, 1));
  const detail::WindingNumber winding(c.points, c.normals, area);
  const double spacing = detail::median_spacing(area); // 0.05 cm
  long empty = 0, sign_changes = 0, contradicted = 0;
  for (const LocalFit& leaf : m.fits) {
    std::vector<int> nearest;
    std::vector<double> d2;
    index.knn(leaf.centre, 1, nearest, d2);
    if (std::sqrt(d2[0]) < leaf.radius + spacing)
      continue;
    ++empty;
    const std::vector<Eigen::Vector3d> X = ball_lattice(leaf, 5); // check_sign's lattice
    std::vector<double> q;
    for (const Eigen::Vector3d& x : X)
      q.push_back(local_fit_value(leaf, x, nullptr));
    if (*std::min_element(q.begin(), q.end()) > 0 || *std::max_element(q.begin(), q.end()) < 0)
      continue;
    ++sign_changes;
    int wrong = 0;
    for (size_t l = 0; l < X.size(); ++l) {
      const double w = winding(X[l]);
      wrong += (w < 0.02 && q[l] > 0) || (w > 0.98 && q[l] < 0);
    }
    contradicted += wrong >= 2;
  }
  INFO(empty << " empty leaves, " << sign_changes << " with a sign change, " << contradicted
             << " contradicted; " << info.sign_fixed_leaves << " re-signed by the fit");
  CHECK(empty > 100);
  CHECK(contradicted == 0);
}

TEST_CASE("cloud implicit: a clean cloud's fits are held to its scan noise, not to the shape in "
          "estimate_noise",
          "[clouds][implicit]") {
  // A closed box 2 x 2 x 0.05 of 20,000 points with exact outward normals: 2.5 spacings thick,
  // so most of estimate_noise's 24-point quadrics straddle it (0.56 spacings read as noise)
  // while the scan noise is 0. Held to that sigma the points lay 0.07 spacings rms from the zero
  // set (2,920 leaves, measured); held to the scan noise 0.015 (5,748 leaves).
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1, 1);
  const double t = 0.05, face[3] = {4, 2 * t, 2 * t}; // areas of the box's faces along z, x, y
  std::discrete_distribution<int> pick({face[0], face[0], face[1], face[1], face[2], face[2]});
  PointCloud c;
  c.points.resize(20000, 3);
  c.normals = Eigen::MatrixX3d::Zero(20000, 3);
  for (Eigen::Index i = 0; i < 20000; ++i) {
    const int f = pick(rng), axis = f < 2 ? 2 : f < 4 ? 0 : 1;
    const double side = f % 2 ? -1 : 1;
    Eigen::Vector3d p(U(rng), U(rng), U(rng) * t / 2);
    p(axis) = side * (axis == 2 ? t / 2 : 1);
    c.points.row(i) = p.transpose();
    c.normals(i, axis) = side;
  }
  CloudFitOptions o;
  o.threads = 1;
  CloudFitInfo info;
  fit_cloud_implicit(c, o, &info);
  CAPTURE(info.noise, info.scan_noise, info.spacing, info.rms_distance, info.leaves);
  REQUIRE(info.noise > 0.3 * info.spacing); // estimate_noise reads the thickness
  REQUIRE(info.scan_noise < 0.002 * info.spacing);
  CHECK(info.rms_distance < 0.03 * info.spacing);
}

TEST_CASE("cloud implicit: on a noisy scan, cells whose fit contradicts the flood fill in part are "
          "split, clean clouds are not",
          "[clouds][implicit][heavy]") {
  // The two faces z = +-0.015 of the plate [-1, 1] x [-0.6, 0.6] (a spacing apart, one band of
  // the fill's shell), no points on its rim: each face fits as a plane, a cell over the rim joins
  // them into a slab that runs on past it, and the scan's noise (half a spacing) keeps such cells
  // large. Probes on the mid-plane z = 0 beyond the rim by 3 spacings + 3 sigma are outside.
  // Measured: 1,067 cells split (cells too sparse for a fit of their own split too), 4 leaves
  // negated; F >= 0 at none of the 280 probes, at all 280 without the fill and the slab split
  // (the slab reaches every one; 97 when only cells with a fit of their own were split), at 1
  // with the slab split alone (slab_past_edge finds it on the winding number); bound: a
  // twentieth.
  const int n = 40000;
  const double spacing = std::sqrt(2 * 2.0 * 1.2 / n), sigma = 0.5 * spacing;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> U(-1, 1);
  std::normal_distribution<double> G(0, sigma);
  PointCloud plate{Points3(n, 3), Points3(n, 3)};
  for (int i = 0; i < n; ++i) {
    const double side = i % 2 ? 1.0 : -1.0;
    plate.points.row(i) << U(rng), 0.6 * U(rng), side * 0.015 + G(rng);
    plate.normals.row(i) << 0, 0, side;
  }
  const double d = 3 * spacing + 3 * sigma;
  Points3 probes(280, 3);
  for (int i = 0; i < 50; ++i) {
    const double y = -0.5 + i / 49.0;
    probes.row(i) << 1 + d, y, 0;
    probes.row(50 + i) << -1 - d, y, 0;
  }
  for (int i = 0; i < 90; ++i) {
    const double x = -0.9 + 1.8 * i / 89.0;
    probes.row(100 + i) << x, 0.6 + d, 0;
    probes.row(190 + i) << x, -0.6 - d, 0;
  }
  const auto [on, off, spurious_on, spurious_off] = fit_with_and_without_fill(plate, probes, false);
  const WithAndWithoutFill slabs = fit_with_and_without_fill(plate, probes);
  INFO("split " << on.exterior_split_cells << ", negated " << on.exterior_negated_leaves
                << "; probes F >= 0 with " << spurious_on << ", without " << spurious_off
                << ", with the slab split alone " << slabs.spurious_off << " ("
                << slabs.off.slab_split_cells << " cells split)");
  CHECK(off.exterior_split_cells + off.slab_split_cells == 0);
  CHECK(on.exterior_split_cells > 0);
  CHECK(spurious_off == probes.rows());
  CHECK(20 * spurious_on < spurious_off);
  CHECK(20 * slabs.spurious_off < spurious_off);
  // A clean cloud (scan noise below kCleanScanNoise spacings) is never split on the fill.
  CloudFitInfo clean;
  fit_cloud_implicit(test::sample_shape({test::Shape::ellipsoid, 1, 0.05}, 12000, 0, 25), {},
                     &clean);
  CHECK(clean.exterior_split_cells == 0);
}

// The largest distance from the truth S of the mesh of F at its default cell, over the vertices
// whose foot lies off the caps (v in 0.02 to 0.98); *far: how many lie beyond `reach`.
double farthest_off_caps(const ImplicitFunction& F, const PiecewiseSurface& S, double reach,
                         long* far) {
  ImplicitMeshOptions mo;
  mo.cell = default_mesh_cell(F, F.box);
  Eigen::MatrixXd V;
  Eigen::MatrixXi T;
  implicit_mesh(F, mo, V, T);
  const SurfaceProjection truth = project_to_surface(S, V);
  double farthest = 0;
  *far = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (truth.v(i) > 0.02 && truth.v(i) < 0.98) {
      farthest = std::max(farthest, truth.distance(i));
      *far += truth.distance(i) > reach;
    }
  return farthest;
}

TEST_CASE("cloud implicit: on a noisy scan, no slab of two sheets runs on past a thin edge",
          "[clouds][implicit][heavy]") {
  // The Rotor 37 blade (its capped loft), 50,000 points, noise 0.02 cm. Two sheets joined into
  // a razor-thin slab (0.001 to 0.02 cm thick) ran on past the blade's edges up to a leaf's
  // radius: a fin of F > 0 whose mesh reached up to 0.44 cm off the truth (bench_clouds, 100,000
  // points). The mesh's vertices off the caps, measured by project_to_surface (independent of
  // the fit). Measured: without the slab split the farthest lies 0.237 cm off and 135 lie beyond
  // 0.1 cm; with it 0.099 cm and 0 (the noise's own reach at the edges: 5 sigma). (Before two
  // sheets' misfit was measured by the sheet that decides the join, session 31: 0.317 cm and 158
  // without the split, 0.102 cm and 3 with it.)
  const PiecewiseSurface S = to_piecewise(loft_sections(test::rotor37()).surface);
  const PointCloud c = prepare_cloud("blade", PointCloud{noisy_blade_scan(S, 50000, 4, 0.02, 11)});
  CloudFitOptions o;
  CloudFitInfo on, off;
  const ImplicitFunction F =
      cloud_implicit_function(std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &on)));
  o.split_slabs = false;
  const ImplicitFunction F0 =
      cloud_implicit_function(std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &off)));
  long far = 0, far_off = 0;
  const double farthest = farthest_off_caps(F, S, 0.1, &far);
  const double farthest_off = farthest_off_caps(F0, S, 0.1, &far_off);
  INFO("farthest vertex " << farthest << " cm, " << far << " beyond 0.1 cm (" << on.slab_split_cells
                          << " cells split); without the split " << farthest_off << " cm, "
                          << far_off);
  CHECK(off.slab_split_cells == 0);
  CHECK(on.slab_split_cells > 0);
  CHECK(farthest_off > 0.2);
  CHECK(farthest < 0.15);
  CHECK(far * 10 < far_off);
}

TEST_CASE("cloud implicit: edge sheets keep a box's edges sharp", "[clouds][implicit]") {
  // One quadric across a 90-degree edge rounds it by up to the acceptance's misfit; edge sheets
  // (CloudFitOptions::edge_sheets) join the two faces' sheets there. The mean distance of the
  // default mesh's vertices to the box near its edges (within 3 spacings of two faces) and
  // elsewhere, with and without edge sheets, 12,000 points, clean and with noise 0.3 spacings.
  // Off, the noisy box's smoothing rounds the edges too (its edge projection follows the same
  // option). Measured near edges 0.51 x (clean) and 0.61 x (noisy) the quadrics' distance, bound
  // 0.7 x; elsewhere 0.72 x and 0.94 x, bound 1 x (no worse).
  const Eigen::Vector3d h(0.5, 0.4, 0.3);
  for (const double sigma : {0.0, 0.005}) {
    const PointCloud c = test::box_cloud(h, 12000, sigma, sigma > 0 ? 62 : 61);
    double edge[2] = {0, 0}, rest[2] = {0, 0};
    CloudFitInfo info[2];
    for (int k = 0; k < 2; ++k) {
      CloudFitOptions o;
      o.edge_sheets = k == 1;
      const auto model = std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &info[k]));
      ImplicitMeshOptions mo;
      mo.cell = info[k].spacing / 2; // the default cell (default_mesh_cell)
      Eigen::MatrixXd V;
      Eigen::MatrixXi T;
      implicit_mesh(cloud_implicit_function(model), mo, V, T);
      long ne = 0, nr = 0;
      for (Eigen::Index i = 0; i < V.rows(); ++i) {
        const Eigen::Vector3d p = V.row(i).transpose();
        const double d = std::abs(test::box_distance(h, p));
        if (test::near_box_edge(h, p, 3 * info[k].spacing))
          edge[k] += d, ++ne;
        else
          rest[k] += d, ++nr;
      }
      edge[k] /= double(ne);
      rest[k] /= double(nr);
    }
    INFO("sigma " << sigma << " spacing " << info[1].spacing << ": near edges " << edge[0] << " -> "
                  << edge[1] << ", elsewhere " << rest[0] << " -> " << rest[1]);
    CHECK(edge[1] <= 0.7 * edge[0]);
    CHECK(rest[1] <= 1.0 * rest[0]);
  }
}

TEST_CASE("cloud implicit: no pockets of F < 0 in the thin walls under the valve's slots",
          "[clouds][implicit][heavy]") {
  // The valve model (data/models/valve.rf): 16 slots 0.3 cm wide in its seat flange, their
  // floors 0.2 cm above the flange's underside; 50,000 points on its zero set (the bench's
  // model_cloud: a mesh's samples moved onto F = 0), noise 0.001 x the diagonal, normals
  // estimated. A slot wall's sheet carried below the slot floor says "outside" in that wall,
  // and the partition of unity leaves pockets of F < 0 there: the fitted mesh's vertices more
  // than 8 sigma inside the true solid (the model's |F| / |grad F|; the noise alone puts none
  // there). Measured: 154 with the split (24 cells), 267 without; at 30,000 points 127 and
  // 165, at 100,000 68 and 118. Bound: a quarter fewer.
  const ImplicitFunction truth = load_model(std::string(INTERLIN_DATA_DIR) + "/models/valve.rf");
  ImplicitMeshOptions tm;
  tm.resolution = 256;
  Eigen::MatrixXd TV;
  Eigen::MatrixXi TT;
  implicit_mesh(truth, tm, TV, TT);
  const double diagonal = (TV.colwise().maxCoeff() - TV.colwise().minCoeff()).norm();
  const double sigma = 0.001 * diagonal;
  PointCloud s = sample_mesh(TV, TT, 50000, 3);
  for (int it = 0; it < 2; ++it) { // onto F = 0 (Newton along the gradient)
    Eigen::VectorXd v(s.points.rows());
    Points3 G(s.points.rows(), 3);
    truth.gradient(s.points, v, G);
    for (Eigen::Index i = 0; i < s.points.rows(); ++i)
      if (const double g2 = G.row(i).squaredNorm(); g2 > 0)
        s.points.row(i) -= v(i) / g2 * G.row(i);
  }
  std::mt19937 rng(4);
  std::normal_distribution<double> noise(0, sigma);
  for (Eigen::Index i = 0; i < s.points.rows(); ++i)
    for (int a = 0; a < 3; ++a)
      s.points(i, a) += noise(rng);
  const PointCloud c = prepare_cloud("valve", PointCloud{s.points});
  const auto pocket_vertices = [&](bool split, CloudFitInfo& info) {
    CloudFitOptions o;
    o.split_pockets = split;
    const ImplicitFunction F =
        cloud_implicit_function(std::make_shared<CloudImplicit>(fit_cloud_implicit(c, o, &info)));
    ImplicitMeshOptions mo;
    mo.cell = default_mesh_cell(F, F.box);
    Eigen::MatrixXd V;
    Eigen::MatrixXi T;
    implicit_mesh(F, mo, V, T);
    Eigen::VectorXd v(V.rows());
    Points3 G(V.rows(), 3);
    truth.gradient(V, v, G);
    long inside = 0;
    for (Eigen::Index i = 0; i < V.rows(); ++i)
      inside += v(i) > 8 * sigma * G.row(i).norm();
    return inside;
  };
  CloudFitInfo on, off;
  const long with = pocket_vertices(true, on), without = pocket_vertices(false, off);
  INFO(on.pocket_split_cells << " cells split; vertices more than 8 sigma inside the solid: "
                             << with << ", without the split " << without);
  CHECK(off.pocket_split_cells == 0);
  CHECK(on.pocket_split_cells > 0);
  CHECK(without > 100);
  CHECK(4 * with < 3 * without);
}
