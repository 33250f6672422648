#pragma once
// Shape diagnostics of interlineation surfaces (seed 001 §2.5 property 2 and Theorem 3; digest
// 001 §6.1 item 12): regions of convexity and concavity along both parameter directions.

#include "interlin/interlineation/gordon_surface.h"
#include "interlin/splines/bspline_surface.h"

#include <vector>

namespace interlin {

// Signs on a sample grid: +1 convex, -1 concave, 0 flat (within the tolerance).
//   u, v               the sample parameters
//   along_u, along_v   #u by #v; entry (i, j) at (u(i), v(j))
struct ShapeMap {
  Eigen::VectorXd u, v;
  Eigen::MatrixXi along_u, along_v;
};

// Parametric surface: signs of the normal curvatures of the parameter lines,
//   kappa_u = S_uu . n / |S_u|^2,  kappa_v = S_vv . n / |S_v|^2,  n = S_u x S_v / |S_u x S_v|,
// convex (+1) where the line bends away from n (kappa < 0). For closed_u surfaces n is flipped,
// if needed, to point outward (away from the centroid of each u-loop), so that +1 means convex as
// seen from outside. flat: |kappa| * D <= flat_tolerance, D = diagonal of the samples' bounding
// box. Throws std::invalid_argument at degenerate points (S_u x S_v = 0).
ShapeMap shape_map(const PiecewiseSurface& S, const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                   double flat_tolerance = 1e-6);

// Scalar operator (O.dim == 1): signs of (O f)_xx and (O f)_yy, flat when |value| <=
// flat_tolerance (seed 001 Theorem 3: convex traces give a convex patch in each direction).
ShapeMap shape_map(const GordonSurface& O, const Eigen::VectorXd& x, const Eigen::VectorXd& y,
                   double flat_tolerance = 0);

// Maximal runs of one sign along a sample line; a run ends half-way between the last sample of
// its sign and the first of the next.
struct SignRun {
  double begin = 0, end = 0;
  int sign = 0;
};
std::vector<SignRun> sign_runs(const Eigen::VectorXd& s, const Eigen::VectorXi& signs);

// Fractions of the samples that are convex / concave / flat, per direction.
struct ShapeSummary {
  double convex_u = 0, concave_u = 0, flat_u = 0, convex_v = 0, concave_v = 0, flat_v = 0;
};
ShapeSummary summarize(const ShapeMap& map);

} // namespace interlin
