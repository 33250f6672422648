#pragma once
// Sections -> the implicit equation of the lofted body (`interlin implicit SECTIONS.csv`): the
// loft (reconstruction/loft), its ruled end caps, the exact signed distance at the nodes of a
// uniform grid (the far field) and, for every grid cell within the blend band, the starts from
// which Newton's foot search finds the nearest foot for every point of the cell (the near
// field). The model is interflatation/models/section_body.h.

#include "interlin/interflatation/models/section_body.h"
#include "interlin/reconstruction/loft/loft.h"

#include <functional>
#include <string>
#include <vector>

namespace interlin {

struct SectionBodyOptions {
  LoftOptions loft;
  int resolution = 96;     // grid cells along the longest side of the model box
  double margin = 0.05;    // model box = body bounding box + margin x its diagonal
  double band_inner = 1.5; // blend band, in grid cells: signed distance exact within inner,
  double band_outer = 3.0; // far field beyond outer
  int checks_per_cell = 2; // random points per band cell that check (and complete) its starts
  int threads = 0;         // 0: all cores
  std::function<void(const std::string&)> progress;
};

// What the build measured.
//   bbox_diagonal        of the body
//   band_cells, seeds    cells with near-field starts, starts stored
//   surface_points       points of the boundary checked for omega = 0 (input section points,
//                        dense samples of side and caps); max_surface_omega the largest |omega|
//   boundary_misses      of 1e5 random boundary points (after as many completed the starts),
//                        how many the stored starts did not find (each then got its own)
//   check_points         interior points of band cells checked against the exact distance;
//                        check_failures how many needed a start of their own (each got one),
//                        validation_failures the same on a second, independent set of points
//   max_far_error        max |far field - exact| over the check points with |d| >= band_inner
struct SectionBodyReport {
  LoftResult loft;
  double bbox_diagonal = 0;
  long band_cells = 0, seeds = 0;
  long surface_points = 0, boundary_misses = 0;
  double max_surface_omega = 0;
  long check_points = 0, check_failures = 0, validation_points = 0, validation_failures = 0;
  double max_far_error = 0;
};

struct SectionBodyBuild {
  SectionBodyModel model;
  SectionBodyReport report;
};

// Inputs: >= 2 closed sections (as for loft_sections), options (std::invalid_argument for a
// resolution below 8 or above 1024, a margin <= 0, a band with 0 < inner < outer violated).
// Throws std::runtime_error when a boundary point would have |omega| > 1e-12 x diagonal (the
// exactness guarantee; never observed), whatever loft_sections throws.
SectionBodyBuild build_section_body(const std::vector<Section>& sections,
                                    const SectionBodyOptions& options = {});

// The same from a loft already made (options.loft unused): e.g. fit_sliced_scan's loft of the
// fitted section curves themselves, which loft_sections of their samples would only approximate
// between the samples. Needs loft.sections[k].points and loft.point_u[k] (the cap edges).
SectionBodyBuild build_section_body(const LoftResult& loft, const SectionBodyOptions& options);

} // namespace interlin
