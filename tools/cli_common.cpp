#include "cli_common.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace interlin::cli {

namespace fs = std::filesystem;

int run_command(const char* name, const char* help, int argc, const char* const* argv,
                std::vector<OptionSpec> options, const CommandBody& body) {
  std::vector<std::string> written;
  try {
    options.push_back({"quiet", 'q', false, false});
    options.push_back({"help", 'h', false, false});
    const ParsedArgs a = parse_args(argc, argv, 2, options);
    if (a.has("help"))
      std::cout << help;
    else
      body(a, written);
    return 0;
  } catch (const UsageError& e) {
    std::cerr << "interlin " << name << ": " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    for (const std::string& o : written)
      std::remove(o.c_str());
    std::cerr << "interlin: " << e.what() << "\n";
    return 1;
  }
}

void Progress::operator()(const std::string& what) const {
  if (!quiet)
    std::fprintf(
        stderr, "[%7.1f ms] %s\n",
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(),
        what.c_str());
}

std::string single_input(const ParsedArgs& args, const std::string& what) {
  if (args.positional.size() != 1)
    throw UsageError(args.positional.empty() ? "missing the " + what + " (see --help)"
                                             : "expected one " + what + ", got " +
                                                   std::to_string(args.positional.size()));
  return args.positional[0];
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_output_dir(const std::string& path) {
  const fs::path dir =
      fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  if (!fs::is_directory(dir))
    throw std::runtime_error("cannot write " + path + ": directory " + dir.string() +
                             " does not exist");
}

void print_written(const std::vector<std::string>& paths) {
  if (paths.empty())
    return;
  std::cout << "  wrote        ";
  for (size_t i = 0; i < paths.size(); ++i)
    std::cout << (i ? ", " : "") << paths[i];
  std::cout << "\n";
}

std::string fmt(double x, int precision) {
  std::ostringstream s;
  s.precision(precision);
  s << x;
  return s.str();
}

ModelOptions model_options(const ParsedArgs& args, SettingLabel label) {
  ModelOptions mo;
  if (args.has("var"))
    mo.output = args.get("var");
  for (const std::string& s : args.all("set")) {
    const auto eq = s.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError("--set " + s + ": expected NAME=VALUE");
    const std::string name = s.substr(0, eq);
    const double v =
        parse_double("set " + (label == SettingLabel::setting ? s : name), s.substr(eq + 1));
    if (mo.parameters.count(name))
      throw UsageError("--set " + name + " given twice");
    mo.parameters[name] = v;
  }
  return mo;
}

} // namespace interlin::cli
