#pragma once
// seed 004 §4.1–4.2 (digest 004 §6.1–6.2): axial-turbine blade profile in a plane cascade from
// 13 geometric parameters. Leading and trailing edges are circle arcs; the suction side
// C2 -> C3 -> C1 and the pressure side K2 -> K3 -> K1 are natural curves: linear curvature from
// the trailing edge to C3 (throat) or K3 (opposite the maximum thickness), then quadratic
// curvature with a G2 joint (§4.1) or cubic curvature with a G3 joint (§4.2, the improved method).
//
// Frame [B]: x axial (trailing edge at x ~ 0, leading edge at x ~ B), y tangential (pitch);
// angles beta from the cascade front (the y axis), in degrees. Key points (digest §6.1):
//   O2 = (r2, r2 ctg(g2/2)),  O1 = (B - r1, [(B - r2) cos by + r1] / sin by)
//   C2 = (r2 [1 - cos(b2 - g2/2)], yO2 + r2 sin(b2 - g2/2)),  phi_C2 = (pi + g2)/2 - b2
//   K2 = (r2 [1 + cos(b2 + g2/2)], yO2 - r2 sin(b2 + g2/2)),  phi_K2 = (pi - g2)/2 - b2
//   C1 = O1 + r1 (cos(b1 - g1/2), sin(b1 - g1/2)),             phi_C1 = b1 - (pi + g1)/2
//   K1 = O1 - r1 (cos(b1 + g1/2), sin(b1 + g1/2)),             phi_K1 = b1 - (pi - g1)/2
//   C3 = O2 + (0, t) + (a + r2)(sin phi_C3, -cos phi_C3),      phi_C3 = phi_C2 - delta
// K3 is diametrically opposite the point A where the maximum-thickness circle (diameter c_m)
// touches the suction side, with phi_K3 = phi_A.
//
// Decisions where the book is silent (digest §13, [R]): relative pitch, relative maximum
// thickness and its relative position are fractions of the axial width B; the position is the
// axial distance of the maximum-thickness circle's centre from the leading-edge point x = B;
// a zero throat defaults to t sin(beta_2). The y_O1 formula is used as printed.

#include "interlin/splines/natural_fit.h"

#include <Eigen/Core>
#include <vector>

namespace interlin {

// The book's 13 parameters (lengths in any unit, angles in degrees).
struct CascadeParameters {
  double relative_pitch = 0;         //  1  t / B
  double axial_width = 0;            //  2  B
  double stagger_deg = 0;            //  3  beta_y
  double inlet_angle_deg = 0;        //  4  beta_1 (geometric)
  double outlet_angle_deg = 0;       //  5  beta_2 (geometric)
  double le_wedge_deg = 0;           //  6  gamma_1
  double te_wedge_deg = 0;           //  7  gamma_2
  double le_radius = 0;              //  8  r_1
  double te_radius = 0;              //  9  r_2
  double te_bend_deg = 0;            // 10  delta
  double max_thickness_position = 0; // 11  axial distance of the max-thickness centre from LE / B
  double max_thickness = 0;          // 12  c_m / B
  double throat = 0;                 // 13  a_2 (absolute); 0 = default t sin(beta_2)
};

// §4.1: quadratic curvature after C3 / K3 (G2 joint); §4.2: cubic (G3 joint).
enum class CascadeJoint { g2_quadratic, g3_cubic };

struct CascadeOptions {
  CascadeJoint joint = CascadeJoint::g3_cubic;
  int side_intervals = 60; // points along each side (cosine spacing in arc length)
  int edge_intervals = 16; // intervals along each edge arc, even (the TE middle is a point)
  ShootingOptions shooting;
};

struct CascadeProfile {
  double pitch = 0, throat = 0, max_thickness = 0; // t, a_2 and c_m, absolute
  Eigen::Vector2d O1, O2;                          // leading / trailing edge circle centres
  CurvePose C1, C2, C3, K1, K2, K3, A;
  std::vector<PlanarNaturalCurve> suction;  // C2 -> C3 (linear k), C3 -> C1
  std::vector<PlanarNaturalCurve> pressure; // K2 -> K3 (linear k), K3 -> K1
  // #P by 2 closed profile (first point not repeated), #P = 2 (side + edge intervals), numbered
  // from the middle of the trailing edge towards the suction side (the book's order).
  Eigen::MatrixXd points;
  double miss = 0; // largest end-point miss of the four fitted segments
};

// Builds the profile. Throws std::invalid_argument for parameters out of range (non-positive
// lengths or radii, angles outside their ranges, a throat not below the pitch, ...) and for
// inconsistent combinations (edge circles overlapping, key points out of order, sides crossing:
// the book's "non-constructive" profiles), std::runtime_error when a side cannot be fitted.
CascadeProfile cascade_profile(const CascadeParameters& p, const CascadeOptions& options = {});

// Tangent angle, curvature and derivative along one side for curvature plots (book Figs. 4.2,
// 4.7–4.9): #s samples at relative arc lengths sbar = s / S in [0, 1]; columns sbar, s, x, y,
// phi, k, k'.
Eigen::MatrixXd side_curvature_plot(const std::vector<PlanarNaturalCurve>& side, int samples,
                                    const QuadratureOptions& q = {});

} // namespace interlin
