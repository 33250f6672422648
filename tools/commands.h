#pragma once
// Subcommands of the interlin executable. Each returns the process exit status:
// 0 success, 1 bad input or failed output (one error line on stderr), 2 wrong usage.

namespace interlin::cli {

int run_loft(int argc, const char* const* argv);
extern const char* const kLoftHelp;

int run_eval(int argc, const char* const* argv);
extern const char* const kEvalHelp;

int run_mesh(int argc, const char* const* argv);
extern const char* const kMeshHelp;

int run_profile(int argc, const char* const* argv);
extern const char* const kProfileHelp;

int run_implicit(int argc, const char* const* argv);
extern const char* const kImplicitHelp;

} // namespace interlin::cli
