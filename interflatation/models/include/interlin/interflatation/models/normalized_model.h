#pragma once
// An R-function model (.rf) turned into a normalised implicit equation
// (`interlin implicit MODEL.rf -o MODEL.ifl`): the same zero set, closer to the signed distance.
//   near field  the distance from p to the tangent plane at the point q where the line through p
//               along grad F crosses F = 0 (Newton on F(p + t g), g = grad F(p) / |grad F(p)|):
//               d = -t (g . n(q)), n(q) = grad F(q) / |grad F(q)|; first-order exact, and 0
//               exactly where F = 0 (t = 0 there);
//   far field   the tricubic interpolant of the signed distance to F = 0 at the grid nodes;
//   blend       as for section bodies (section_body.h): omega = f + chi(|d|) (d - f), chi
//               decided by the near value, so the zero set is F's.
// Points where the crossing is not found within the band (no sign change along the line, or a
// grazing crossing) take d = F / |grad F| (the seed's normalisation to first order).

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/models/ifl_codecs.h"
#include "interlin/interflatation/models/ifl_file.h"
#include "interlin/interflatation/rfunctions/model.h"

#include <string>

namespace interlin {

// The stored model.
//   source     the .rf text
//   path       the absolute path it was read from: names it in messages, and relative
//              ifl("...") paths inside it are resolved against its directory
//   options    output variable and parameter values used
//   grid       signed distance to F = 0 at the nodes (positive where F > 0)
//   band_inner, band_outer   the blend band (0 < inner < outer)
//   box        the model's box
struct NormalizedModel {
  std::string source, path;
  ModelOptions options;
  NodeGrid grid;
  double band_inner = 0, band_outer = 0;
  Eigen::AlignedBox3d box;
};

// The .ifl block (kind normalized_rf) and back.
IflBlock to_ifl(const NormalizedModel& m);
NormalizedModel normalized_model_from_ifl(const IflBlock& b);

// The function (value and gradient; the near field's gradient is n(q), exact on F = 0).
// Throws InputError when the source does not compile (it is checked again at load).
ImplicitFunction normalized_model_function(const NormalizedModel& m);

} // namespace interlin
