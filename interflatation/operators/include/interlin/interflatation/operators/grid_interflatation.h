#pragma once
// Interflatation on a grid of planes x = x_i, y = y_j, z = z_k (seed 001 §2.8, digest §5 items
// 1 and 4 [SUPPLEMENT]): the Boolean sum of the three blending projectors
//   O = P1 + P2 + P3 - P1P2 - P1P3 - P2P3 + P1P2P3,
//   Pk u(p) = sum_i alpha^k_i(p_k) u(p with p_k = x^k_i),
// the 3-D counterpart of the Gordon operator of interlineation/gordon_surface.h, with its
// cardinal blending functions alpha^k (interlineation/cardinal_splines.h): degree 1 gives the
// per-box trilinear Boolean sum (C0), degree 3 the spline-blended C2 operator. O equals u on
// every grid plane (exact on all planes), and f - Of = (I - P1)(I - P2)(I - P3) f.
// With two planes per axis and degree 1 it is the box interflatation (T14).

#include "interlin/interlineation/cardinal_splines.h"

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

namespace interlin {

// The trace of u on one grid plane, as a function of the other two coordinates in axis order
// ((y, z) on x = x_i, (x, z) on y = y_j, (x, y) on z = z_k).
using PlaneTrace = std::function<double(double a, double b)>;

// Traces on the planes of a grid.
//   nodes   per axis, the increasing plane positions (>= 2 each)
//   traces  per axis, one trace per plane (traces[k].size() == nodes[k].size())
// Traces must be compatible: two traces agree on the line where their planes cross
// (plane_trace_mismatch measures it).
struct PlaneTraces {
  std::array<Eigen::VectorXd, 3> nodes;
  std::array<std::vector<PlaneTrace>, 3> traces;
};

// The traces of one function u on the planes of `nodes` (compatible by construction).
PlaneTraces plane_traces(const std::function<double(const Eigen::Vector3d&)>& u,
                         const std::array<Eigen::VectorXd, 3>& nodes);

// Largest |difference| of two crossing traces over `samples` points of every crossing line
// (inside the grid box): 0 for compatible traces.
double plane_trace_mismatch(const PlaneTraces& t, int samples = 17);

// The operator: traces and the cardinal blending functions per axis.
struct GridInterflatation {
  PlaneTraces traces;
  std::array<CardinalSplines, 3> blend;
};

// Inputs: traces (>= 2 planes per axis, increasing nodes, one trace per plane), degree 1 (C0)
// or 3 (C2). Throws std::invalid_argument otherwise.
GridInterflatation grid_interflatation(const PlaneTraces& traces, int degree);

// Ou at p (p inside the grid box; outside the blending functions extrapolate).
double evaluate(const GridInterflatation& O, const Eigen::Vector3d& p);

// The box interflatation of u on [lo, hi] (trilinear Boolean sum, exact on the six faces):
// grid_interflatation of the traces of u on the faces, degree 1, at p.
double box_interflatation(const std::function<double(const Eigen::Vector3d&)>& u,
                          const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                          const Eigen::Vector3d& p);

} // namespace interlin
