#pragma once
// seed 004 Ch. 1 (digest 004 §2.5, §3.2–3.6): planar natural curves through given points and
// tangents ("shooting"). The unknown polynomial coefficients of k(s) and the arc lengths are
// found so that the curve hits the targets; coefficients fixed by the end tangent angles are
// eliminated in closed form first (the book's elimination formulas, corrected per digest §10).
//
// Solvers: Levenberg–Marquardt on the residual vector (computed point - target), default, or
// the book's Hooke–Jeeves on the Germeier sum Q = sum_i lambda_i |P_i' - P_i| (1.17).
// Angles are in radians and are taken literally: the curve turns by exactly phi_end - phi_start
// (add 2 pi for a loop). Every fit throws std::runtime_error when the miss stays above the
// tolerance from every starting point, and std::invalid_argument for bad input.

#include "interlin/splines/hooke_jeeves.h"
#include "interlin/splines/levenberg_marquardt.h"
#include "interlin/splines/natural_curve.h"

#include <vector>

namespace interlin {

// A point with a tangent angle (radians, from +x, counter-clockwise).
struct CurvePose {
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  double angle = 0;
};

enum class ShootingSolver { levenberg_marquardt, hooke_jeeves };

// What Hooke–Jeeves minimises: the book's Germeier sum Q = sum lambda_i |P_i' - P_i| (1.17), or
// sum lambda_i |P_i' - P_i|^2. The sum of distances is not smooth at the solution and direct
// search stalls on it for 4-unknown problems (digest §2.5 [V]; test "Book mode"); the squares
// are smooth.
enum class HookeJeevesObjective { germeier, sum_of_squares };

struct ShootingOptions {
  ShootingSolver solver = ShootingSolver::levenberg_marquardt;
  HookeJeevesObjective hj_objective = HookeJeevesObjective::germeier;
  QuadratureOptions quadrature;
  double tolerance = 1e-10; // accepted max miss |P_i' - P_i| over the targets
  LevenbergMarquardtOptions lm;
  HookeJeevesOptions hj;
};

// The book's setting (digest §2.4–2.5, acceptance ≤ 1e-4): Hooke–Jeeves on (1.17), trapezoid
// rule with 2000 intervals, miss tolerance 1e-4.
ShootingOptions book_mode();

// Result of a fit: consecutive pieces (each with its own local arc length from 0), piece i+1
// starting at the computed end of piece i with the same tangent angle; miss = max distance
// between computed and target points.
struct NaturalFit {
  std::vector<PlanarNaturalCurve> pieces;
  double miss = 0;
};

// seed 004 (1.7)–(1.11), (4.1)–(4.2), §4.2: G1 Hermite arc from p0 to p1 with
//   k(s) = sum_{j<m} fixed(j) s^j + b s^m + a s^{m+1},  m = #fixed,
// the lower coefficients prescribed (k and k' at the start for G2/G3 joints), a eliminated by
// the end angle:
//   a = (m+2)/S^{m+2} (Delta phi - sum_{j<m} fixed(j) S^{j+1}/(j+1) - b S^{m+1}/(m+1)).
// m = 0 is the clothoid arc of §1.5 (a = (2/S^2)(Delta phi - b S)); m = 1 the quadratic segment
// of §4.1, m = 2 the cubic segment of §4.2. Unknowns (b, S), start S = chord.
NaturalFit fit_hermite_curvature(const CurvePose& p0, const CurvePose& p1,
                                 const Eigen::VectorXd& fixed = Eigen::VectorXd(),
                                 const ShootingOptions& options = {});

// seed 004 §1.5: the linear-curvature (clothoid) G1 Hermite arc, fit_hermite_curvature with m = 0.
NaturalFit fit_linear_curvature(const CurvePose& p0, const CurvePose& p1,
                                const ShootingOptions& options = {});

// seed 004 §1.6: composite curve of linear-curvature links through #poses >= 2 points with
// tangents, link i from poses[i] to poses[i+1] (G1 at the nodes; curvature jumps).
NaturalFit fit_linear_curvature_chain(const std::vector<CurvePose>& poses,
                                      const ShootingOptions& options = {});

// seed 004 §1.6 (Fig. 1.37, after Ahlberg–Nilson–Walsh): tangent angles at the points from the
// clamped cubic spline y(x) with y'(x_0) = tan phi_first, y'(x_{n-1}) = tan phi_last
// [SUPPLEMENT: the standard tridiagonal system]. P #P by 2 with strictly increasing x, #P >= 2;
// the end angles in (-pi/2, pi/2). Output: #P angles atan y'(x_i).
Eigen::VectorXd spline_tangent_angles(const Eigen::MatrixXd& P, double phi_first, double phi_last);

// seed 004 §1.7 (errata digest §10.1): k = a s^2 + b s + c through P0 (angle phi0), the interior
// point P1 (no tangent) and P2 (angle phi2), S = S1 + S2,
//   a = (3/S^2)((phi2 - phi0)/S - b S/2 - c);  unknowns b, c, S1, S2; Hooke–Jeeves weights 1/2.
NaturalFit fit_quadratic_curvature_3pt(const CurvePose& p0, const Eigen::Vector2d& p1,
                                       const CurvePose& p2, const ShootingOptions& options = {});

// seed 004 §1.8 (1.18)–(1.25) (errata §10.2): two quadratic-curvature pieces P1 -> P2 -> P3 with a
// G3 joint at P2: c2 = k1(S1) (1.19), b2 = k1'(S1) (1.20), a1, a2 from the angles (1.24), (1.25).
// Unknowns b1, c1, S1, S2; piece 2 starts at the computed end of piece 1.
NaturalFit fit_quadratic_curvature_g3(const CurvePose& p1, const CurvePose& p2, const CurvePose& p3,
                                      const ShootingOptions& options = {});

// seed 004 §1.9 (errata §10.3): k = a s^3 + b s^2 + c s + d through P0, P1 (s = S1) and P2
// (s = S2 > S1), all with tangents; a, b from cubic_curvature_ab; unknowns c, d, S1, S2;
// Hooke–Jeeves weights (0.8, 0.2) as in the book.
NaturalFit fit_cubic_curvature_3pt(const CurvePose& p0, const CurvePose& p1, const CurvePose& p2,
                                   const ShootingOptions& options = {});

// seed 004 §1.9, the elimination of a and b (b's c-term with the factor 1/2 restored, digest
// §10.3): with Phi_i = 4 (phi_i - phi_0) / S_i^4,
//   a = (Phi2 S2 - Phi1 S1)/(S2 - S1) + 2c/(S1 S2) + 4d (S1 + S2)/(S1^2 S2^2),
//   b = 3 S1 S2 (Phi2 - Phi1) / (4 (S1 - S2)) - 3c (S1 + S2)/(2 S1 S2)
//       - 3d (S1^2 + S1 S2 + S2^2)/(S1^2 S2^2).
// Output (a, b). Requires 0 < S1 < S2.
Eigen::Vector2d cubic_curvature_ab(double dphi1, double dphi2, double S1, double S2, double c,
                                   double d);

} // namespace interlin
