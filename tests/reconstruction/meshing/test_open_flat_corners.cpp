// Flat hexahedral corners opened by moving interior nodes (open_flat_corners, private to the
// meshing module): a 2 x 2 x 2 block of unit cubes whose centre node is pushed towards an edge.
#include "corner_jacobian.h"
#include "open_flat_corners.h"

#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

using namespace interlin;

namespace {

// 27 nodes (i + 3 j + 9 k at (i, j, k)), 8 hexahedra in VTK order.
void block(Eigen::MatrixXd& V, Eigen::MatrixXi& C) {
  V.resize(27, 3);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i)
        V.row(i + 3 * j + 9 * k) << i, j, k;
  C.resize(8, 8);
  int e = 0;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i, ++e) {
        const int n = i + 3 * j + 9 * k;
        C.row(e) << n, n + 1, n + 4, n + 3, n + 9, n + 10, n + 13, n + 12;
      }
}

// The smallest corner scaled Jacobian, -1 when an element folds at a corner or its centre.
double smallest(const Eigen::MatrixXd& V, const Eigen::MatrixXi& C) {
  const Eigen::MatrixXi T = corner_table(8);
  double m = 1;
  for (long e = 0; e < C.rows(); ++e) {
    Eigen::Vector3d p[8];
    for (int j = 0; j < 8; ++j)
      p[j] = V.row(C(e, j));
    const detail::CornerJacobian r = detail::corner_scaled_jacobian(p, T);
    m = std::min(m, r.inverted || !(detail::centre_jacobian(p) > 0) ? -1 : r.min_scaled);
  }
  return m;
}

} // namespace

TEST_CASE("open_flat_corners: a centre node pushed half a cell along a face diagonal moves back",
          "[volume][hex]") {
  Eigen::MatrixXd V;
  Eigen::MatrixXi C;
  block(V, C);
  V.row(13) << 1.495, 1.495, 1; // at (1.5, 1.5, 1) the cubes above and below it have flat corners
  const double before = smallest(V, C);
  REQUIRE(before > 0);
  REQUIRE(before < 0.02); // 0.016
  std::vector<char> fixed(27, 1);
  fixed[13] = 0;
  const Eigen::MatrixXd V0 = V;
  CHECK(detail::open_flat_corners(C, fixed, 0.02, V) == 0);
  // Every move raises the minimum (1 with the node back at the centre).
  INFO("moved to " << V.row(13) << ", smallest " << smallest(V, C));
  CHECK(smallest(V, C) > 0.5);
  V.row(13) = V0.row(13);
  CHECK(V == V0); // only the free node moved
}
