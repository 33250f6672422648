#pragma once
// The one error type for bad user input: its message is the single line the CLI prints,
// "FILE:LINE: what is wrong", "FILE:LINE:COLUMN: ..." for model files, or "FILE: ..." when no
// line applies. Declared here, the lowest module that reads user files (R-function models);
// interlin/reconstruction/input_error.h includes it.

#include <stdexcept>

namespace interlin {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

} // namespace interlin
