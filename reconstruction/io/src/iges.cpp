#include "interlin/reconstruction/io/iges.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include "cad_text.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace interlin {
namespace {

// Fixed-form layout (IGES 5.3 §2.2): columns 1-72 data (P section: 1-64 data, 65 blank, 66-72
// Directory Entry pointer), column 73 section letter, 74-80 sequence number.
constexpr std::size_t kDataColumns = 72;
constexpr std::size_t kParamColumns = 64;
constexpr std::size_t kMaxString = 64; // a Hollerith string of the Global section fits one line
constexpr long kMaxSequence = 9999999; // seven digits

// ---------------------------------------------------------------------------------- writing --

// Shortest decimal that reads back to x, in IGES real syntax ("1.", "0.25", "1.5E-07").
std::string iges_real(double x) {
  return detail::cad_real(x);
}

// Printable ASCII only (the file is 7-bit text), at most `max` characters.
std::string printable(const std::string& s, std::size_t max) {
  std::string out;
  for (char c : s) {
    if (out.size() == max)
      break;
    const auto u = static_cast<unsigned char>(c);
    out += (u >= 0x20 && u <= 0x7e) ? c : '?';
  }
  return out;
}

// "nHtext"; the empty string is written as an empty (defaulted) parameter.
std::string hollerith(const std::string& s) {
  return s.empty() ? std::string() : std::to_string(s.size()) + "H" + s;
}

// One fixed-form line: data padded to 72 columns, section letter, right-justified sequence.
std::string fixed_line(const std::string& data, char section, long seq) {
  if (seq > kMaxSequence)
    throw std::invalid_argument("write_iges: more than 9999999 lines in one section");
  std::string line = data;
  line.resize(kDataColumns, ' ');
  std::array<char, 32> tail{};
  std::snprintf(tail.data(), tail.size(), "%c%7ld", section, seq);
  return line + tail.data();
}

// Free-format record: parameters separated by ',' and ended by ';', packed into lines of
// `width` columns; a parameter never spans two lines.
std::vector<std::string> pack_record(const std::vector<std::string>& params, std::size_t width) {
  std::vector<std::string> lines;
  std::string current;
  for (std::size_t k = 0; k < params.size(); ++k) {
    const std::string item = params[k] + (k + 1 == params.size() ? ';' : ',');
    if (item.size() > width)
      throw std::logic_error("write_iges: parameter longer than a line");
    if (current.size() + item.size() > width) {
      lines.push_back(current);
      current.clear();
    }
    current += item;
  }
  if (!current.empty())
    lines.push_back(current);
  return lines;
}

// Global parameter 18/25 "YYYYMMDD.HHNNSS" (UTC); SOURCE_DATE_EPOCH makes the output reproducible.
std::string iges_date() {
  return detail::file_time("%Y%m%d.%H%M%S");
}

struct UnitLabel {
  int flag;
  const char* name;
};

UnitLabel unit_label(LengthUnit unit) {
  switch (unit) {
  case LengthUnit::mm:
    return {2, "MM"};
  case LengthUnit::cm:
    return {10, "CM"};
  case LengthUnit::m:
    return {6, "M"};
  case LengthUnit::inch:
    return {1, "IN"};
  }
  throw std::invalid_argument("write_iges: unknown LengthUnit");
}

// Parameter Data of entity 128 (IGES 5.3 §4.24), one string per parameter.
std::vector<std::string> surface_parameters(const BSplineSurface& s) {
  const Eigen::Index nu = s.num_u, nv = s.num_v;
  std::vector<std::string> p;
  p.reserve(static_cast<std::size_t>(14 + s.knots_u.size() + s.knots_v.size() + 4 * nu * nv));
  p.push_back("128");
  p.push_back(std::to_string(nu - 1));                // K1: upper index of the first sum
  p.push_back(std::to_string(nv - 1));                // K2
  p.push_back(std::to_string(s.degree_u));            // M1
  p.push_back(std::to_string(s.degree_v));            // M2
  p.push_back(s.closed_u ? "1" : "0");                // PROP1: closed in u
  p.push_back("0");                                   // PROP2: not closed in v
  p.push_back("1");                                   // PROP3: polynomial (weights all 1)
  p.push_back("0");                                   // PROP4: not periodic in u
  p.push_back("0");                                   // PROP5: not periodic in v
  for (Eigen::Index k = 0; k < s.knots_u.size(); ++k) // S(-M1) .. S(N1+M1)
    p.push_back(iges_real(s.knots_u(k)));
  for (Eigen::Index k = 0; k < s.knots_v.size(); ++k) // T(-M2) .. T(N2+M2)
    p.push_back(iges_real(s.knots_v(k)));
  for (Eigen::Index k = 0; k < nu * nv; ++k) // W(0,0), W(1,0), ..., first index fastest
    p.push_back("1.");
  for (Eigen::Index k = 0; k < nu * nv; ++k) // X, Y, Z of P(i,j) at k = i + num_u * j
    for (int c = 0; c < 3; ++c)
      p.push_back(iges_real(s.ctrl(k, c)));
  p.push_back(iges_real(s.knots_u(s.degree_u))); // U(0), U(1): the whole knot domain
  p.push_back(iges_real(s.knots_u(nu)));
  p.push_back(iges_real(s.knots_v(s.degree_v))); // V(0), V(1)
  p.push_back(iges_real(s.knots_v(nv)));
  return p;
}

// ---------------------------------------------------------------------------------- reading --

constexpr std::string_view kSections = "SGDPT";

struct IgesFile {
  std::string path;
  std::vector<std::string> lines;   // every line, CR stripped
  std::array<long, 5> first_line{}; // file line (1-based) of each section's first line
  std::array<long, 5> count{};      // lines per section
  char param_delim = ',', record_delim = ';';

  // File line of sequence number `seq` of section k.
  long file_line(int k, long seq) const { return first_line[k] + seq - 1; }
  const std::string& line(int k, long seq) const {
    return lines[static_cast<std::size_t>(file_line(k, seq) - 1)];
  }
  [[noreturn]] void fail(long line, const std::string& message) const {
    throw_input_error(path, line, message);
  }
};

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos)
    return {};
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// Integer in `text` (surrounding blanks allowed, empty -> `empty_value`); false if malformed.
bool parse_long(std::string_view text, long empty_value, long& out) {
  text = trim(text);
  if (text.empty()) {
    out = empty_value;
    return true;
  }
  if (text.front() == '+')
    text.remove_prefix(1);
  const auto res = std::from_chars(text.data(), text.data() + text.size(), out);
  return res.ec == std::errc() && res.ptr == text.data() + text.size();
}

// IGES real constant (E or D exponent, optional sign; an integer is accepted); empty -> 0.
bool parse_real(std::string_view text, double& out) {
  text = trim(text);
  if (text.empty()) {
    out = 0.0;
    return true;
  }
  std::string t(text);
  if (t.front() == '+')
    t.erase(0, 1);
  for (char& c : t)
    if (c == 'D' || c == 'd')
      c = 'E';
  const auto res = std::from_chars(t.data(), t.data() + t.size(), out);
  return res.ec == std::errc() && res.ptr == t.data() + t.size() && std::isfinite(out);
}

// The file's lines, CR stripped.
std::vector<std::string> split_lines(std::string_view text) {
  std::vector<std::string> lines;
  while (!text.empty()) {
    const std::size_t e = std::min(text.find('\n'), text.size());
    std::string_view l = text.substr(0, e);
    if (!l.empty() && l.back() == '\r')
      l.remove_suffix(1);
    lines.emplace_back(l);
    text.remove_prefix(std::min(e + 1, text.size()));
  }
  return lines;
}

// Section letters in column 73 in the order S G D P T, sequence numbers 1, 2, ... in each.
void read_sections(IgesFile& f) {
  int current = -1;
  for (std::size_t i = 0; i < f.lines.size(); ++i) {
    const std::string& l = f.lines[i];
    const long ln = static_cast<long>(i) + 1;
    if (current == 4 && trim(l).empty())
      continue; // blank lines after the Terminate section
    if (l.size() < kDataColumns + 1)
      f.fail(ln, "line has " + std::to_string(l.size()) +
                     " columns; the IGES fixed form needs 80 (section letter in column 73)");
    const char letter = l[kDataColumns];
    if (letter == 'C' || letter == 'B')
      f.fail(ln, "compressed or binary IGES is not supported (fixed ASCII form only)");
    const auto k = kSections.find(letter);
    if (k == std::string_view::npos)
      f.fail(ln, std::string("unknown section letter '") + letter + "' in column 73");
    const int kk = static_cast<int>(k);
    if (kk < current)
      f.fail(ln, std::string("section ") + letter + " after section " + kSections[current]);
    if (current == 4)
      f.fail(ln, "more than one Terminate line");
    if (kk > current) {
      current = kk;
      f.first_line[kk] = ln;
    }
    ++f.count[kk];
    long seq = 0;
    const std::string_view seq_text = std::string_view(l).substr(kDataColumns + 1, 7);
    if (!parse_long(seq_text, -1, seq) || seq != f.count[kk])
      f.fail(ln, "sequence number '" + std::string(trim(seq_text)) + "', expected " +
                     std::to_string(f.count[kk]));
  }
  if (current != 4)
    f.fail(static_cast<long>(f.lines.size()), "file ends without a Terminate section (truncated?)");
}

// Every section present, whole Directory entries, and the Terminate line's counts
// "S      nG      nD      nP      n" equal to the line counts.
void check_counts(const IgesFile& f) {
  const char* names[] = {"Start", "Global", "Directory Entry", "Parameter Data"};
  for (int k = 1; k < 4; ++k)
    if (f.count[k] == 0)
      f.fail(f.first_line[4], std::string("no ") + names[k] + " section");
  if (f.count[2] % 2 != 0)
    f.fail(f.file_line(2, f.count[2]), "Directory Entry section has an odd number of lines");
  const std::string& t = f.lines[static_cast<std::size_t>(f.first_line[4] - 1)];
  for (int k = 0; k < 4; ++k) {
    long n = 0;
    if (t[static_cast<std::size_t>(8 * k)] != kSections[static_cast<std::size_t>(k)] ||
        !parse_long(std::string_view(t).substr(static_cast<std::size_t>(8 * k + 1), 7), -1, n))
      f.fail(f.first_line[4], "malformed Terminate section");
    if (n != f.count[k])
      f.fail(f.first_line[4], std::string("Terminate section counts ") + std::to_string(n) + " " +
                                  names[k] + " lines, the file has " + std::to_string(f.count[k]) +
                                  " (truncated?)");
  }
}

// Global parameters 1 and 2: the delimiters ("1H," / "1H;" or empty for the defaults).
void read_delimiters(IgesFile& f) {
  std::string g;
  for (long seq = 1; seq <= f.count[1]; ++seq)
    g += f.line(1, seq).substr(0, kDataColumns);
  std::size_t pos = g.find_first_not_of(' ');
  const long gline = f.first_line[1];
  if (pos == std::string::npos)
    f.fail(gline, "empty Global section");
  auto delimiter = [&](char default_value, char next_delim) {
    if (pos < g.size() && (g[pos] == next_delim || g[pos] == ';'))
      return default_value; // empty parameter: the default
    if (g.compare(pos, 2, "1H") != 0 || pos + 2 >= g.size())
      f.fail(gline, "Global section must start with the delimiters (1H, or empty)");
    const char c = g[pos + 2];
    pos += 3;
    return c;
  };
  f.param_delim = delimiter(',', ',');
  if (pos >= g.size() || g[pos] != f.param_delim)
    f.fail(gline, "Global section: parameter delimiter expected after parameter 1");
  ++pos;
  f.record_delim = delimiter(';', f.param_delim);
  if (f.param_delim == f.record_delim || f.param_delim == ' ' || f.record_delim == ' ')
    f.fail(gline, "Global section: invalid delimiters");
}

IgesFile load(std::string_view text, const std::string& path) {
  IgesFile f;
  f.path = path;
  f.lines = split_lines(text);
  if (f.lines.empty())
    throw_input_error(path, 0, "empty file");
  read_sections(f);
  check_counts(f);
  read_delimiters(f);
  return f;
}

struct DirectoryEntry {
  long seq = 0; // sequence number of its first line (odd)
  long type = 0, param_pointer = 0, transform = 0, param_lines = 0, form = 0;
};

DirectoryEntry directory_entry(const IgesFile& f, long seq) {
  DirectoryEntry e;
  e.seq = seq;
  const std::string& l1 = f.line(2, seq);
  const std::string& l2 = f.line(2, seq + 1);
  auto field = [&](const std::string& l, long line_seq, int n, long& out) {
    const std::string_view text =
        std::string_view(l).substr(static_cast<std::size_t>(8 * (n - 1)), 8);
    if (!parse_long(text, 0, out))
      f.fail(f.file_line(2, line_seq), "Directory Entry field " + std::to_string(n) + " '" +
                                           std::string(trim(text)) + "' is not an integer");
  };
  long type2 = 0;
  field(l1, seq, 1, e.type);
  field(l1, seq, 2, e.param_pointer);
  field(l1, seq, 7, e.transform);
  field(l2, seq + 1, 1, type2);
  field(l2, seq + 1, 4, e.param_lines);
  field(l2, seq + 1, 5, e.form);
  if (type2 != e.type)
    f.fail(f.file_line(2, seq + 1), "entity type " + std::to_string(type2) +
                                        " differs from the first line's " + std::to_string(e.type));
  return e;
}

struct Token {
  std::string text;
  long line = 0;
};

// The free-format parameter record of entity `e`: parameters (Hollerith strings decoded) with
// the file line where each starts. Reading stops at the record delimiter.
std::vector<Token> parameters(const IgesFile& f, const DirectoryEntry& e, long& last_line) {
  const long de_line = f.file_line(2, e.seq);
  if (e.param_pointer < 1 || e.param_lines < 1 || e.param_pointer + e.param_lines - 1 > f.count[3])
    f.fail(de_line, "parameter data lines " + std::to_string(e.param_pointer) + ".." +
                        std::to_string(e.param_pointer + e.param_lines - 1) +
                        " outside the Parameter Data section (" + std::to_string(f.count[3]) +
                        " lines)");
  std::string text;
  for (long k = 0; k < e.param_lines; ++k) {
    const long seq = e.param_pointer + k;
    const std::string& l = f.line(3, seq);
    long owner = 0;
    if (!parse_long(std::string_view(l).substr(kParamColumns + 1, 7), -1, owner) || owner != e.seq)
      f.fail(f.file_line(3, seq), "parameter line belongs to Directory Entry '" +
                                      std::string(trim(std::string_view(l).substr(65, 7))) +
                                      "', expected " + std::to_string(e.seq));
    text += l.substr(0, kParamColumns);
  }
  const long first = f.file_line(3, e.param_pointer);
  last_line = first + e.param_lines - 1;
  auto line_at = [&](std::size_t i) { return first + static_cast<long>(i / kParamColumns); };

  std::vector<Token> tokens;
  std::size_t i = 0;
  const std::size_t n = text.size();
  while (true) {
    while (i < n && text[i] == ' ')
      ++i;
    if (i >= n)
      f.fail(last_line, "parameter data ends without the record delimiter '" +
                            std::string(1, f.record_delim) + "'");
    Token t;
    t.line = line_at(i);
    std::size_t j = i;
    while (j < n && std::isdigit(static_cast<unsigned char>(text[j])))
      ++j;
    if (j > i && j < n && text[j] == 'H') { // Hollerith string nH...
      const std::size_t len = j - i > 9 ? n : std::stoul(text.substr(i, j - i));
      if (j + 1 + len > n)
        f.fail(t.line, "Hollerith string runs past the end of the parameter data");
      t.text = text.substr(j + 1, len);
      i = j + 1 + len;
      while (i < n && text[i] == ' ')
        ++i;
    } else {
      j = i;
      while (j < n && text[j] != f.param_delim && text[j] != f.record_delim)
        ++j;
      t.text = std::string(trim(std::string_view(text).substr(i, j - i)));
      i = j;
    }
    tokens.push_back(std::move(t));
    if (i >= n)
      f.fail(last_line, "parameter data ends without the record delimiter '" +
                            std::string(1, f.record_delim) + "'");
    if (text[i] == f.record_delim)
      break;
    if (text[i] != f.param_delim)
      f.fail(line_at(i), std::string("unexpected '") + text[i] + "' after a parameter");
    ++i;
  }
  return tokens;
}

// Reads parameters by index with typed checks and line-accurate errors.
struct ParameterReader {
  const IgesFile& f;
  const std::vector<Token>& tokens;
  long last_line;
  std::string entity;

  const Token& at(std::size_t k, const std::string& what) const {
    if (k >= tokens.size())
      f.fail(last_line, entity + " parameter data ends after " + std::to_string(tokens.size()) +
                            " values, before " + what);
    return tokens[k];
  }
  long integer(std::size_t k, const std::string& what) const {
    const Token& t = at(k, what);
    long v = 0;
    if (!parse_long(t.text, 0, v))
      f.fail(t.line, "bad integer '" + t.text + "' for " + what);
    return v;
  }
  double real(std::size_t k, const std::string& what) const {
    const Token& t = at(k, what);
    double v = 0.0;
    if (!parse_real(t.text, v))
      f.fail(t.line, "bad number '" + t.text + "' for " + what);
    return v;
  }
};

// Applies the transformation matrix chain (entity 124: x -> R x + T) starting at DE `pointer`.
void apply_transform(const IgesFile& f, long pointer, long referenced_from, Eigen::MatrixXd& ctrl) {
  for (int depth = 0; pointer != 0; ++depth) {
    if (depth > 32)
      f.fail(referenced_from, "transformation matrix chain longer than 32 (a cycle?)");
    if (pointer < 1 || pointer >= f.count[2] || pointer % 2 == 0)
      f.fail(referenced_from, "transformation matrix pointer " + std::to_string(pointer) +
                                  " is not a Directory Entry");
    const DirectoryEntry e = directory_entry(f, pointer);
    if (e.type != 124)
      f.fail(referenced_from, "transformation matrix pointer " + std::to_string(pointer) +
                                  " refers to entity " + std::to_string(e.type) + ", expected 124");
    long last_line = 0;
    const std::vector<Token> tokens = parameters(f, e, last_line);
    const ParameterReader r{f, tokens, last_line, "entity 124"};
    Eigen::Matrix3d R;
    Eigen::Vector3d T;
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col)
        R(row, col) = r.real(static_cast<std::size_t>(1 + 4 * row + col),
                             "R" + std::to_string(row + 1) + std::to_string(col + 1));
      T(row) = r.real(static_cast<std::size_t>(4 + 4 * row), "T" + std::to_string(row + 1));
    }
    ctrl = ((ctrl * R.transpose()).rowwise() + T.transpose()).eval();
    referenced_from = f.file_line(2, e.seq);
    pointer = e.transform;
  }
}

bool is_clamped(const Eigen::VectorXd& knots, int degree, Eigen::Index num) {
  for (int k = 1; k <= degree; ++k)
    if (knots(k) != knots(0) || knots(num + k) != knots(num))
      return false;
  return true;
}

// The first Directory entry of type 128 (rational B-spline surface).
DirectoryEntry find_surface_entry(const IgesFile& f) {
  for (long seq = 1; seq < f.count[2]; seq += 2) {
    const DirectoryEntry e = directory_entry(f, seq);
    if (e.type == 128)
      return e;
  }
  f.fail(0, "no rational B-spline surface (entity 128) in the file");
}

// Parameters 1-9 of entity 128: K1, K2, M1, M2, PROP1..5 -> degrees, counts, closed_u.
BSplineSurface surface_header(const ParameterReader& r, const DirectoryEntry& e) {
  const IgesFile& f = r.f;
  const std::vector<Token>& tokens = r.tokens;
  const long type = r.integer(0, "the entity type");
  if (type != 128)
    f.fail(tokens[0].line, "parameter data of Directory Entry " + std::to_string(e.seq) +
                               " is entity " + std::to_string(type) + ", expected 128");
  const long k1 = r.integer(1, "K1"), k2 = r.integer(2, "K2");
  const long m1 = r.integer(3, "M1"), m2 = r.integer(4, "M2");
  constexpr long kMaxIndex = 10'000'000;
  if (m1 < 1 || m2 < 1 || m1 > 64 || m2 > 64)
    f.fail(tokens[3].line, "degrees M1 = " + std::to_string(m1) + ", M2 = " + std::to_string(m2) +
                               " (1..64 supported)");
  if (k1 < m1 || k2 < m2 || k1 > kMaxIndex || k2 > kMaxIndex)
    f.fail(tokens[1].line, "K1 = " + std::to_string(k1) + ", K2 = " + std::to_string(k2) +
                               " do not fit degrees " + std::to_string(m1) + ", " +
                               std::to_string(m2) + " (need K >= M)");
  long prop[5];
  for (int k = 0; k < 5; ++k) {
    prop[k] = r.integer(static_cast<std::size_t>(5 + k), "PROP" + std::to_string(k + 1));
    if (prop[k] != 0 && prop[k] != 1)
      f.fail(tokens[static_cast<std::size_t>(5 + k)].line,
             "PROP" + std::to_string(k + 1) + " must be 0 or 1, is " + std::to_string(prop[k]));
  }
  BSplineSurface s;
  s.degree_u = static_cast<int>(m1);
  s.degree_v = static_cast<int>(m2);
  s.num_u = k1 + 1;
  s.num_v = k2 + 1;
  s.closed_u = prop[0] == 1;
  return s;
}

// A nondecreasing, clamped knot vector of `count` knots from parameter k on; advances k.
Eigen::VectorXd read_knots(const ParameterReader& r, std::size_t& k, std::int64_t count,
                           const char* dir, int degree, Eigen::Index num) {
  const std::size_t first = k;
  Eigen::VectorXd knots(count);
  for (Eigen::Index q = 0; q < count; ++q, ++k) {
    knots(q) = r.real(k, std::string(dir) + " knot " + std::to_string(q));
    if (q > 0 && knots(q) < knots(q - 1))
      r.f.fail(r.tokens[k].line, std::string(dir) + " knots decrease at knot " + std::to_string(q));
  }
  if (!is_clamped(knots, degree, num))
    r.f.fail(r.tokens[first].line, std::string(dir) +
                                       " knot vector is not clamped (end knots of multiplicity "
                                       "degree + 1 = " +
                                       std::to_string(degree + 1) + " are required)");
  return knots;
}

// Positive, equal weights (equal weights cancel in the rational form: the surface is polynomial).
void check_weights(const ParameterReader& r, std::size_t& k, std::int64_t num_ctrl) {
  const double w0 = r.real(k, "weight W(0,0)");
  for (std::int64_t q = 0; q < num_ctrl; ++q, ++k) {
    const double w = r.real(k, "weight " + std::to_string(q));
    if (!(w > 0.0))
      r.f.fail(r.tokens[k].line, "weight " + std::to_string(q) + " is not positive");
    if (std::abs(w - w0) > 1e-12 * w0)
      r.f.fail(r.tokens[k].line, "rational surface (unequal weights) is not supported");
  }
}

// U(0), U(1), V(0), V(1) must be the knot domain: a restricted range is not representable.
void check_parameter_range(const ParameterReader& r, std::size_t k, const BSplineSurface& s) {
  const double range[4] = {r.real(k, "U(0)"), r.real(k + 1, "U(1)"), r.real(k + 2, "V(0)"),
                           r.real(k + 3, "V(1)")};
  const double domain[4] = {s.knots_u(s.degree_u), s.knots_u(s.num_u), s.knots_v(s.degree_v),
                            s.knots_v(s.num_v)};
  for (int q = 0; q < 4; ++q) {
    const double span = q < 2 ? domain[1] - domain[0] : domain[3] - domain[2];
    if (std::abs(range[q] - domain[q]) > 1e-9 * std::abs(span))
      r.f.fail(r.tokens[k + static_cast<std::size_t>(q)].line,
               "parameter range [" + iges_real(range[0]) + ", " + iges_real(range[1]) + "] x [" +
                   iges_real(range[2]) + ", " + iges_real(range[3]) +
                   "] differs from the knot domain; restricted surfaces are not supported");
  }
}

// Entity 128's parameter record (IGES 5.3 §4.24) -> the polynomial B-spline surface.
BSplineSurface surface_of_parameters(const ParameterReader& r, const DirectoryEntry& e) {
  BSplineSurface s = surface_header(r, e);
  const std::int64_t num_ku = s.num_u + s.degree_u + 1, num_kv = s.num_v + s.degree_v + 1;
  const std::int64_t num_ctrl = static_cast<std::int64_t>(s.num_u) * s.num_v;
  const std::int64_t needed = 10 + num_ku + num_kv + 4 * num_ctrl + 4;
  if (static_cast<std::int64_t>(r.tokens.size()) < needed)
    r.f.fail(r.last_line, "entity 128 with K1 = " + std::to_string(s.num_u - 1) + ", K2 = " +
                              std::to_string(s.num_v - 1) + " needs " + std::to_string(needed) +
                              " parameters, the record has " + std::to_string(r.tokens.size()));
  std::size_t k = 10;
  s.knots_u = read_knots(r, k, num_ku, "u", s.degree_u, s.num_u);
  s.knots_v = read_knots(r, k, num_kv, "v", s.degree_v, s.num_v);
  check_weights(r, k, num_ctrl);
  s.ctrl.resize(num_ctrl, 3);
  for (std::int64_t q = 0; q < num_ctrl; ++q)
    for (int c = 0; c < 3; ++c, ++k)
      s.ctrl(q, c) = r.real(k, "control point " + std::to_string(q) + " coordinate " +
                                   std::string(1, "XYZ"[c]));
  check_parameter_range(r, k, s);
  return s;
}

// Start section: a fixed first line, then the description's paragraphs cut at 72 columns.
std::vector<std::string> start_section(const std::string& description_text) {
  std::vector<std::string> start = {
      "interlin B-spline surface (IGES 5.3 entity 128, polynomial, untrimmed)"};
  std::string description = description_text;
  while (!description.empty() && (description.back() == '\n' || description.back() == '\r'))
    description.pop_back();
  if (description.empty())
    return start;
  for (std::size_t b = 0; b <= description.size();) {
    auto e = description.find('\n', b);
    if (e == std::string::npos)
      e = description.size();
    const std::string paragraph = printable(description.substr(b, e - b), std::string::npos);
    for (std::size_t c = 0; c < paragraph.size() || c == 0; c += kDataColumns)
      start.push_back(paragraph.substr(c, kDataColumns));
    b = e + 1;
  }
  return start;
}

// Global section (IGES 5.3 §2.2.4): the 25 parameters, packed into 72-column lines.
std::vector<std::string> global_section(const std::string& path, const BSplineSurface& s,
                                        const IgesOptions& opt) {
  const UnitLabel unit = unit_label(opt.unit);
  const std::string date = iges_date();
  const double max_coord = s.ctrl.size() > 0 ? s.ctrl.cwiseAbs().maxCoeff() : 0.0;
  // Minimum intended resolution: far below any modelling tolerance, far above the round-off of
  // the written coordinates (readers such as OpenCASCADE use it as their working precision).
  const double resolution = 1e-7 * (max_coord > 0.0 ? max_coord : 1.0);
  const std::string name = printable(std::filesystem::path(path).filename().string(), kMaxString);
  const std::string product = "interlin";
  return pack_record(
      {
          hollerith(","),                               // 1 parameter delimiter
          hollerith(";"),                               // 2 record delimiter
          hollerith(product),                           // 3 sender's product id
          hollerith(name),                              // 4 file name
          hollerith(product),                           // 5 native system id
          hollerith("interlin IGES writer 1"),          // 6 preprocessor version
          "32",                                         // 7 bits per integer
          "38",                                         // 8 single precision: max power of ten
          "6",                                          // 9 single precision: digits
          "308",                                        // 10 double precision: max power of ten
          "15",                                         // 11 double precision: digits
          hollerith(product),                           // 12 receiver's product id
          "1.",                                         // 13 model space scale
          std::to_string(unit.flag),                    // 14 unit flag
          hollerith(unit.name),                         // 15 unit name
          "1",                                          // 16 line weight gradations
          "1.",                                         // 17 maximum line width
          hollerith(date),                              // 18 file generation date
          iges_real(resolution),                        // 19 minimum resolution
          iges_real(max_coord),                         // 20 approximate maximum coordinate
          hollerith(printable(opt.author, kMaxString)), // 21 author
          "",                                           // 22 organization
          "11",                                         // 23 version flag: IGES 5.3
          "0",                                          // 24 drafting standard: none
          hollerith(date),                              // 25 model modification date
      },
      kDataColumns);
}

// The two Directory Entry lines of the one entity 128, its parameter data `num_param` lines long.
std::array<std::string, 2> directory_lines(long num_param) {
  std::array<char, 96> d1{}, d2{};
  std::snprintf(d1.data(), d1.size(), "%8d%8d%8d%8d%8d%8d%8d%8d%8s", 128, 1, 0, 0, 0, 0, 0, 0,
                "00000000");
  std::snprintf(d2.data(), d2.size(), "%8d%8d%8d%8ld%8d%8s%8s%8s%8d", 128, 0, 0, num_param, 0, "",
                "", "BSURFACE", 0);
  return {d1.data(), d2.data()};
}

} // namespace

void write_iges(const std::string& path, const BSplineSurface& s, const IgesOptions& opt) {
  check_surface(s);
  const std::vector<std::string> start = start_section(opt.description);
  const std::vector<std::string> global = global_section(path, s, opt);
  const std::vector<std::string> param = pack_record(surface_parameters(s), kParamColumns);
  const long num_param = static_cast<long>(param.size());
  const std::array<std::string, 2> d = directory_lines(num_param);
  write_file_atomically(path, [&](std::ostream& out) {
    long seq = 0;
    for (const std::string& l : start)
      out << fixed_line(l, 'S', ++seq) << '\n';
    const long num_start = seq;
    seq = 0;
    for (const std::string& l : global)
      out << fixed_line(l, 'G', ++seq) << '\n';
    out << fixed_line(d[0], 'D', 1) << '\n' << fixed_line(d[1], 'D', 2) << '\n';
    seq = 0;
    for (const std::string& l : param) {
      std::string data = l;
      data.resize(kParamColumns, ' ');
      std::array<char, 16> owner{};
      std::snprintf(owner.data(), owner.size(), " %7d", 1); // column 65 blank, 66-72 DE pointer
      out << fixed_line(data + owner.data(), 'P', ++seq) << '\n';
    }
    std::array<char, 64> t{};
    std::snprintf(t.data(), t.size(), "S%7ldG%7ldD%7dP%7ld", num_start,
                  static_cast<long>(global.size()), 2, num_param);
    out << fixed_line(t.data(), 'T', 1) << '\n';
  });
}

BSplineSurface read_iges_surface(const std::string& path) {
  return parse_iges_surface(read_input_file(path), path);
}

BSplineSurface parse_iges_surface(std::string_view text, const std::string& path) {
  const IgesFile f = load(text, path);
  const DirectoryEntry e = find_surface_entry(f);
  const long de_line = f.file_line(2, e.seq);
  long last_line = 0;
  const std::vector<Token> tokens = parameters(f, e, last_line);
  BSplineSurface s = surface_of_parameters(ParameterReader{f, tokens, last_line, "entity 128"}, e);
  apply_transform(f, e.transform, de_line, s.ctrl);

  try {
    check_surface(s);
    to_piecewise(s); // the explicit form every evaluation uses: near-coincident knots fail here
  } catch (const std::invalid_argument& ex) {
    f.fail(de_line, std::string("invalid surface: ") + ex.what());
  } catch (const std::runtime_error& ex) { // the explicit basis of near-coincident knots
    f.fail(de_line, std::string("invalid surface: ") + ex.what());
  }
  return s;
}

} // namespace interlin
