#include "interlin/reconstruction/meshing/regular_grid.h"

#include "interlin/reconstruction/meshing/parallel_for.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace interlin {

namespace {

RegularGrid grid_with_step(const Eigen::AlignedBox3d& box, double h, const char* who) {
  if (box.isEmpty() || !box.min().allFinite() || !box.max().allFinite())
    throw std::invalid_argument(std::string(who) + ": the box is empty or not finite");
  if (!(h > 0) || !std::isfinite(h))
    throw std::invalid_argument(std::string(who) + ": the cell size must be positive and finite");
  RegularGrid g;
  g.spacing.setConstant(h);
  double total = 1;
  for (int a = 0; a < 3; ++a) {
    const double side = box.max()(a) - box.min()(a);
    // 1e-9: a side that is a whole number of cells up to round-off gets exactly that many.
    const double cells = std::max(1.0, std::ceil(side / h - 1e-9));
    total *= cells + 1;
    if (!(total <= 2147483648.0))
      throw std::invalid_argument(std::string(who) + ": more than 2^31 grid nodes");
    g.nodes(a) = int(cells) + 1;
    g.origin(a) = box.min()(a) - 0.5 * (cells * h - side);
  }
  return g;
}

} // namespace

RegularGrid grid_with_resolution(const Eigen::AlignedBox3d& box, int cells) {
  if (cells < 1)
    throw std::invalid_argument("grid_with_resolution: cells must be >= 1, got " +
                                std::to_string(cells));
  if (box.isEmpty() || !box.min().allFinite() || !box.max().allFinite())
    throw std::invalid_argument("grid_with_resolution: the box is empty or not finite");
  const double longest = box.sizes().maxCoeff();
  if (!(longest > 0))
    throw std::invalid_argument("grid_with_resolution: the box has zero size");
  return grid_with_step(box, longest / cells, "grid_with_resolution");
}

RegularGrid grid_with_cell(const Eigen::AlignedBox3d& box, double h) {
  return grid_with_step(box, h, "grid_with_cell");
}

long nodes_reaching_box(const RegularGrid& g, const Eigen::VectorXd& S) {
  if (S.size() != g.size())
    throw std::invalid_argument("nodes_reaching_box: S must hold one value per grid node");
  long count = 0;
  for (long k = 0; k < g.nodes(2); ++k)
    for (long j = 0; j < g.nodes(1); ++j)
      for (long i = 0; i < g.nodes(0); ++i)
        if (g.outer(i, j, k) && reaches_box(S(g.index(i, j, k))))
          ++count;
  return count;
}

void sample_grid(const ImplicitFunction& f, const RegularGrid& g, Eigen::VectorXd& S, int threads) {
  if (!f.value)
    throw std::invalid_argument("sample_grid: the implicit function has no value");
  if ((g.nodes < 2).any() || !(g.spacing.array() > 0).all())
    throw std::invalid_argument("sample_grid: invalid grid");
  const long slice = long(g.nodes(0)) * g.nodes(1);
  S.resize(g.size());
  detail::parallel_for(g.nodes(2), detail::resolve_threads(threads), [&](long k, int) {
    Points3 P(slice, 3);
    for (long j = 0, r = 0; j < g.nodes(1); ++j)
      for (long i = 0; i < g.nodes(0); ++i, ++r)
        P.row(r) = g.point(i, j, k).transpose();
    f.value(P, S.segment(k * slice, slice));
  });
}

} // namespace interlin
