#include "interlin/reconstruction/io/input_error.h"

namespace interlin {

void throw_input_error(const std::string& path, long line, const std::string& message) {
  if (line > 0)
    throw InputError(path + ":" + std::to_string(line) + ": " + message);
  throw InputError(path + ": " + message);
}

} // namespace interlin
