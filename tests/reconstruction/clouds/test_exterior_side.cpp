// The flood fill's outside votes (private exterior_side.h) on clouds whose outside is known.

#include "exterior_side.h"

#include "support/test_clouds.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace interlin;

namespace {

struct Tally {
  long right = 0, wrong = 0, none = 0;
};

// Votes against the exact outward normals: +1 right, -1 wrong, 0 none.
Tally tally(const std::vector<signed char>& vote) {
  Tally t;
  for (const signed char v : vote)
    (v > 0 ? t.right : v < 0 ? t.wrong : t.none)++;
  return t;
}

// The voxel of exterior_votes' callers: 1.5 point spacings, spacing = sqrt(area / n).
double voxel_for(double area, long n) {
  return 1.5 * std::sqrt(area / double(n));
}

} // namespace

TEST_CASE("exterior votes: closed bodies get the side of every normal right", "[clouds][normals]") {
  // Sphere (radius 1) and torus (tube 0.3) of 6000 points: the shell is 3 voxels (about 0.2 and
  // 0.13) thick, so every point sees the inside behind it. Measured: 6000 of 6000 right on
  // both at sigma 0 and 0.01. No vote may be wrong: a wrong vote pins a patch
  // to the wrong side.
  for (const test::Shape shape : {test::Shape::sphere, test::Shape::torus})
    for (const double sigma : {0.0, 0.01}) {
      const test::SampledShape truth{shape};
      const double area = shape == test::Shape::sphere ? 4 * M_PI : 4 * M_PI * M_PI * 0.3;
      const PointCloud c = test::sample_shape(truth, 6000, sigma, 3);
      const double voxel = voxel_for(area, 6000);
      const Tally out = tally(detail::exterior_votes(c.points, c.normals, voxel));
      INFO("shape " << int(shape) << " sigma " << sigma << ": right " << out.right << ", wrong "
                    << out.wrong << ", none " << out.none);
      CHECK(out.wrong == 0);
      CHECK(out.right >= 0.95 * 6000);
      // the same cloud with every normal turned inward: every vote turns with it
      const Tally in = tally(detail::exterior_votes(c.points, -c.normals, voxel));
      CHECK(in.right == out.wrong);
      CHECK(in.wrong == out.right);
    }
}

TEST_CASE("exterior votes: no vote where the shell hides the inside or the outside leaks in",
          "[clouds][normals]") {
  SECTION("a wall thinner than the shell (ellipsoid 0.04 thick)") {
    const PointCloud c = test::sample_shape({test::Shape::ellipsoid, 1, 0.02}, 6000, 0, 4);
    const Tally t =
        tally(detail::exterior_votes(c.points, c.normals, voxel_for(2 * M_PI * 0.6, 6000)));
    CHECK(t.wrong == 0);
    CHECK(t.right == 0);
  }
  SECTION("an open cloud: the upper hemisphere") {
    const PointCloud s = test::sample_shape({test::Shape::sphere}, 6000, 0, 5);
    Eigen::MatrixX3d P(0, 3), N(0, 3);
    for (Eigen::Index i = 0; i < s.points.rows(); ++i)
      if (s.points(i, 2) > 0) {
        P.conservativeResize(P.rows() + 1, 3);
        N.conservativeResize(N.rows() + 1, 3);
        P.row(P.rows() - 1) = s.points.row(i);
        N.row(N.rows() - 1) = s.normals.row(i);
      }
    const Tally t = tally(detail::exterior_votes(P, N, voxel_for(4 * M_PI, 6000)));
    CHECK(t.wrong == 0);
    CHECK(t.right == 0);
  }
}

TEST_CASE("exterior votes: degenerate input and the voxel limit", "[clouds][normals]") {
  const PointCloud c = test::sample_shape({test::Shape::sphere}, 2000, 0, 6);
  CHECK(tally(detail::exterior_votes(c.points, c.normals, 0)).none == 2000);
  CHECK(tally(detail::exterior_votes(c.points, c.normals, std::nan(""))).none == 2000);
  CHECK(detail::exterior_votes(Eigen::MatrixX3d(0, 3), Eigen::MatrixX3d(0, 3), 0.1).empty());
  // a voxel of 1e-6 would make 8e18 voxels: the voxel is doubled until the grid holds at most
  // 2^26, so the call returns, and its votes are still never wrong
  const Tally t = tally(detail::exterior_votes(c.points, c.normals, 1e-6));
  CHECK(t.wrong == 0);
}

TEST_CASE("open pockets: inside parts the winding number reads as outside become outside",
          "[clouds][normals]") {
  // Two unit spheres of 6000 points, centres 3 apart: two inside parts the fill cannot reach.
  const PointCloud a = test::sample_shape({test::Shape::sphere}, 6000, 0, 3);
  Eigen::MatrixX3d P(12000, 3);
  P << a.points, a.points.rowwise() + Eigen::RowVector3d(3, 0, 0);
  const double voxel = voxel_for(4 * M_PI, 6000);
  const detail::ExteriorGrid grid = detail::exterior_grid(P, voxel);
  auto count = [](const detail::ExteriorGrid& g, std::uint8_t s) {
    return long(std::count(g.state.begin(), g.state.end(), s));
  };
  const long inside = count(grid, detail::ExteriorGrid::kInside);
  REQUIRE(inside > 1000);
  auto opened = [&](auto winding) {
    detail::ExteriorGrid g = grid;
    const long n = detail::open_pockets(g, winding, 1);
    CHECK(count(g, detail::ExteriorGrid::kInside) == inside - n);
    CHECK(count(g, detail::ExteriorGrid::kShell) == count(grid, detail::ExteriorGrid::kShell));
    return std::pair{n, g};
  };
  // the exact winding number (1 in either ball): nothing opened
  auto exact = [](const Eigen::Vector3d& x) {
    return x.norm() < 1 || (x - Eigen::Vector3d(3, 0, 0)).norm() < 1 ? 1.0 : 0.0;
  };
  CHECK(opened(exact).first == 0);
  // the second ball read as outside: exactly its inside opened, the first one's kept
  auto first_only = [](const Eigen::Vector3d& x) { return x.norm() < 1 ? 1.0 : 0.0; };
  const auto [n, g] = opened(first_only);
  long second = 0; // inside voxels of the second ball (centre x beyond 1.5)
  for (long v = 0; v < long(grid.state.size()); ++v)
    second += grid.state[size_t(v)] == detail::ExteriorGrid::kInside &&
              grid.lo(0) + grid.h * (double(v % grid.n[0]) + 0.5) > 1.5;
  CHECK(n == second);
  CHECK(detail::exterior_side(g, Eigen::Vector3d(0, 0, 0)) == -1);
  CHECK(detail::exterior_side(g, Eigen::Vector3d(3, 0, 0)) == 1);
  // a median of 1/2 or more keeps a part: a winding number of 0.6 inside keeps both
  CHECK(opened([](const Eigen::Vector3d&) { return 0.6; }).first == 0);
  CHECK(opened([](const Eigen::Vector3d&) { return 0.4; }).first == inside);
}
