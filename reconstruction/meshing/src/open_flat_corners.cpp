// Flat hexahedral corners opened by a compass search on their interior nodes (open_flat_corners.h).
#include "open_flat_corners.h"

#include "corner_jacobian.h"
#include "interlin/reconstruction/meshing/volume_smoothing.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace interlin::detail {

namespace {

double element_min(const Eigen::MatrixXi& C, const Eigen::MatrixXi& T, const Eigen::MatrixXd& V,
                   long e) {
  Eigen::Vector3d p[8];
  for (int j = 0; j < 8; ++j)
    p[j] = V.row(C(e, j));
  const CornerJacobian r = corner_scaled_jacobian(p, T);
  return r.inverted || !(centre_jacobian(p) > 0) ? -1 : r.min_scaled; // folded: at a corner or
                                                                      // at the centre
}

double nodes_min(const Eigen::MatrixXi& C, const Eigen::MatrixXi& T, const Eigen::MatrixXd& V,
                 const std::vector<long>& elements) {
  double m = std::numeric_limits<double>::infinity();
  for (long e : elements)
    m = std::min(m, element_min(C, T, V, e));
  return m;
}

std::vector<long> flat_elements(const Eigen::MatrixXi& C, const Eigen::MatrixXi& T,
                                const Eigen::MatrixXd& V, double flat) {
  std::vector<long> out;
  for (long e = 0; e < C.rows(); ++e)
    if (element_min(C, T, V, e) < flat)
      out.push_back(e);
  return out;
}

// The compass search of node v over its elements.
void open_node(const Eigen::MatrixXi& C, const Eigen::MatrixXi& T, const std::vector<long>& at,
               long v, Eigen::MatrixXd& V) {
  double edge = 0;
  int edges = 0;
  for (long e : at)
    for (int j = 0; j < 8; ++j)
      if (C(e, j) == v)
        for (int k = 0; k < 3; ++k, ++edges)
          edge += (V.row(C(e, T(j, k))) - V.row(v)).norm();
  edge /= std::max(edges, 1);
  double best = nodes_min(C, T, V, at);
  for (double step = 0.25 * edge; step > 1e-3 * edge;) {
    const Eigen::RowVector3d x = V.row(v);
    Eigen::RowVector3d to = x;
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {1.0, -1.0}) {
        V.row(v) = x;
        V(v, axis) += sign * step;
        const double m = nodes_min(C, T, V, at);
        if (m > best)
          best = m, to = V.row(v);
      }
    V.row(v) = to;
    if (to == x)
      step *= 0.5;
  }
}

} // namespace

long open_flat_corners(const Eigen::MatrixXi& C, const std::vector<char>& fixed, double flat,
                       Eigen::MatrixXd& V) {
  if (C.cols() != 8)
    return 0;
  const Eigen::MatrixXi T = corner_table(8);
  std::vector<long> flat_ones = flat_elements(C, T, V, flat);
  for (int pass = 0; pass < 3 && !flat_ones.empty(); ++pass) {
    std::vector<long> nodes;
    for (long e : flat_ones)
      for (int j = 0; j < 8; ++j)
        if (!fixed[size_t(C(e, j))])
          nodes.push_back(C(e, j));
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    std::vector<std::vector<long>> at(nodes.size());
    for (long e = 0; e < C.rows(); ++e)
      for (int j = 0; j < 8; ++j) {
        const auto it = std::lower_bound(nodes.begin(), nodes.end(), long(C(e, j)));
        if (it != nodes.end() && *it == C(e, j))
          at[size_t(it - nodes.begin())].push_back(e);
      }
    for (size_t k = 0; k < nodes.size(); ++k)
      open_node(C, T, at[k], nodes[k], V);
    flat_ones = flat_elements(C, T, V, flat);
  }
  return long(flat_ones.size());
}

} // namespace interlin::detail
