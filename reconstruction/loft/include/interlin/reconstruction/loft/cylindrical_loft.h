#pragma once
// The seed's cylindrical surface model for star-shaped sections (seed 001 §2.5, formula (4)):
//   x = SX(t, z) cos t,   y = SY(t, z) sin t,   z = z,
// with t the polar angle around an axis parallel to z. At the sections' own points t is their
// polar angle, so SX = x / cos t and SY = y / sin t both equal the polar radius: the model is one
// scalar function R(t, z) = SX = SY (fitting x / cos t and y / sin t separately would divide by
// zero at t = pi/2 and t = 0). R is a Gordon interlineation (digest 001 §5.1 [SUPPLEMENT]) of
// the traces R(t, z_k) (periodic splines through each section's radii, nonuniform angles,
// any point count) and, when given, R(t_l, z) on meridians t = t_l (vertical sections through
// the axis, seed 001 §2.5 (iii)). For blades, which are not star-shaped, use the direct form
// (loft_sections, guided_loft). Not a polynomial B-spline: exported as a mesh, not as IGES.

#include "interlin/interlineation/gordon_surface.h"
#include "interlin/interlineation/shape_diagnostics.h"
#include "interlin/reconstruction/io/guide_csv.h"
#include "interlin/reconstruction/io/section_csv.h"

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace interlin {

struct CylindricalLoftOptions {
  int degree = 3;      // around: periodic splines in t (radius traces); 3 = C2
  int span_degree = 3; // along z (blending, meridian traces), reduced to #sections - 1
  // Axis through (center_x, center_y); NaN: the mean of the sections' vertex centroids.
  double center_x = std::numeric_limits<double>::quiet_NaN();
  double center_y = std::numeric_limits<double>::quiet_NaN();
  double tolerance = 1e-6; // x bbox diagonal: planarity of sections, meridians in their plane
};

// The model.
//   center      the axis (x, y)
//   z           K increasing section heights
//   radius      R(t, z): x-lines t = t_l (meridians, may be none), y-lines z = z_k; periodic in t
//               with period 2 pi
//   angles      per section, the polar angle of each point (increasing from the first point)
//   deviation   per section, |S(t_i, z_k) - P_i| for each point; max_deviation, bbox_diagonal
//   reversed    per section: its points ran clockwise and were taken in reverse order
struct CylindricalLoft {
  Eigen::Vector2d center;
  Eigen::VectorXd z;
  GordonSurface radius;
  std::vector<Eigen::VectorXd> angles, deviation;
  std::vector<bool> reversed;
  double max_deviation = 0, bbox_diagonal = 0;
};

// Inputs: K >= 2 sections, each in a plane z = const (within tolerance), star-shaped around the
// axis (the polar angle turns once around, monotonically), at distinct heights; meridians
// (optional): polylines in a half-plane t = const through the axis, spanning the sections'
// heights, each with a point on every section plane (its radius there is replaced by the
// section's, so the traces meet; GuideSet::path names the file in errors).
// Throws std::invalid_argument naming the section and line for sections that break these rules
// (and for bad options), InputError "FILE:LINE: ..." for meridians, std::runtime_error if a
// section point were not reproduced in (x, y) to 1e-9 x diagonal (z is z_k, the mean height of
// the section's points, so deviation includes the section's own non-planarity).
CylindricalLoft cylindrical_loft(const std::vector<Section>& sections, const GuideSet& meridians,
                                 const CylindricalLoftOptions& options = {});

// d^(dt+dz) S / dt^dt dz^dz at (t, z), S = (R cos t, R sin t, z); dt, dz <= 2.
Eigen::Vector3d evaluate(const CylindricalLoft& m, double t, double z, int dt = 0, int dz = 0);

// Convexity of the model: around, the sign of the section curves' curvature
// (R^2 + 2 R_t^2 - R R_tt) / (R^2 + R_t^2)^(3/2) (+1 convex, polar curves); along z, the sign of
// -R_zz (+1 where the meridian bulges outward). Flat: |curvature| x bbox diagonal <= tolerance.
ShapeMap shape_map(const CylindricalLoft& m, const Eigen::VectorXd& t, const Eigen::VectorXd& z,
                   double flat_tolerance = 1e-6);

} // namespace interlin
