#include "interlin/interflatation/read_input_file.h"

#include "interlin/interflatation/input_error.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

namespace interlin {

std::string read_input_file(const std::string& path) {
  // std::ifstream opens a directory and reads it as an empty file: name the problem instead.
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw InputError(path + ": cannot open: " + std::strerror(EISDIR));
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
