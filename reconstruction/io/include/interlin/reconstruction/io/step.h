#pragma once
// STEP output (ISO 10303-21, application protocol AP214 "automotive_design") of a B-spline
// surface: one B_SPLINE_SURFACE_WITH_KNOTS face, or with caps a closed shell (one solid).

#include "interlin/reconstruction/io/iges.h"
#include "interlin/splines/bspline_surface.h"

#include <array>
#include <string>

namespace interlin {

// A cap face: a patch on [0, 1]^2 bounded by the lateral surface's end loop at v = v, cut at the
// parameters corner_u (corner_u[0] < corner_u[1], in [u0, u1)): its side t = 0 runs along the
// loop from corner 0 to corner 1, its side t = 1 from corner 0 to corner 1 the other way round
// (through the seam), and the sides s = 0 and s = 1 are the two corner points (degenerate). The
// ruled cap of reconstruction/loft (end_cap).
struct StepCap {
  BSplineSurface patch;
  std::array<double, 2> corner_u{};
  double v = 0;
};

struct StepOptions {
  LengthUnit unit = LengthUnit::mm; // written as the file's length unit (coordinates unscaled)
  std::string name = "interlin";    // product name (printable ASCII)
  std::string description;          // FILE_DESCRIPTION text
  // Geometric tolerance written as the context's uncertainty, relative to the bounding-box
  // diagonal (CAD readers use it to join edges).
  double relative_uncertainty = 1e-9;
};

// Writes `s` as an AP214 STEP file. Polynomial B-splines (all weights 1) are written as
// B_SPLINE_SURFACE_WITH_KNOTS / B_SPLINE_CURVE_WITH_KNOTS (knots with multiplicities, every value
// the shortest decimal that reads back to the same double), so a reader evaluates exactly our
// surface.
// Without caps: one ADVANCED_FACE bounded by the surface's four parameter lines (for closed_u
// surfaces the seam line u = u0 twice and the two end loops), in an OPEN_SHELL of a
// SHELL_BASED_SURFACE_MODEL (MANIFOLD_SURFACE_SHAPE_REPRESENTATION).
// With caps (closed_u surfaces): a CLOSED_SHELL of the lateral face and the two cap faces sharing
// their edges (the end loops, split at u0 and the caps' corners: the lateral face and the caps
// use the same EDGE_CURVEs, in opposite directions), oriented outward (the lateral face by the
// sign of (S_u x S_v) . (S - loop centroid) summed around its middle loop, each cap consistently
// with it), in a MANIFOLD_SOLID_BREP (ADVANCED_BREP_SHAPE_REPRESENTATION).
// Units: the length unit (SI millimetre, centimetre or metre; the inch as a conversion-based
// unit of 25.4 mm), plane angle radian, solid angle steradian. The header's time stamp is the
// current UTC time, or SOURCE_DATE_EPOCH when set (reproducible files).
// Inputs:
//   path  output file, written atomically
//   s     check_surface-valid surface (std::invalid_argument otherwise)
//   caps  nullptr, or two caps {at v0, at v1} of a closed_u surface (std::invalid_argument for
//         an open surface or corners outside the domain)
// Throws std::runtime_error("cannot write PATH: ...") when writing fails.
void write_step(const std::string& path, const BSplineSurface& s,
                const std::array<StepCap, 2>* caps = nullptr, const StepOptions& opt = {});

} // namespace interlin
