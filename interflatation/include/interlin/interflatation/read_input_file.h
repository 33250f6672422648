#pragma once
// The whole text of a user's input file, with the one-line InputError of every reader.

#include <string>

namespace interlin {

// Reads the file `path` whole (bytes as they are).
// Throws InputError "PATH: cannot open: why" or "PATH: cannot read: why".
// See also: InputError (input_error.h).
std::string read_input_file(const std::string& path);

} // namespace interlin
