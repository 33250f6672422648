#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>

namespace interlin {

void throw_input_error(const std::string& path, long line, const std::string& message) {
  if (line > 0)
    throw InputError(path + ":" + std::to_string(line) + ": " + message);
  throw InputError(path + ": " + message);
}

long line_at(std::string_view content, std::size_t byte) {
  byte = std::min(byte, content.size());
  return 1 + static_cast<long>(std::count(
                 content.begin(), content.begin() + static_cast<std::ptrdiff_t>(byte), '\n'));
}

void throw_json_number_error(std::string_view content, const std::string& path,
                             const std::string& what) {
  const auto b = what.find('\''), q = what.rfind('\'');
  long line = 0;
  if (b != std::string::npos && q > b + 1)
    if (const auto at = content.find(what.substr(b + 1, q - b - 1)); at != std::string::npos)
      line = line_at(content, at);
  const auto bracket = what.find("] ");
  throw_input_error(path, line,
                    "JSON " + (bracket == std::string::npos ? what : what.substr(bracket + 2)) +
                        " (not a finite double)");
}

} // namespace interlin
