#pragma once
// The one error type for bad user input: its message is the single line the CLI prints,
// "FILE:LINE: what is wrong" (or "FILE: ..." when no line applies).

#include "interlin/interflatation/input_error.h" // the InputError type itself

#include <string>

namespace interlin {

// "path:line: message" (line > 0) or "path: message".
[[noreturn]] void throw_input_error(const std::string& path, long line, const std::string& message);

} // namespace interlin
