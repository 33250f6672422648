#pragma once
// The expression of a model file before compilation: for combining models with the C++ library
// (interlin/interflatation/expression.h) or differentiating them. load_model() is
// compile(load_model_expression()).

#include "interlin/interflatation/rfunctions/expression.h"
#include "interlin/interflatation/rfunctions/model.h"

#include <Eigen/Geometry>
#include <string>

namespace interlin {

struct ModelExpression {
  rf::Expr F;              // the output variable's expression
  Eigen::AlignedBox3d box; // the declared box
};

// As load_model / parse_model (same errors), without compiling. The passes over an expression
// recurse along its longest chain (up to limits::expression_depth): the caller's thread needs
// a large stack for deep models, destroying the result included (load_model reads on a thread
// of its own).
ModelExpression load_model_expression(const std::string& path, const ModelOptions& options = {});
ModelExpression parse_model_expression(const std::string& text, const std::string& name = "<model>",
                                       const ModelOptions& options = {});

} // namespace interlin
