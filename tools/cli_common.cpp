#include "cli_common.h"

#include "interlin/interflatation/limits.h"
#include "interlin/interflatation/load_implicit.h"
#include "interlin/reconstruction/io/atomic_file.h"

#include <cctype>
#include <cerrno>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
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
    std::cerr << "interlin: " << e.what();
    if (const auto* limit = dynamic_cast<const LimitError*>(&e); limit && !limit->option.empty())
      std::cerr << " (raise it with --" << limit->option << " N)";
    std::cerr << "\n";
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

namespace {

// Throws "cannot write PATH: why" unless a file can be created at `path`.
void check_writable(const std::string& path) {
  const fs::path dir =
      fs::path(path).has_parent_path() ? fs::path(path).parent_path() : fs::path(".");
  const auto fail = [&](const std::string& why) {
    throw std::runtime_error("cannot write " + path + ": " + why);
  };
  if (fs::exists(dir) && !fs::is_directory(dir))
    fail(dir.string() + " is not a directory");
  if (!fs::is_directory(dir))
    fail("directory " + dir.string() + " does not exist");
  if (fs::is_directory(path))
    fail("it is a directory");
  // Permissions do not tell (root, read-only mounts, /proc): create the writer's temporary file.
  const AtomicPath probe(path);
  std::FILE* f = std::fopen(probe.temp().c_str(), "wb");
  if (!f)
    fail(std::strerror(errno));
  std::fclose(f);
}

// Whether `a` and `b` name the same file: the same file when both exist (hard and symbolic links
// included), else the same path once made absolute and normal.
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec))
    return fs::equivalent(a, b, ec);
  const fs::path ca = fs::weakly_canonical(a, ec);
  if (ec)
    return a == b;
  const fs::path cb = fs::weakly_canonical(b, ec);
  return ec ? a == b : ca == cb;
}

} // namespace

void check_outputs(const std::vector<std::string>& inputs,
                   const std::vector<std::string>& outputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    for (size_t j = 0; j < i; ++j)
      if (same_file(outputs[j], outputs[i]))
        throw UsageError("output '" + outputs[i] + "' given twice");
    for (const std::string& in : inputs)
      if (same_file(in, outputs[i]))
        throw UsageError("output '" + outputs[i] + "' is the input file '" + in +
                         "' (it would be overwritten)");
  }
  for (const std::string& out : outputs)
    check_writable(out);
}

long long limit_option(const ParsedArgs& args, const std::string& name, long long fallback) {
  if (!args.has(name))
    return fallback;
  const std::string text = args.get(name);
  long long v = 0;
  const auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || p != text.data() + text.size() || v < 1)
    throw UsageError("--" + name + " expects a positive integer, got '" + text + "'");
  return v;
}

void options_exceed(const std::string& option_and_value, const std::string& what, long long limit,
                    const std::string& limit_name) {
  throw UsageError(option_and_value + ": asks for " + what + ", more than the limit of " +
                   std::to_string(limit) + " (raise it with --" + limit_name + " N)");
}

void warn_body_reaches_box(long nodes, bool quiet) {
  if (!quiet && nodes > 0)
    std::cerr << "warning: the body reaches the box at " << nodes
              << " grid nodes; the mesh is cut by the box there\n";
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

MeshPrecision mesh_precision(const ParsedArgs& args) {
  return parse_choice("mesh-precision", args.get("mesh-precision", "double"),
                      {"double", "single"}) == "double"
             ? MeshPrecision::float64
             : MeshPrecision::float32;
}

void warn_single_precision(const std::string& path, const Eigen::MatrixXd& V,
                           MeshPrecision precision, bool quiet) {
  const std::string ext = lower_extension(path);
  const bool single = ext == ".stl" || ext == ".off" || precision == MeshPrecision::float32;
  if (quiet || !single || V.rows() == 0)
    return;
  const double diagonal = (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
  const float far = float(V.cwiseAbs().maxCoeff());
  const double rounding = 0.5 * double(std::nextafter(far, FLT_MAX) - far); // half a float's ulp
  if (rounding > 1e-5 * diagonal)
    std::cerr << "warning: " << path << " stores single-precision coordinates: at "
              << fmt(double(far), 3) << " from the origin they round by up to " << fmt(rounding, 2)
              << " (" << fmt(rounding / diagonal, 2)
              << " of the mesh's size); .ply and .obj keep double precision\n";
}

ModelOptions model_options(const ParsedArgs& args, SettingLabel label) {
  ModelOptions mo;
  mo.max_size = limit_option(args, "max-model-size", limits::model_size);
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

ModelOptions model_file_options(const ParsedArgs& args, const std::string& path,
                                SettingLabel label) {
  const std::string ext = lower_extension(path);
  if (!is_implicit_model(path))
    throw UsageError("model '" + path + "': unknown kind '" + ext + "' (expected .rf or .ifl)");
  if (ext != ".rf" && (args.has("set") || args.has("var")))
    throw UsageError("--set and --var apply to R-function models (.rf) only");
  return model_options(args, label);
}

} // namespace interlin::cli
