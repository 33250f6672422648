#pragma once
// R-function model -> normalised implicit model (`interlin implicit MODEL.rf`): the signed
// distance to the model's zero set at the nodes of a uniform grid (from a fine mesh of F = 0:
// implicit_mesh with its vertices on F = 0, exact point-to-triangle distances, the sign of F),
// which becomes the far field of interflatation/models/normalized_model.h.

#include "interlin/interflatation/models/normalized_model.h"

#include <functional>
#include <string>

namespace interlin {

struct NormalizeOptions {
  int resolution = 96;     // far-field grid cells along the longest side of the model's box
  int mesh_resolution = 0; // cells of the mesh of F = 0; 0: 2 x resolution, at least 128
  double band_inner = 1.5; // blend band in grid cells (models/normalized_model.h)
  double band_outer = 3.0;
  int threads = 0; // 0: all cores
  std::function<void(const std::string&)> progress;
};

// What the build measured.
//   mesh_vertices, mesh_triangles   the mesh of F = 0 the distances come from
//   max_zero_omega     max |omega| at the mesh vertices (points of F = 0 to 1e-10 of a cell)
//   max_zero_first_order  max |F / |grad F|| at the same points (what omega reproduces there)
struct NormalizeReport {
  long mesh_vertices = 0, mesh_triangles = 0;
  double max_zero_omega = 0, max_zero_first_order = 0;
};

struct NormalizeBuild {
  NormalizedModel model;
  NormalizeReport report;
};

// Inputs: a .rf file and its options; InputError for model errors (as load_model),
// std::invalid_argument for bad options, std::runtime_error when the model has no surface in
// its box.
NormalizeBuild normalize_model(const std::string& rf_path, const ModelOptions& model_options,
                               const NormalizeOptions& options = {});

} // namespace interlin
