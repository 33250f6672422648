#pragma once
// The implicit equation of a body lofted from sections (`interlin implicit SECTIONS.csv`):
//   omega = d_near + chi(|d_near|) ... blended with the far field,
// exact (omega = 0) on the loft surface and its end caps, positive inside, equal to the signed
// distance in a band around the boundary:
//   near field  d_near: the signed distance to side and caps (body_patches.h), Newton's foot
//               search from the starts stored for the point's grid cell (only cells within the
//               band have starts);
//   far field   the tricubic interpolant (cubic_grid.h) of the exact signed distance at the
//               grid nodes;
//   blend       omega = f + chi(|d|) (d - f), chi = 1 for |d| <= band_inner, 0 for
//               |d| >= band_outer, C2 quintic step in between, so the zero set is the boundary's
//               exactly and omega is the signed distance inside the inner band.
// Outside the grid box omega = f(q) - |p - q| with q the nearest point of the box.
// The model is data only (surface, grid values, starts); builders live in
// reconstruction/implicit (build_section_body), the evaluator here needs splines and grids.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/models/body_patches.h"
#include "interlin/interflatation/models/ifl_codecs.h"
#include "interlin/interflatation/models/ifl_file.h"

#include <array>
#include <cstdint>
#include <vector>

namespace interlin {

// The stored model.
//   side, edge_u  the boundary (body_patches)
//   grid          signed distance (positive inside) at the nodes: the far field; its cells
//                 (i + (n0-1) (j + (n1-1) k)) carry the near-field starts
//   band_cells    the cells with starts (the band), increasing; other cells are far field only
//   band_start    #band_cells + 1 offsets into seeds: the starts of band cell b are
//                 seeds[band_start[b] .. band_start[b+1])
//   seeds         the starts
//   band_inner, band_outer   0 < inner < outer: the blend band (signed-distance units)
//   box           the region of the body (ImplicitFunction::box), inside the grid
struct SectionBodyModel {
  BSplineSurface side;
  std::array<Eigen::Vector2d, 2> edge_u;
  NodeGrid grid;
  std::vector<std::int64_t> band_cells, band_start;
  std::vector<PatchSeed> seeds;
  double band_inner = 0, band_outer = 0;
  Eigen::AlignedBox3d box;
};

// The .ifl block (kind section_body) and back; docs/formats.md lists the fields.
IflBlock to_ifl(const SectionBodyModel& m);
SectionBodyModel section_body_from_ifl(const IflBlock& b);

// The function: value and exact gradient of omega (the near field's gradient is the unit vector
// from the foot, the far field's the interpolant's). Thread-safe; copies share the model.
// Throws std::invalid_argument for inconsistent data (sizes, band, orientation of the caps).
ImplicitFunction section_body_function(const SectionBodyModel& m);

// Smooth blend weight: 1 for r <= inner, 0 for r >= outer, 1 - (6x^5 - 15x^4 + 10x^3) between
// (x = (r - inner) / (outer - inner)); derivative in `slope`.
double band_weight(double r, double inner, double outer, double* slope = nullptr);

} // namespace interlin
