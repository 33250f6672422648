#pragma once
// The spline-blended interflatation of node data on a uniform grid of planes, in its fast form:
// the tricubic tensor-product spline through the node values (C2). Its traces on every grid
// plane are the bicubic interpolants of the plane's values, and the Boolean sum
// P1 + P2 + P3 - P1P2 - P1P3 - P2P3 + P1P2P3 of traces that lie in the tensor space is the
// tensor interpolant itself (each (I - Pk) annihilates it), so the general operator of
// grid_interflatation.h reduces to 64 coefficients per point. Used as the far field of the
// implicit bodies (models/), fitted to signed distances at the nodes.

#include <Eigen/Core>
#include <vector>

namespace interlin {

// Uniform cubic B-spline coefficients over nodes origin + h (i, j, k), 0 <= i < n(0), ...:
// (n(0)+2) x (n(1)+2) x (n(2)+2) coefficients, x fastest; natural end conditions (second
// derivative 0 across the end planes).
struct CubicGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double h = 1;
  Eigen::Array3i n = Eigen::Array3i::Constant(2);
  std::vector<double> coeffs;
};

// Inputs: node values, n(0)*n(1)*n(2) of them, x fastest (index i + n0 (j + n1 k)); every
// n(axis) >= 2; h > 0. Throws std::invalid_argument otherwise.
// Output: the interpolant: evaluate(G, node) = value at every node (to round-off).
CubicGrid cubic_grid(const std::vector<double>& values, const Eigen::Vector3d& origin, double h,
                     const Eigen::Array3i& n);

// The interpolant at p, with its gradient when `gradient` is not null. Points outside the node
// box take the polynomial of the nearest cell (extrapolation).
double evaluate(const CubicGrid& G, const Eigen::Vector3d& p, Eigen::Vector3d* gradient = nullptr);

// The box of the nodes: origin to origin + h (n - 1).
Eigen::Vector3d grid_max(const CubicGrid& G);

} // namespace interlin
