// Fuzz target: the command-line parser (tools/cli_args): the input is split at NUL bytes into
// argv, parsed with an option table of every kind the subcommands use (values, flags,
// repeatable options, short aliases), and every value goes through every value parser.
#include "fuzz_support.h"

#include "cli_args.h"

#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace interlin::cli;
  std::vector<std::string> words{"interlin", "loft"};
  std::string word;
  for (std::size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      words.push_back(word);
      word.clear();
    } else {
      word += static_cast<char>(data[i]);
    }
  }
  words.push_back(word);
  std::vector<const char*> argv;
  for (const std::string& w : words)
    argv.push_back(w.c_str());
  const std::vector<OptionSpec> spec = {{"output", 'o', true, true},  {"samples", 0, true, false},
                                        {"cap", 0, false, false},     {"set", 0, true, true},
                                        {"quiet", 'q', false, false}, {"box", 0, true, false}};
  ParsedArgs args;
  if (!interlin::fuzz::only_throws<UsageError>(
          [&] { args = parse_args(static_cast<int>(argv.size()), argv.data(), 2, spec); }))
    return 0;
  std::vector<std::string> values = args.positional;
  for (const auto& [name, vs] : args.values)
    values.insert(values.end(), vs.begin(), vs.end());
  for (const std::string& v : values) {
    interlin::fuzz::only_throws<UsageError>([&] { parse_int("n", v, -5, 100000); });
    interlin::fuzz::only_throws<UsageError>([&] { parse_int_pair("samples", v, 3, 100000); });
    interlin::fuzz::only_throws<UsageError>([&] { parse_int_list("withhold", v, 0); });
    interlin::fuzz::only_throws<UsageError>([&] { parse_double("cell", v); });
    interlin::fuzz::only_throws<UsageError>([&] { parse_double_list("box", v); });
    interlin::fuzz::only_throws<UsageError>([&] { parse_choice("align", v, {"first", "le"}); });
  }
  return 0;
}
