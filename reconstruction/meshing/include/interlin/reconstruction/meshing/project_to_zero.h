#pragma once
// Moving points onto the surface F = 0 of an implicit body (seed 003 §5.1: "find the
// intersection of the node with the boundary": a step to bracket a sign change, then bisection).

#include "interlin/interflatation/implicit_function.h"
#include "interlin/reconstruction/meshing/marching_cubes.h"
#include "interlin/reconstruction/meshing/regular_grid.h"

#include <Eigen/Core>
#include <vector>

namespace interlin {

struct RootOptions {
  // Stop when the bracket is shorter than tolerance x its initial length (or F = 0 exactly).
  double tolerance = 1e-10;
  // Evaluations per point at most (the bracket then still holds the root).
  int max_evaluations = 100;
  int threads = 0; // 0: all cores
};

// The point where F changes from inside (F > 0) to not inside on each segment A_i B_i.
// Method: the seed's bisection sped up as regula falsi with the Illinois modification; every fourth
// step is a plain bisection unless the three before halved the bracket, so the bracket halves at
// least every four steps (never slower than a quarter of bisection's), and convergence is
// superlinear near a simple root; no trial lies within half the tolerance of an end (Dekker), so
// a converged estimate closes the bracket at once. Non-finite values (treated as outside, like
// NaN in marching_cubes) force bisection steps.
// Inputs:
//   f       implicit function (value only)
//   A, B    #P by 3 segment ends
//   FA, FB  #P values of F at A and B; exactly one of each pair must be inside (F > 0), else
//           std::invalid_argument
//   o       options
// Output:   t #P in [0, 1]: the root is A + t (B - A) to within the tolerance; among the points
//           evaluated, the one with the smallest |F| inside the final bracket.
Eigen::VectorXd roots_on_segments(const ImplicitFunction& f, const Points3& A, const Points3& B,
                                  const Eigen::VectorXd& FA, const Eigen::VectorXd& FB,
                                  const RootOptions& o = {});

// Moves marching-cubes vertices onto F = 0 along the grid edges they lie on (roots_on_segments
// between the edge's two nodes, whose sampled values E holds), keeping the edge parameter in
// [kEdgeClamp, 1 - kEdgeClamp].
// Inputs:  f, g (the grid E refers to), E #V edges, o
// In/out:  V #V by 3
void project_edge_vertices(const ImplicitFunction& f, const RegularGrid& g,
                           const std::vector<EdgeVertex>& E, Eigen::MatrixXd& V,
                           const RootOptions& o = {});

// Seed 003's findBorder: projects each point P_i onto F = 0 along the line through it with
// direction D_i (the outward normal, pointing from F > 0 to F < 0). From an inside point it steps
// outward, from an outside point inward: first one step h_i; if F keeps its sign, a scan in
// steps of scan_step x h_i up to reach x h_i (the seed code: steps of 0.01 h_i, reach 100); the
// first sign change is then narrowed by roots_on_segments. A point with F = 0 stays; a point whose
// scan finds no change stays and is reported. Inputs:
//   f  implicit function
//   D  #P by 3 directions (any length > 0; normalised here; a zero row leaves its point)
//   h  #P step lengths (> 0)
//   o  options (tolerance relative to the final bracket's initial length)
// In/out:   P #P by 3
// Output:   number of points that found no sign change (left where they were); with `moved`,
//           per point whether it is on the surface now (projected, or F = 0 already)
long project_along(const ImplicitFunction& f, Eigen::MatrixXd& P, const Eigen::MatrixXd& D,
                   const Eigen::VectorXd& h, const RootOptions& o = {},
                   std::vector<char>* moved = nullptr, double reach = 100, double scan_step = 0.01);

// Seed 003 code's projection of an arbitrary point (findBorder(p, h) with a gradient walk): steps
// of length h_i along the local direction of -grad F / |grad F| towards F = 0 (outward from an
// inside point, inward from an outside one), the direction re-evaluated at every step
// (f.gradient, else central differences with step h_i / 2 as in the seed code), until F changes
// sign; the last step is then narrowed by roots_on_segments. A point with F = 0 stays; a point
// that finds no change within max_steps steps, or meets a vanishing gradient, stays and is
// reported.
// Inputs:  f, h #P steps (> 0), max_steps (>= 1), o
// In/out:  P #P by 3
// Output:  number of points left where they were; with `moved`, per point whether it is on the
//          surface now
long project_by_gradient_walk(const ImplicitFunction& f, Eigen::MatrixXd& P,
                              const Eigen::VectorXd& h, int max_steps = 100,
                              const RootOptions& o = {}, std::vector<char>* moved = nullptr);

// Unit outward directions -grad F / |grad F| at the points P (#P by 3): from f.gradient when
// available, else by central differences with step h (seed 003 code: h/2 of the walk step).
// Rows where the gradient vanishes or is not finite are zero. Chunks of P on `threads` threads
// (0: all cores; the result does not depend on it).
Eigen::MatrixXd outward_directions(const ImplicitFunction& f, const Eigen::MatrixXd& P, double h,
                                   int threads = 0);

} // namespace interlin
