#pragma once
// What the interlin subcommands share: the run that maps errors to exit statuses and removes
// the outputs of a failed run, progress lines, output checks, number formatting and the model
// options of the commands that read an R-function model.

#include "cli_args.h"

#include "interlin/interflatation/limits.h"
#include "interlin/interflatation/rfunctions/model.h"
#include "interlin/reconstruction/io/mesh_io.h"

#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace interlin::cli {

// The body of a subcommand: its parsed arguments and the list of files it has written so far.
using CommandBody = std::function<void(const ParsedArgs& args, std::vector<std::string>& written)>;

// Runs one subcommand: parses argv[2..] with `options` plus -q/--quiet and -h/--help, prints
// `help` on -h, else calls `body`; returns the exit status. A UsageError prints the one line
// "interlin NAME: what" and gives 2; any other exception removes the files listed in `written`
// (a command's outputs come as a set), prints "interlin: what" (a LimitError adds the option
// that raises the limit) and gives 1; otherwise 0.
int run_command(const char* name, const char* help, int argc, const char* const* argv,
                std::vector<OptionSpec> options, const CommandBody& body);

// Progress lines "[   12.3 ms] what" on stderr, timed from construction; none when quiet.
struct Progress {
  bool quiet;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  void operator()(const std::string& what) const;
};

// The single input file of a command; UsageError "missing the WHAT (see --help)" or
// "expected one WHAT, got N".
std::string single_input(const ParsedArgs& args, const std::string& what);

// The extension of `path` in lower case (".stl"), empty when it has none.
std::string lower_extension(const std::string& path);

// The checks of a command's output files before any work: UsageError when an output is given
// twice or is one of the `inputs` (the same file under any spelling), std::runtime_error
// "cannot write PATH: why" when an output cannot be created (missing directory, a directory in
// its place, a parent that is a file, no permission or a read-only file system: a probe file is
// created and removed beside it).
void check_outputs(const std::vector<std::string>& inputs, const std::vector<std::string>& outputs);

// A value option that raises a limit (--max-NAME N, N >= 1), or `fallback` when absent.
long long limit_option(const ParsedArgs& args, const std::string& name, long long fallback);

// UsageError "--OPTION VALUE: asks for WHAT, more than the limit of LIMIT (raise it with
// --max-NAME N)": a limit the options alone exceed, reported before any work.
[[noreturn]] void options_exceed(const std::string& option_and_value, const std::string& what,
                                 long long limit, const std::string& limit_name);

// "  wrote        A, B" on stdout; nothing when `paths` is empty.
void print_written(const std::vector<std::string>& paths);

// The warning of `interlin mesh`, surface or volume, when the body reaches the box at `nodes` > 0
// outer grid nodes (ImplicitMeshInfo::clipped, VolumeMeshInfo::clipped); nothing when quiet.
void warn_body_reaches_box(long nodes, bool quiet);

// `x` with `precision` significant digits, as an ostream prints it.
std::string fmt(double x, int precision = 4);

// --mesh-precision double|single (default double): the coordinates of PLY and OBJ outputs.
MeshPrecision mesh_precision(const ParsedArgs& args);

// A warning on stderr (unless quiet) when the mesh file `path` stores its coordinates in single
// precision (.stl and .off always, .ply and .obj with MeshPrecision::float32) and rounding them
// to floats moves a vertex by more than 1e-5 of the bounding-box diagonal of V (#V by 3): a body
// far from the origin. Names the rounding and the double-precision formats.
void warn_single_precision(const std::string& path, const Eigen::MatrixXd& V,
                           MeshPrecision precision, bool quiet);

// How a --set value that is not a number is named in its error: the whole NAME=VALUE (eval) or
// the NAME alone (mesh).
enum class SettingLabel { setting, name };

// The model options of --var NAME, the repeatable --set NAME=VALUE and --max-model-size N.
// Throws UsageError for a setting without '=' or name, a value that is not a finite number, and
// a name given twice.
ModelOptions model_options(const ParsedArgs& args, SettingLabel label);

// The model options of `args` for the model file `path` (.rf or .ifl, read by load_implicit):
// --set/--var apply to .rf models only. UsageError for those on another kind and for an
// extension that is neither (checked before any work).
ModelOptions model_file_options(const ParsedArgs& args, const std::string& path,
                                SettingLabel label);

} // namespace interlin::cli
