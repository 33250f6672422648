#pragma once
// Running the interlin executable from a test: the command line as a user types it, with exit
// status, stdout and stderr captured, plus small file helpers for the CLI tests.

#include "support/test_support.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace interlin::test {

// What one run of the executable left: exit status (-1 when it did not exit normally), stdout
// and stderr.
struct Run {
  int status;
  std::string out, err;
};

// The whole content of a file ("" when it cannot be read).
inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Writes `text` to `path` (replacing it).
inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

// Runs `interlin ARGS` through the shell. stdout and stderr are captured in a scratch directory
// of their own, so that a test's directory holds only what the command wrote.
inline Run run(const std::string& args) {
  const TempDir io("cli-io");
  const std::string out = io / "stdout.txt", err = io / "stderr.txt";
  const int raw =
      std::system((std::string(INTERLIN_CLI) + " " + args + " >" + out + " 2>" + err).c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, slurp(out), slurp(err)};
}

// The number of entries in a test's directory.
inline std::size_t files_in(const TempDir& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir.path()),
                                                std::filesystem::directory_iterator()));
}

// A failed run: exit status `status` and one line on stderr containing `what`.
inline void expect_error(const Run& r, int status, const std::string& what) {
  INFO("stderr: " << r.err);
  CHECK(r.status == status);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_THAT(r.err, Catch::Contains(what));
}

} // namespace interlin::test
