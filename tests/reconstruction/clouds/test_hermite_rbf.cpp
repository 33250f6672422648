// Hermite RBF interpolation of sparse clouds (Macêdo, Gois, Velho 2011): the interpolation
// conditions and side conditions as solved, the gradient against central differences, sign and
// accuracy against exact surfaces with the observed convergence order, against the partition of
// unity on the same sparse clouds, and bad input.

#include "interlin/reconstruction/clouds/choose_cloud_fit.h"
#include "interlin/reconstruction/clouds/cloud_implicit.h"
#include "interlin/reconstruction/clouds/hermite_rbf.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"

#include "support/test_clouds.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

using namespace interlin;

namespace {

ImplicitFunction hrbf(const PointCloud& c, HermiteRbfInfo* info = nullptr) {
  return hermite_rbf_function(std::make_shared<const HermiteRbf>(fit_hermite_rbf(c, info)));
}

// rms distance of the zero set (mesh vertices) to the exact surface
double zero_set_rms(const ImplicitFunction& F, const test::SampledShape& truth) {
  ImplicitMeshOptions mo;
  mo.resolution = 64;
  Eigen::MatrixXd V;
  Eigen::MatrixXi T;
  implicit_mesh(F, mo, V, T);
  double s2 = 0;
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    s2 += std::pow(truth.distance(V.row(i).transpose()), 2);
  return std::sqrt(s2 / double(V.rows()));
}

} // namespace

TEST_CASE("hermite rbf: F = 0 and grad F = -n at every point, side conditions", "[clouds][hrbf]") {
  const test::SampledShape torus{test::Shape::torus};
  const PointCloud c = test::sample_shape(torus, 300, 0, 3);
  const HermiteRbf m = fit_hermite_rbf(c);
  const ImplicitFunction F = hermite_rbf_function(std::make_shared<const HermiteRbf>(m));
  Eigen::VectorXd v(c.points.rows());
  Points3 G(c.points.rows(), 3);
  F.gradient(c.points, v, G);
  // Cholesky of a system of 1204 unknowns with kernel values of order 1: round-off ~1e-12
  CHECK(v.cwiseAbs().maxCoeff() < 1e-9);
  CHECK((G + c.normals).rowwise().norm().maxCoeff() < 1e-8);
  CHECK(std::abs(m.a.sum()) < 1e-9);
  CHECK((m.points.transpose() * m.a + m.b.colwise().sum().transpose()).norm() < 1e-9);
}

TEST_CASE("hermite rbf: the gradient is the derivative of the value", "[clouds][hrbf]") {
  const test::SampledShape ellipsoid{test::Shape::ellipsoid};
  const ImplicitFunction F = hrbf(test::sample_shape(ellipsoid, 200, 0, 5));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.1, 1.1);
  Points3 P(50, 3);
  for (Eigen::Index i = 0; i < P.rows(); ++i)
    P.row(i) << U(rng), 0.6 * U(rng), 0.3 * U(rng);
  Eigen::VectorXd v(P.rows());
  Points3 G(P.rows(), 3);
  F.gradient(P, v, G);
  Eigen::VectorXd v2(P.rows());
  F.value(P, v2);
  CHECK((v - v2).cwiseAbs().maxCoeff() < 1e-12); // the same sums, in another order
  constexpr double h = 1e-6; // central differences: error h^2 |F'''| + eps |F| / h
  for (int c = 0; c < 3; ++c) {
    Points3 Pp = P, Pm = P;
    Pp.col(c).array() += h;
    Pm.col(c).array() -= h;
    Eigen::VectorXd fp(P.rows()), fm(P.rows());
    F.value(Pp, fp);
    F.value(Pm, fm);
    CHECK(((fp - fm) / (2 * h) - G.col(c)).cwiseAbs().maxCoeff() < 1e-6);
  }
}

TEST_CASE("hermite rbf: sign, accuracy and convergence order on sparse clouds",
          "[clouds][hrbf][heavy]") {
  for (const test::Shape shape :
       {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid}) {
    const test::SampledShape truth{shape};
    std::vector<double> spacing, error;
    for (const int n : {100, 200, 400, 800}) {
      const PointCloud c = test::sample_shape(truth, n, 0, 11);
      HermiteRbfInfo info;
      const ImplicitFunction F = hrbf(c, &info);
      CHECK_FALSE(info.flipped);
      spacing.push_back(info.spacing);
      error.push_back(zero_set_rms(F, truth));
      INFO("shape " << int(shape) << " n " << n << " rms " << error.back());
      const PointCloud probe = test::sample_shape(truth, 1000, 0, 12);
      const double delta = 0.05; // beyond the zero set's error at n = 100 (measured < 0.01)
      Eigen::VectorXd in(1000), out(1000);
      F.value(probe.points - delta * probe.normals, in);
      F.value(probe.points + delta * probe.normals, out);
      // all right, but for the thin ellipsoid at 100 points: its rim (radius of curvature
      // 0.0225) between points about 0.35 apart (measured 8 and 4 probes wrong there)
      const long right = shape == test::Shape::ellipsoid && n == 100 ? 990 : 1000;
      CHECK((in.array() > 0).count() >= right);
      CHECK((out.array() < 0).count() >= right);
    }
    // observed order: least-squares slope of log error against log spacing
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t k = 0; k < error.size(); ++k) {
      const double x = std::log(spacing[k]), y = std::log(error[k]);
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double m = double(error.size());
    const double order = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    CAPTURE(int(shape), order, error[0], error[3]);
    // measured: sphere 4.15, torus 5.9 (still pre-asymptotic at 100 points), ellipsoid 2.06 (the
    // rim is not resolved below 800 points)
    CHECK(order > (shape == test::Shape::ellipsoid ? 1.8 : 3.5));
  }
}

TEST_CASE("hermite rbf: more accurate than the partition of unity on sparse clouds",
          "[clouds][hrbf]") {
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid})
    for (const int n : {150, 400}) {
      const test::SampledShape truth{shape};
      const PointCloud c = test::sample_shape(truth, n, 0, 21);
      const double rbf = zero_set_rms(hrbf(c), truth);
      const double pu = zero_set_rms(
          cloud_implicit_function(std::make_shared<const CloudImplicit>(fit_cloud_implicit(c))),
          truth);
      CAPTURE(int(shape), n, rbf, pu);
      // measured 0.0016 to 0.15; the thin ellipsoid at 150 points 0.35, since its partition of
      // unity (read as a noisy scan) splits the slabs past its rim (0.052 -> 0.020)
      CHECK(rbf < (shape == test::Shape::ellipsoid && n == 150 ? 0.5 : 0.2) * pu);
    }
}

TEST_CASE("hermite rbf: inward normals flipped, bad clouds refused", "[clouds][hrbf]") {
  const test::SampledShape sphere{test::Shape::sphere};
  PointCloud c = test::sample_shape(sphere, 100, 0, 1);
  c.normals = -c.normals;
  HermiteRbfInfo info;
  const ImplicitFunction F = hrbf(c, &info);
  CHECK(info.flipped);
  Eigen::VectorXd v(1);
  F.value(Points3::Zero(1, 3), v);
  CHECK(v(0) > 0.5); // the centre is inside, about the distance 1 away
  PointCloud bare = c;
  bare.normals.resize(0, 3);
  CHECK_THROWS_AS(fit_hermite_rbf(bare), std::invalid_argument);
  PointCloud three = c;
  three.points.conservativeResize(3, 3);
  three.normals.conservativeResize(3, 3);
  CHECK_THROWS_AS(fit_hermite_rbf(three), std::invalid_argument);
  PointCloud twice = c;
  twice.points.row(1) = twice.points.row(0);
  CHECK_THROWS_AS(fit_hermite_rbf(twice), std::invalid_argument);
  const PointCloud many = test::sample_shape(sphere, int(kHermiteRbfMaxPoints) + 1, 0, 2);
  CHECK_THROWS_AS(fit_hermite_rbf(many), std::invalid_argument);
}

TEST_CASE("hermite rbf: the hold-out choice between the fits", "[clouds][hrbf]") {
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::torus}) {
    const test::SampledShape truth{shape};
    const PointCloud c = test::sample_shape(truth, 300, 0, 23);
    const CloudFitChoice a = choose_cloud_fit(c), b = choose_cloud_fit(c);
    CHECK(a.holdout_hrbf == b.holdout_hrbf); // the folds are seeded: deterministic
    CHECK(a.holdout_pu == b.holdout_pu);
    // smooth bodies: the interpolant predicts the held-out points far better (the fits' zero
    // sets are 10 to 600 times apart here, "more accurate than the partition of unity")
    CAPTURE(int(shape), a.holdout_hrbf, a.holdout_pu);
    CHECK(a.hermite);
    CHECK(a.holdout_hrbf < 0.2 * a.holdout_pu);
  }
  // a fold of 16 points is too few for the partition of unity (20 per fit): the RBF alone
  const CloudFitChoice few = choose_cloud_fit(test::sample_shape({test::Shape::sphere}, 20, 0, 24));
  CHECK(std::isnan(few.holdout_pu));
  CHECK(few.hermite);
  CHECK_THROWS_AS(choose_cloud_fit(test::sample_shape({test::Shape::sphere}, 501, 0, 25)),
                  std::invalid_argument);
}
