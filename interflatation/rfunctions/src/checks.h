#pragma once
// Internal: argument checks shared by the primitive and operation builders.

#include "interlin/interflatation/rfunctions/expression.h"

#include <sstream>
#include <stdexcept>
#include <string>

namespace interlin::rf::detail {

// A size given as a constant must be > 0 (an expression, e.g. a radius varying with z, is the
// caller's responsibility).
inline void require_positive(const Expr& e, const char* function, const char* what) {
  if (e.is_constant() && !(e.constant_value() > 0)) {
    std::ostringstream s;
    s << function << ": " << what << " must be > 0, got " << e.constant_value();
    throw std::invalid_argument(s.str());
  }
}

} // namespace interlin::rf::detail
