// The shipped R-function models (data/models/*.rf, issue 5 part A) meshed by implicit_mesh: closed
// meshes of the expected topology, and the volumes of seed 000's impeller and UAV converging to
// the digest's Monte Carlo values (T19: 1234, T21: 7.565, +-0.5 %) and to an independent
// stratified Monte Carlo estimate (interflatation/volume_estimate.h) as the grid is refined.
#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/interflatation/rfunctions/volume_estimate.h"
#include "interlin/reconstruction/meshing/implicit_mesh.h"
#include "interlin/reconstruction/meshing/mesh_check.h"

#include "support/test_implicits.h"
#include "support/test_support.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

using namespace interlin;

namespace {

std::string model(const std::string& name) {
  return std::string(INTERLIN_DATA_DIR) + "/models/" + name;
}

struct Level {
  double h, volume;
};

// Meshes at each resolution; every mesh must be closed.
std::vector<Level> volumes(const ImplicitFunction& f, const std::vector<int>& resolutions) {
  std::vector<Level> out;
  for (int n : resolutions) {
    const test::CheckedMesh m = test::checked_mesh(f, test::at_resolution(n));
    INFO("resolution " << n);
    REQUIRE(m.report.watertight());
    out.push_back({m.info.grid.spacing(0), m.report.volume});
  }
  return out;
}

double order_against(const std::vector<Level>& L, double reference) {
  std::vector<double> h, e;
  for (const Level& l : L) {
    h.push_back(l.h);
    e.push_back(std::abs(l.volume - reference));
  }
  return test::fitted_order(h, e);
}

} // namespace

TEST_CASE("Shipped models mesh into closed surfaces of the expected topology", "[model]") {
  struct Case {
    const char* file;
    int resolution;
    long genus; // -1: not asserted
  };
  // valve: one solid (the bore is closed at the top); NACA plate: three holes; UAV: one solid.
  // The car's wheels touch their arches, so its genus depends on the grid and is not asserted.
  const Case cases[] = {
      {"valve.rf", 96, 0}, {"naca0011_plate.rf", 120, 3}, {"uav.rf", 184, 0}, {"car.rf", 80, -1}};
  for (const Case& c : cases) {
    const MeshReport r =
        test::checked_mesh(load_model(model(c.file)), test::at_resolution(c.resolution)).report;
    INFO(c.file);
    CHECK(r.watertight());
    CHECK(r.volume > 0);
    if (c.genus >= 0)
      CHECK(r.genus == c.genus);
  }
}

TEST_CASE("Impeller volume converges to 1234 (digest 000 T19) and to a stratified Monte Carlo "
          "estimate",
          "[model]") {
  const ImplicitFunction f = load_model(model("impeller.rf"));
  const VolumeEstimate mc = estimate_volume(f, 0.15, 1, 2);
  // h = 0.4 .. 0.132: the 0.4-thick blades go from one cell to three.
  const std::vector<Level> L = volumes(f, {66, 100, 132, 200});
  // Measured: 1246.0, 1234.7, 1232.3, 1232.6 against 1233.0 +- 0.4; the error falls faster
  // than h^2 while the blades become resolved (fitted order 3.2), then sits at the level of the
  // grid-alignment scatter of the flat faces (about +-0.1 %).
  const double order = order_against(L, mc.volume);
  CHECK(order > 1.5);
  for (const Level& l : L)
    if (l.h <= 0.27) {
      CHECK(std::abs(l.volume - 1234) < 0.005 * 1234);
      // Against the independent estimate: 0.15 % (alignment scatter) plus 4 standard errors.
      CHECK(std::abs(l.volume - mc.volume) < 0.0015 * mc.volume + 4 * mc.standard_error);
    }
}

TEST_CASE("UAV volume converges to 7.565 (digest 000 T21) and to a stratified Monte Carlo "
          "estimate",
          "[model]") {
  const ImplicitFunction f = load_model(model("uav.rf"));
  const VolumeEstimate mc = estimate_volume(f, 0.05, 1, 2);
  // h = 0.071 .. 0.025: the fins are 0.064 thick and the wing slabs 0.1, so these grids are
  // still pre-asymptotic: whether a fin or a slab rim gets one node layer or two depends on the
  // grid's alignment, and the error alternates in sign while its size falls (measured: +0.024,
  // -0.028, +0.017, -0.003 against 7.560 +- 0.004, fitted order 1.9; 1.1 on other grids).
  const std::vector<Level> L = volumes(f, {130, 184, 260, 368});
  CHECK(order_against(L, mc.volume) > 0.5);
  const Level& fine = L.back();
  CHECK(std::abs(fine.volume - 7.565) < 0.005 * 7.565);
  CHECK(std::abs(fine.volume - mc.volume) < 0.002 * mc.volume + 4 * mc.standard_error);
}
