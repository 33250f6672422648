#pragma once
// Knot vectors: validation, span search and the standard constructions used by interpolation.

#include <Eigen/Core>

namespace interlin {

// Throws std::invalid_argument unless `knots` is finite, non-decreasing and long enough for
// `num_ctrl` control points of degree `degree` (#knots = num_ctrl + degree + 1), with a
// non-empty parameter domain [knots(degree), knots(num_ctrl)].
void check_knots(const Eigen::VectorXd& knots, int degree, Eigen::Index num_ctrl);

// Index k of the knot span [knots(k), knots(k+1)) that contains u, with degree <= k < num_ctrl
// and the last non-empty span used for u at (or beyond) the right end of the domain; u left of
// the domain maps to the first span. Binary search, O(log #knots).
Eigen::Index find_span(const Eigen::VectorXd& knots, int degree, Eigen::Index num_ctrl, double u);

// Clamped knot vector for open interpolation at parameters u (#u points, increasing, u(0)=0,
// u(end)=1) by knot averaging (de Boor; Piegl & Tiller eq. 9.8). Output: #u + degree + 1 knots.
Eigen::VectorXd averaged_knots(const Eigen::VectorXd& u, int degree);

// Knot vector of a periodic (closed) spline for interpolation at the N sites u(0..N-1) with
// closing parameter u(N) (= u(0) + period). Odd degree: knots at the sites; even degree: knots
// at the midpoints between sites, which keeps the collocation matrix regular (the knots-at-sites
// choice is singular for even degree and an even number of intervals, digest 001 §2.2 ⚠).
// Output: N + 2*degree + 1 knots, periodic extension on both sides; the parameter domain is
// [knots(degree), knots(N+degree)], one period long and containing every site.
Eigen::VectorXd periodic_knots(const Eigen::VectorXd& u, int degree);

// Clamped knots for least squares with n control points of degree p at the N data parameters u
// (increasing, n <= N): interior knots where the data's parameters fall in equal shares, so every
// knot span holds data (Piegl & Tiller eq. 9.68-9.69); n == N: averaged_knots.
// Output: n + p + 1 knots.
Eigen::VectorXd approximation_knots(const Eigen::VectorXd& u, int degree, Eigen::Index n);

// Periodic knots for n distinct control points from the N + 1 parameters u (closing one last):
// one period [u(0), u(N)] split where the cumulative weight of the parameter intervals (w(i) on
// [u(i), u(i+1)], linear inside; empty w: all 1, the parameter quantiles) reaches j / n of its
// total, extended periodically on both sides; n == N with empty w: periodic_knots.
// Output: n + 2 p + 1 knots.
Eigen::VectorXd periodic_quantile_knots(const Eigen::VectorXd& u, int degree, Eigen::Index n,
                                        const Eigen::VectorXd& w);

} // namespace interlin
