#pragma once
// Blocks of .ifl files shared by several model kinds: B-spline surfaces, uniform node grids and
// R-function model sources. Each pair writes a block and reads it back exactly (InputError via
// IflBlock::fail for blocks that break the rules).

#include "interlin/interflatation/models/ifl_file.h"
#include "interlin/splines/bspline_surface.h"

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace interlin {

// block bspline_surface NAME: numbers degree_u, degree_v, closed_u (0/1); arrays knots_u,
// knots_v (f64), ctrl (f64, num_u*num_v x 3).
IflBlock surface_block(const std::string& name, const BSplineSurface& s);
BSplineSurface surface_from_block(const IflBlock& b);

// Values at the nodes origin + h (i, j, k), i < n(0), j < n(1), k < n(2), x fastest.
struct NodeGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double h = 1;
  Eigen::Array3i n = Eigen::Array3i::Constant(2);
  std::vector<double> values;
};

// block node_grid NAME: array origin f64 3, number h, array n i64 3, array values f64
// n(2) x n(1) x n(0).
IflBlock grid_block(const std::string& name, const NodeGrid& g);
NodeGrid grid_from_block(const IflBlock& b);
// A model's far field: its block node_grid 'distance', which must hold the model's box (the
// tricubic is an interpolant over the grid's nodes; far beyond them it overflows).
NodeGrid distance_grid_from_block(const IflBlock& model, const Eigen::AlignedBox3d& box);

// array NAME f64 6: x0 y0 z0 x1 y1 z1 (non-empty box).
void set_box(IflBlock& b, const std::string& name, const Eigen::AlignedBox3d& box);
Eigen::AlignedBox3d box_from_block(const IflBlock& b, const std::string& name);

// The box and blend band of a model (section_body, normalized_rf): array box (set_box), numbers
// band_inner, band_outer with 0 < inner < outer (valid_band).
struct IflBand {
  Eigen::AlignedBox3d box;
  double inner = 0, outer = 0;
};
bool valid_band(double inner, double outer);
void set_band(IflBlock& b, const IflBand& band);
IflBand band_from_block(const IflBlock& b);

} // namespace interlin
