#pragma once
// R-function model files (.rf): a small text language for implicit bodies F(x,y,z) >= 0 built
// from normalised primitives, R-operations and transforms (seeds 000, 002, 003). The language is
// described in docs/formats.md, section "R-function model files"; data/models/ holds examples.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/limits.h"

#include <map>
#include <string>

namespace interlin {

struct ModelOptions {
  // The variable whose final value is the body function (RFPreview's convention: res).
  std::string output = "res";
  // Values that replace the defaults of the model's `param NAME = value;` declarations. Naming a
  // parameter the model does not declare is an InputError.
  std::map<std::string, double> parameters;
  // Work allowed while reading the model: expression nodes built, user-function calls expanded
  // and Bezier sampling (limits::model_size). Past it reading stops with a LimitError naming
  // the statement.
  long long max_size = limits::model_size;
};

// Reads and compiles the model file at `path`.
// Output: an ImplicitFunction whose `value` and `gradient` evaluate the model's output variable
// in batches (gradient: forward-mode dual numbers, exact derivatives of the compiled
// expression), and whose `box` is the model's declared box (never empty: a model must declare
// one). Values are always finite: where the expression is undefined (0/0, sqrt of a negative)
// F is -DBL_MAX (outside), infinities are clamped to +-DBL_MAX, non-finite gradient components
// are 0. The function owns its compiled program; calls are safe concurrently on disjoint
// outputs, and copies share the program.
// Throws InputError("FILE:LINE:COLUMN: message") for syntax and semantic errors (LINE and
// COLUMN count from 1, COLUMN in bytes), InputError("FILE: message") for file-level problems
// (unreadable file, no box, no output variable, unknown parameter override), LimitError
// ("FILE:LINE:COLUMN: ...") when the model needs more than options.max_size.
ImplicitFunction load_model(const std::string& path, const ModelOptions& options = {});

// The same from text in memory; `name` stands for FILE in error messages.
ImplicitFunction parse_model(const std::string& text, const std::string& name = "<model>",
                             const ModelOptions& options = {});

} // namespace interlin
