#pragma once
// A small command-line parser for the interlin subcommands: long options (--name VALUE or
// --name=VALUE), short aliases (-o FILE), flags, repeatable options and positionals.

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace interlin::cli {

// Wrong usage: the message is printed as one line and the program exits with status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name; // long name without dashes
  char alias = 0;   // short alias, 0 for none
  bool takes_value = false;
  bool repeatable = false;
};

struct ParsedArgs {
  std::vector<std::string> positional;
  std::map<std::string, std::vector<std::string>> values; // flags map to {""}
  bool has(const std::string& name) const { return values.count(name) > 0; }
  // The (last) value of an option, or `fallback` when absent.
  std::string get(const std::string& name, const std::string& fallback = "") const;
  // Every value of a repeatable option in command-line order, none when absent.
  std::vector<std::string> all(const std::string& name) const;
};

// Parses argv[first..argc). Throws UsageError for unknown options, missing values and repeated
// non-repeatable options.
ParsedArgs parse_args(int argc, const char* const* argv, int first,
                      const std::vector<OptionSpec>& spec);

// Value parsers; each throws UsageError naming the option and the expected form.
int parse_int(const std::string& option, const std::string& text, int min, int max);
std::pair<int, int> parse_int_pair(const std::string& option, const std::string& text, int min,
                                   int max);
std::vector<int> parse_int_list(const std::string& option, const std::string& text, int min);
// One finite number, the whole text ("--OPTION: 'TEXT' is not a finite number").
double parse_double(const std::string& option, const std::string& text);
// Comma-separated finite numbers.
std::vector<double> parse_double_list(const std::string& option, const std::string& text);
// One of `choices`; the error message lists them.
std::string parse_choice(const std::string& option, const std::string& text,
                         const std::vector<std::string>& choices);

} // namespace interlin::cli
