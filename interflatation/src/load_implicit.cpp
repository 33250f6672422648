#include "interlin/interflatation/load_implicit.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/models/ifl_registry.h"

#include <cctype>
#include <filesystem>
#include <stdexcept>

namespace interlin {

namespace {

std::string extension(const std::string& path) {
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

} // namespace

bool is_implicit_model(const std::string& path) {
  const std::string e = extension(path);
  return e == ".rf" || e == ".ifl";
}

ImplicitFunction load_implicit(const std::string& path, const ModelOptions& options) {
  const std::string e = extension(path);
  if (e == ".rf")
    return load_model(path, options);
  if (e == ".ifl") {
    if (options.output != ModelOptions{}.output || !options.parameters.empty())
      throw std::invalid_argument(
          "an output variable or parameter values apply to .rf models only");
    return load_ifl(path);
  }
  throw InputError(path + ": unknown model type '" + e + "' (expected .rf or .ifl)");
}

} // namespace interlin
