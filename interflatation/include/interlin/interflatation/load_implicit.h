#pragma once
// One loader for every implicit model file, chosen by extension: `.rf` R-function models
// (rfunctions/model.h) and `.ifl` implicit model files (models/ifl_registry.h). The commands that
// read a model (interlin eval, mesh, ...) all go through it.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/rfunctions/model.h"

#include <string>

namespace interlin {

// Inputs:
//   path     a .rf or .ifl file (extension case-insensitive)
//   options  output variable and parameter values of a .rf model; must be the defaults for
//            other kinds (std::invalid_argument otherwise)
// Output: the model's function. Throws InputError for unreadable or invalid files and for other
// extensions ("PATH: unknown model type '.ext' (expected .rf or .ifl)").
ImplicitFunction load_implicit(const std::string& path, const ModelOptions& options = {});

// True when `path` has an extension load_implicit reads.
bool is_implicit_model(const std::string& path);

} // namespace interlin
