#include "cli_args.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace interlin::cli {

std::string ParsedArgs::get(const std::string& name, const std::string& fallback) const {
  const auto it = values.find(name);
  return it == values.end() ? fallback : it->second.back();
}

std::vector<std::string> ParsedArgs::all(const std::string& name) const {
  const auto it = values.find(name);
  return it == values.end() ? std::vector<std::string>{} : it->second;
}

ParsedArgs parse_args(int argc, const char* const* argv, int first,
                      const std::vector<OptionSpec>& spec) {
  ParsedArgs out;
  bool only_positional = false;
  for (int i = first; i < argc; ++i) {
    const std::string arg = argv[i];
    if (only_positional || arg.size() < 2 || arg[0] != '-') {
      out.positional.push_back(arg);
      continue;
    }
    if (arg == "--") {
      only_positional = true;
      continue;
    }
    std::string name, value;
    bool inline_value = false;
    const OptionSpec* opt = nullptr;
    if (arg[1] == '-') {
      name = arg.substr(2);
      if (const auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        inline_value = true;
      }
      for (const OptionSpec& s : spec)
        if (s.name == name)
          opt = &s;
    } else if (arg.size() == 2) {
      for (const OptionSpec& s : spec)
        if (s.alias == arg[1])
          opt = &s;
    }
    if (!opt)
      throw UsageError("unknown option '" + arg + "' (see --help)");
    if (opt->takes_value && !inline_value) {
      if (i + 1 >= argc)
        throw UsageError("option --" + opt->name + " needs a value");
      value = argv[++i];
    } else if (!opt->takes_value && inline_value) {
      throw UsageError("option --" + opt->name + " takes no value");
    }
    auto& slot = out.values[opt->name];
    if (!slot.empty() && !opt->repeatable)
      throw UsageError("option --" + opt->name + " given twice");
    slot.push_back(value);
  }
  return out;
}

namespace {

bool to_int(const std::string& t, int& v) {
  const char* end = t.data() + t.size();
  const auto [p, ec] = std::from_chars(t.data(), end, v);
  return ec == std::errc() && p == end && !t.empty();
}

} // namespace

int parse_int(const std::string& option, const std::string& text, int min, int max) {
  int v = 0;
  if (!to_int(text, v) || v < min || v > max)
    throw UsageError("--" + option + " expects an integer in [" + std::to_string(min) + ", " +
                     std::to_string(max) + "], got '" + text + "'");
  return v;
}

std::pair<int, int> parse_int_pair(const std::string& option, const std::string& text, int min,
                                   int max) {
  const auto comma = text.find(',');
  int a = 0, b = 0;
  if (comma == std::string::npos || !to_int(text.substr(0, comma), a) ||
      !to_int(text.substr(comma + 1), b) || a < min || b < min || a > max || b > max)
    throw UsageError("--" + option + " expects two integers A,B in [" + std::to_string(min) + ", " +
                     std::to_string(max) + "], got '" + text + "'");
  return {a, b};
}

std::vector<int> parse_int_list(const std::string& option, const std::string& text, int min) {
  std::vector<int> out;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    int v = 0;
    if (!to_int(text.substr(start, comma - start), v) || v < min)
      throw UsageError("--" + option + " expects a comma-separated list of integers >= " +
                       std::to_string(min) + ", got '" + text + "'");
    out.push_back(v);
    if (comma == std::string::npos)
      return out;
    start = comma + 1;
  }
}

double parse_double(const std::string& option, const std::string& text) {
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || r.ec != std::errc() || r.ptr != text.data() + text.size() ||
      !std::isfinite(v))
    throw UsageError("--" + option + ": '" + text + "' is not a finite number");
  return v;
}

std::vector<double> parse_double_list(const std::string& option, const std::string& text) {
  std::vector<double> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ','))
    out.push_back(parse_double(option, item));
  if (!text.empty() && text.back() == ',')
    throw UsageError("--" + option + ": trailing comma in '" + text + "'");
  return out;
}

std::string parse_choice(const std::string& option, const std::string& text,
                         const std::vector<std::string>& choices) {
  std::string list;
  for (const std::string& c : choices) {
    if (c == text)
      return c;
    list += (list.empty() ? "" : "|") + c;
  }
  throw UsageError("--" + option + " expects one of " + list + ", got '" + text + "'");
}

} // namespace interlin::cli
