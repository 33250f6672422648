#pragma once
// What every fuzz target shares: the input as a string and the rule that bad input may only
// raise the error type the CLI reports as one line (InputError for files, UsageError for the
// command line). Any other exception is a defect (a message without a file and line, or an
// exhausted resource): it is printed and the process aborts, so libFuzzer keeps the input.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

namespace interlin::fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Runs `body`; returns true when it completed, false when it threw `Expected`.
template <class Expected, class Body>
bool only_throws(Body&& body) {
  try {
    body();
    return true;
  } catch (const Expected&) {
    return false;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: unexpected exception: %s\n", e.what());
    std::abort();
  }
}

} // namespace interlin::fuzz
