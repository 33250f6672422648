#include "interlin/interflatation/read_input_file.h"

#include "interlin/interflatation/input_error.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace interlin {

std::string read_input_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path + ": cannot open: " + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad())
    throw InputError(path + ": cannot read: " + std::strerror(errno));
  return s.str();
}

} // namespace interlin
