// Point-cloud implicits in .ifl files (kinds cloud_pu and cloud_hrbf): written and read back, a
// model evaluates to the same doubles (value and gradient) as the fitted one, through load_ifl like
// any model; blocks that break the kind's rules are refused with the block's InputError.

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/load_implicit.h"
#include "interlin/interflatation/models/ifl_registry.h"
#include "interlin/reconstruction/clouds/cloud_implicit_ifl.h"
#include "interlin/reconstruction/clouds/hermite_rbf.h"

#include "support/test_clouds.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <fstream>
#include <memory>
#include <random>
#include <sstream>

using namespace interlin;

namespace {

std::string text(const IflBlock& b) {
  std::ostringstream s;
  write_ifl(s, b);
  return s.str();
}

} // namespace

TEST_CASE("cloud .ifl: read back exactly, loaded through the registry", "[clouds][ifl]") {
  register_cloud_ifl_kind();
  register_cloud_ifl_kind(); // idempotent
  test::TempDir d("cloudifl");
  std::mt19937 rng(3);
  for (const test::Shape shape :
       {test::Shape::sphere, test::Shape::torus, test::Shape::ellipsoid}) {
    const PointCloud c = test::sample_shape({shape}, 3000, 0.003, 31);
    CloudFitOptions o;
    o.noise = 0.003;
    CloudFitInfo info;
    auto fitted = std::make_shared<const CloudImplicit>(fit_cloud_implicit(c, o, &info));
    const ImplicitFunction F = cloud_implicit_function(fitted);
    const std::string path = d / "m.ifl";
    std::ofstream(path, std::ios::binary) << text(to_ifl(*fitted, info.noise));
    const ImplicitFunction G = load_implicit(path);
    CHECK(G.box.min() == F.box.min());
    CHECK(G.box.max() == F.box.max());
    // points near the surface, inside, outside and beyond the root cube
    std::uniform_real_distribution<double> U(-2.5, 2.5);
    Points3 P(400, 3);
    for (int i = 0; i < 400; ++i)
      P.row(i) = i < 200 ? c.points.row(i * 7) : Eigen::RowVector3d(U(rng), U(rng), U(rng));
    Eigen::VectorXd f(400), g(400);
    Points3 Df(400, 3), Dg(400, 3);
    F.gradient(P, f, Df);
    G.gradient(P, g, Dg);
    CHECK(f == g); // bit-identical
    CHECK(Df == Dg);
    // the detail F resolves travels with the model (it sets the default mesh cell): twice the
    // point spacing, the noise (0.05 spacings) having had the points smoothed
    CHECK(info.smoothed_points > 0);
    CHECK(info.spacing > 0);
    CHECK(fitted->spacing == 2 * info.spacing);
    CHECK(F.sample_spacing == fitted->spacing);
    CHECK(G.sample_spacing == fitted->spacing);
    // and the file written again from the read model is the same file
    const CloudImplicit back = cloud_implicit_from_ifl(read_ifl(path));
    CHECK(text(to_ifl(back, info.noise)) == text(to_ifl(*fitted, info.noise)));
  }
}

TEST_CASE("cloud .ifl: blocks that break the kind's rules are refused", "[clouds][ifl]") {
  register_cloud_ifl_kind();
  const PointCloud c = test::sample_shape({test::Shape::sphere}, 2000, 0, 32);
  const CloudImplicit m = fit_cloud_implicit(c, {});
  const IflBlock good = to_ifl(m, 0);
  auto refused = [&](const IflBlock& b, const std::string& what) {
    INFO(what);
    CHECK_THROWS_AS(load_ifl_model(b, "x.ifl"), InputError);
    CHECK_THROWS_WITH(load_ifl_model(b, "x.ifl"), Catch::Contains(what));
  };
  IflBlock b = good;
  b.arrays["sheets"].i64[0] = 3;
  refused(b, "sheets must be 1 or 2");
  b = good;
  b.arrays["sheet"].f64[5] = std::nan("");
  refused(b, "not finite");
  b = good;
  b.arrays["sheet"].f64[3] = 2; // frame row 0 no longer a unit vector
  refused(b, "not orthonormal");
  b = good;
  b.arrays["radius"].f64[0] *= 0.5;
  refused(b, "does not cover its cell");
  b = good;
  b.arrays["cell"].dims = {1, 3};
  refused(b, "cell");
  b = good;
  b.numbers["support"] = 0.4;
  refused(b, "support > 0.5");
  b = good;
  b.numbers.erase("version");
  refused(b, "version");
  b = good;
  b.numbers["spacing"] = -1;
  refused(b, "spacing >= 0");
  // a file written before the spacing was stored: read, spacing unknown (0)
  b = good;
  b.numbers.erase("spacing");
  CHECK(load_ifl_model(b, "x.ifl").sample_spacing == 0);
}

TEST_CASE("cloud .ifl: the Hermite RBF read back exactly, bad blocks refused", "[clouds][ifl]") {
  register_cloud_ifl_kind();
  test::TempDir d("hrbfifl");
  const PointCloud c = test::sample_shape({test::Shape::torus}, 300, 0.001, 33);
  const auto fitted = std::make_shared<const HermiteRbf>(fit_hermite_rbf(c));
  const ImplicitFunction F = hermite_rbf_function(fitted);
  const std::string path = d / "r.ifl";
  std::ofstream(path, std::ios::binary) << text(to_ifl(*fitted));
  const ImplicitFunction G = load_implicit(path);
  CHECK(G.box.min() == F.box.min());
  CHECK(G.box.max() == F.box.max());
  CHECK(G.sample_spacing == fitted->spacing);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> U(-2, 2);
  Points3 P(200, 3);
  for (int i = 0; i < 200; ++i)
    P.row(i) = i < 100 ? c.points.row(i * 3) : Eigen::RowVector3d(U(rng), U(rng), U(rng));
  Eigen::VectorXd f(200), g(200);
  Points3 Df(200, 3), Dg(200, 3);
  F.gradient(P, f, Df);
  G.gradient(P, g, Dg);
  CHECK(f == g); // bit-identical: 17 significant digits give the doubles back
  CHECK(Df == Dg);
  CHECK(text(to_ifl(hermite_rbf_from_ifl(read_ifl(path)))) == text(to_ifl(*fitted)));

  const IflBlock good = to_ifl(*fitted);
  auto refused = [&](const IflBlock& b, const std::string& what) {
    INFO(what);
    CHECK_THROWS_AS(load_ifl_model(b, "x.ifl"), InputError);
    CHECK_THROWS_WITH(load_ifl_model(b, "x.ifl"), Catch::Contains(what));
  };
  IflBlock b = good;
  b.arrays["b"].f64[7] = std::nan("");
  refused(b, "not finite");
  b = good;
  b.arrays["points"].dims = {299, 3};
  refused(b, "points");
  b = good;
  b.numbers["scale"] = 0;
  refused(b, "scale > 0");
  b = good;
  b.arrays["a"].f64.resize(3);
  b.arrays["a"].dims = {3};
  refused(b, "fewer than 4 centres");
}
