#pragma once
// The one error type for bad user input: its message is the single line the CLI prints,
// "FILE:LINE: what is wrong" (or "FILE: ..." when no line applies).

#include "interlin/interflatation/input_error.h" // the InputError type itself

#include <cstddef>
#include <string>
#include <string_view>

namespace interlin {

// "path:line: message" (line > 0) or "path: message".
[[noreturn]] void throw_input_error(const std::string& path, long line, const std::string& message);

// 1-based line of byte offset `byte` in `content`.
long line_at(std::string_view content, std::size_t byte);

// A JSON reader's error for a number beyond the double range: nlohmann's `what` ("...
// number overflow parsing 'TOKEN'") reports no position, so the line is that of TOKEN in content.
[[noreturn]] void throw_json_number_error(std::string_view content, const std::string& path,
                                          const std::string& what);

} // namespace interlin
