#pragma once
// The free traces of Theorems 4 and 5 chosen by a criterion (seed 001 §2.7-2.8: rho(Ou, w) -> min
// with w the distance to dG or an R-function; digest §7 item 6 leaves the parameterisation and
// the optimiser open). Parameterisation: the traces are the restrictions of
//   u = w (1 + sum_k c_k phi_k),
// phi_k the piecewise-linear (2-D: bilinear, 3-D: trilinear) hat functions of the grid nodes, so
// every trace is w modulated by a piecewise-linear factor with knots at the line crossings, and
// u = 0 on dG whenever w is (the traces stay compatible and Ou continuous). c = 0 is the naive
// choice u = w (Ou interpolates w on every grid line or plane). O is linear in u, so
// Ou = O w + sum_k c_k O(w phi_k): the criterion over sample points of G is a linear fit.
//   least_squares   min sum_i (Ou - w)^2 at the samples (normal equations by QR)
//   min_max         min max_i |Ou - w| at the samples: Lawson's iteratively reweighted least
//                   squares from the least-squares start, keeping the best iterate (so never
//                   worse than least squares, and never worse than c = 0 on the samples)

#include "interlin/interflatation/operators/region_interlineation.h"
#include "interlin/interflatation/operators/solid_interflatation.h"

#include <Eigen/Core>
#include <functional>

namespace interlin {

enum class TraceCriterion { least_squares, min_max };

// The linear core: coefficients c minimising |A c - r| at the rows (2-norm or max-norm).
// A #samples by #c, r #samples. Throws std::invalid_argument for mismatched sizes.
Eigen::VectorXd fit_trace_coefficients(const Eigen::MatrixXd& A, const Eigen::VectorXd& r,
                                       TraceCriterion criterion);

// Inputs: an operator built with its traces from w (O.u = w), the target w, sample points of G
// (#S by 2 / #S by 3). Output: O with O.u = w (1 + sum c_k phi_k) for the criterion's c.
// `coefficients`, when not null, receives c (one per grid node, x fastest).
// See also region_interlineation, solid_interflatation.
RegionInterlineation fit_free_traces(const RegionInterlineation& O,
                                     const std::function<double(const Eigen::Vector2d&)>& w,
                                     const Eigen::MatrixX2d& samples, TraceCriterion criterion,
                                     Eigen::VectorXd* coefficients = nullptr);
SolidInterflatation fit_free_traces(const SolidInterflatation& O,
                                    const std::function<double(const Eigen::Vector3d&)>& w,
                                    const Eigen::MatrixX3d& samples, TraceCriterion criterion,
                                    Eigen::VectorXd* coefficients = nullptr);

} // namespace interlin
