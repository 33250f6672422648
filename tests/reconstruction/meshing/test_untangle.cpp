// The hexahedral untangling's rounds (untangle.h, private to the meshing module): a node of an
// element that stays folded must not run off (functional (15) grows with an element's size).
#include "corner_jacobian.h"
#include "untangle.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

using namespace interlin;

TEST_CASE("untangle_hexahedra: the free nodes of an element folded at a fixed corner stay near",
          "[volume][hex]") {
  // The unit cube with node 4 pushed below node 0: corner 0 (nodes 0, 1, 3, 4, all fixed) is
  // inverted whatever the free nodes 2, 5, 6, 7 do.
  Eigen::MatrixXd V(8, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, -1, 1, 0, 1, 1, 1, 1, 0, 1, 1;
  Eigen::MatrixXi C(1, 8);
  C << 0, 1, 2, 3, 4, 5, 6, 7;
  const std::vector<char> fixed = {1, 1, 0, 1, 1, 0, 0, 0};
  const Eigen::MatrixXd V0 = V;
  const double edge = detail::mean_edge(V0, C);
  CHECK(detail::untangle_hexahedra(C, fixed, 1, V) == 1);
  double moved = 0;
  for (long v = 0; v < V.rows(); ++v)
    moved = std::max(moved, (V.row(v) - V0.row(v)).norm());
  INFO("farthest move " << moved << " (mean edge " << edge << ")");
  CHECK(moved <= 16 * edge); // before the guard: 163, 135 mean edges
  for (long v : {0, 1, 3, 4})
    CHECK(V.row(v) == V0.row(v));
}
