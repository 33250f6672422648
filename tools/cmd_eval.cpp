// interlin eval: an R-function model (.rf) evaluated at the points of a CSV file.
#include "cli_common.h"
#include "commands.h"

#include "interlin/interflatation/model.h"
#include "interlin/reconstruction/atomic_file.h"
#include "interlin/reconstruction/input_error.h"

#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string_view>

namespace interlin::cli {

const char* const kEvalHelp =
    R"(interlin eval - evaluate an R-function model at points

Usage: interlin eval MODEL.rf POINTS.csv [options]

MODEL.rf    a model file (docs/formats.md, "R-function model files"); F > 0 inside,
            F = 0 on the surface, F < 0 outside
POINTS.csv  a CSV file with a header naming the columns x, y, z (any order, case-insensitive,
            other columns ignored), one point per row; '#' comment lines and blank lines are
            skipped

Output: CSV with the header x,y,z,F (x,y,z,F,Fx,Fy,Fz with --gradient), one row per input
point in input order, numbers with 17 significant digits; on stdout, or in the file of -o.

Options:
  --gradient             also print the gradient of F (exact, forward-mode dual numbers)
  --set NAME=VALUE       override a 'param NAME = ...;' of the model (repeatable)
  --var NAME             evaluate the variable NAME instead of res
  -o, --output FILE      write the CSV to FILE (written whole or not at all)
  -q, --quiet            no progress lines on stderr
  -h, --help             this help

Examples:
  interlin eval data/models/impeller.rf points.csv
  interlin eval data/models/uav.rf points.csv --gradient -o values.csv
  interlin eval data/models/car.rf points.csv --var fig5 --set xs=7
)";

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r'))
    s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> split_commas(std::string_view line) {
  std::vector<std::string_view> f;
  for (;;) {
    const auto c = line.find(',');
    f.push_back(trim(line.substr(0, c)));
    if (c == std::string_view::npos)
      return f;
    line.remove_prefix(c + 1);
  }
}

std::string lower(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'A' && c <= 'Z')
      c = static_cast<char>(c - 'A' + 'a');
  return r;
}

// The whole field must be one finite number (an optional leading '+').
void parse_number(std::string_view field, double& v, const std::string& path, long line,
                  const char* column) {
  std::string_view t = field;
  bool ok = !t.empty();
  if (ok && t.front() == '+') { // one leading '+' is accepted, not "+-1" or "++1"
    t.remove_prefix(1);
    ok = !t.empty() && t.front() != '+' && t.front() != '-';
  }
  const auto r = ok ? std::from_chars(t.data(), t.data() + t.size(), v)
                    : std::from_chars_result{t.data(), std::errc::invalid_argument};
  if (r.ec == std::errc::result_out_of_range)
    throw_input_error(path, line,
                      std::string("column ") + column + ": '" + std::string(field) +
                          "' is out of the range of a double");
  if (r.ec != std::errc() || r.ptr != t.data() + t.size())
    throw_input_error(path, line,
                      std::string("column ") + column + ": '" + std::string(field) +
                          "' is not a number");
  if (!std::isfinite(v))
    throw_input_error(path, line,
                      std::string("column ") + column + ": '" + std::string(field) +
                          "' is not a finite value (NaN and infinity are not allowed)");
}

Points3 read_points(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw_input_error(path, 0, std::string("cannot open: ") + std::strerror(errno));
  std::string text;
  long number = 0;
  std::array<int, 3> col{-1, -1, -1};
  std::size_t fields = 0;
  long header_line = 0;
  std::vector<std::array<double, 3>> rows;
  while (std::getline(in, text)) {
    ++number;
    std::string_view line = text;
    if (number == 1 && line.substr(0, 3) == "\xEF\xBB\xBF")
      line.remove_prefix(3);
    const std::string_view t = trim(line);
    if (t.empty() || t.front() == '#')
      continue;
    const auto f = split_commas(line);
    if (header_line == 0) {
      header_line = number;
      fields = f.size();
      for (std::size_t i = 0; i < f.size(); ++i) {
        const std::string name = lower(f[i]);
        for (int c = 0; c < 3; ++c)
          if (name == std::string(1, static_cast<char>('x' + c))) {
            if (col[c] >= 0)
              throw_input_error(path, number,
                                "column " + name + " appears twice in the header (fields " +
                                    std::to_string(col[c] + 1) + " and " + std::to_string(i + 1) +
                                    ")");
            col[c] = static_cast<int>(i);
          }
      }
      std::string missing;
      for (int c = 0; c < 3; ++c)
        if (col[c] < 0)
          missing += std::string(missing.empty() ? "" : ", ") + static_cast<char>('x' + c);
      if (!missing.empty())
        throw_input_error(path, number,
                          "header lacks the column(s) " + missing +
                              ": a points file starts with a header naming the columns x, y, z");
      continue;
    }
    if (f.size() != fields)
      throw_input_error(path, number,
                        "expected " + std::to_string(fields) +
                            " comma-separated fields (as in the header on line " +
                            std::to_string(header_line) + "), found " + std::to_string(f.size()));
    std::array<double, 3> p{};
    for (int c = 0; c < 3; ++c) {
      const char name[2] = {static_cast<char>('x' + c), 0};
      parse_number(f[static_cast<std::size_t>(col[c])], p[c], path, number, name);
    }
    rows.push_back(p);
  }
  if (in.bad())
    throw_input_error(path, 0, std::string("cannot read: ") + std::strerror(errno));
  if (header_line == 0)
    throw_input_error(path, 0,
                      "no header: the file is empty or holds only comments and blank lines");
  if (rows.empty())
    throw_input_error(path, 0, "no points after the header on line " + std::to_string(header_line));
  Points3 P(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int c = 0; c < 3; ++c)
      P(static_cast<Eigen::Index>(i), c) = rows[i][c];
  return P;
}

void write_values(std::ostream& out, const Points3& P, const Eigen::VectorXd& F, const Points3* G) {
  out << (G ? "x,y,z,F,Fx,Fy,Fz\n" : "x,y,z,F\n");
  char buf[32];
  auto put = [&](double v, char end) {
    std::snprintf(buf, sizeof buf, "%.17g", v);
    out << buf << end;
  };
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    put(P(i, 0), ',');
    put(P(i, 1), ',');
    put(P(i, 2), ',');
    put(F(i), G ? ',' : '\n');
    if (G) {
      put((*G)(i, 0), ',');
      put((*G)(i, 1), ',');
      put((*G)(i, 2), '\n');
    }
  }
}

// The body of `interlin eval` (run_command handles help and exit statuses).
void eval_main(const ParsedArgs& a, std::vector<std::string>&) {
  if (a.positional.size() != 2)
    throw UsageError("expected MODEL.rf POINTS.csv, got " + std::to_string(a.positional.size()) +
                     " argument(s) (see --help)");
  const ModelOptions mo = model_options(a, SettingLabel::setting);
  const std::string output = a.get("output");
  if (!output.empty())
    check_output_dir(output);
  const bool with_gradient = a.has("gradient");
  const Progress progress{a.has("quiet")};
  progress("reading " + a.positional[0]);
  const ImplicitFunction f = load_model(a.positional[0], mo);
  progress("reading " + a.positional[1]);
  const Points3 P = read_points(a.positional[1]);
  progress("evaluating at " + std::to_string(P.rows()) + " points");
  Eigen::VectorXd F(P.rows());
  Points3 G(P.rows(), 3);
  if (with_gradient)
    f.gradient(P, F, G);
  else
    f.value(P, F);
  if (output.empty()) {
    write_values(std::cout, P, F, with_gradient ? &G : nullptr);
    std::cout.flush();
    if (!std::cout)
      throw std::runtime_error("cannot write to standard output");
  } else {
    write_file_atomically(
        output, [&](std::ostream& out) { write_values(out, P, F, with_gradient ? &G : nullptr); });
    progress("wrote " + output);
  }
}

} // namespace

int run_eval(int argc, const char* const* argv) {
  return run_command("eval", kEvalHelp, argc, argv,
                     {{"output", 'o', true, false},
                      {"gradient", 0, false, false},
                      {"set", 0, true, true},
                      {"var", 0, true, false}},
                     eval_main);
}

} // namespace interlin::cli
