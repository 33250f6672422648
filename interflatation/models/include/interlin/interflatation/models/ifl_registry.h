#pragma once
// Model kinds of .ifl files: each kind (the model block's KIND) has a loader that turns the block
// into an ImplicitFunction. The built-in kinds (section_body, normalized_rf) are registered on
// first use; another module adds its own with register_ifl_kind (e.g. point-cloud implicits),
// without touching the container or the other evaluators.

#include "interlin/interflatation/implicit_function.h"
#include "interlin/interflatation/models/ifl_file.h"

#include <functional>
#include <string>
#include <vector>

namespace interlin {

// Turns a model block into the function it describes. Throws InputError (block.fail) for blocks
// that break the kind's rules. `path` is the file the block came from (for kinds that refer to
// other files relative to it).
using IflLoader = std::function<ImplicitFunction(const IflBlock& model, const std::string& path)>;

// Registers `loader` for model blocks of kind `kind`. Thread-safe. Throws std::invalid_argument
// when the kind is registered already or its name is not a valid block kind.
void register_ifl_kind(const std::string& kind, IflLoader loader);

// The registered kinds, sorted (for messages and --help).
std::vector<std::string> ifl_kinds();

// The function of a model block: the loader of its kind. Throws InputError
// "FILE:LINE: unknown model kind 'K' (known: ...)".
ImplicitFunction load_ifl_model(const IflBlock& model, const std::string& path);

// read_ifl + load_ifl_model.
ImplicitFunction load_ifl(const std::string& path);

} // namespace interlin
