#include "interlin/reconstruction/io/csv_fields.h"

#include "interlin/reconstruction/io/input_error.h"

#include <charconv>
#include <cmath>

namespace interlin {

LineReader::LineReader(std::string_view text) : text_(text) {
  if (text_.substr(0, 3) == "\xEF\xBB\xBF")
    pos_ = 3;
}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size())
    return false;
  const std::size_t e = text_.find('\n', pos_);
  const std::size_t stop = e == std::string_view::npos ? text_.size() : e;
  line = text_.substr(pos_, stop - pos_);
  if (!line.empty() && line.back() == '\r')
    line.remove_suffix(1);
  pos_ = e == std::string_view::npos ? text_.size() : e + 1;
  ++number_;
  return true;
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && is_blank(s.front()))
    s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back()))
    s.remove_suffix(1);
  return s;
}

void split_commas(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  for (;;) {
    const size_t c = line.find(',');
    out.push_back(trim(line.substr(0, c)));
    if (c == std::string_view::npos)
      return;
    line.remove_prefix(c + 1);
  }
}

void split_plain(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  line = trim(line);
  if (line.empty())
    return;
  for (;;) {
    const size_t c = line.find(',');
    std::string_view piece = trim(line.substr(0, c));
    if (piece.empty())
      out.push_back(piece);
    while (!piece.empty()) {
      size_t e = 0;
      while (e < piece.size() && !is_blank(piece[e]))
        ++e;
      out.push_back(piece.substr(0, e));
      piece = trim(piece.substr(e));
    }
    if (c == std::string_view::npos)
      return;
    line.remove_prefix(c + 1);
  }
}

std::string ascii_lower(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'A' && c <= 'Z')
      c = static_cast<char>(c - 'A' + 'a');
  return r;
}

NumberKind parse_strict_double(std::string_view tok, double& v) {
  if (!tok.empty() && tok.front() == '+') { // one leading '+', not "+-1" or "++1"
    tok.remove_prefix(1);
    if (tok.empty() || tok.front() == '+' || tok.front() == '-')
      return NumberKind::not_number;
  }
  if (tok.empty())
    return NumberKind::not_number;
  const char* end = tok.data() + tok.size();
  const auto [p, ec] = std::from_chars(tok.data(), end, v, std::chars_format::general);
  if (p != end)
    return NumberKind::not_number;
  if (ec == std::errc::result_out_of_range)
    return NumberKind::out_of_range;
  if (ec != std::errc())
    return NumberKind::not_number;
  return std::isfinite(v) ? NumberKind::ok : NumberKind::not_finite;
}

bool parse_strict_long(std::string_view tok, long& v) {
  if (!tok.empty() && tok.front() == '+') {
    tok.remove_prefix(1);
    if (tok.empty() || tok.front() == '-')
      return false;
  }
  const char* end = tok.data() + tok.size();
  const auto [p, ec] = std::from_chars(tok.data(), end, v);
  return !tok.empty() && ec == std::errc() && p == end;
}

double field_number(std::string_view field, const std::string& path, long line,
                    const char* column) {
  double v = 0;
  const NumberKind kind = parse_strict_double(field, v);
  if (kind == NumberKind::ok)
    return v;
  const std::string what = std::string("column ") + column + ": '" + std::string(field) + "' ";
  throw_input_error(path, line,
                    what + (kind == NumberKind::not_number     ? "is not a number"
                            : kind == NumberKind::out_of_range ? "is out of the range of a double"
                                                               : "is not a finite value (NaN and "
                                                                 "infinity are not allowed)"));
}

long field_index(std::string_view field, const std::string& path, long line) {
  long v = 0;
  if (!parse_strict_long(field, v))
    throw_input_error(path, line, "column index: '" + std::string(field) + "' is not an integer");
  return v;
}

std::vector<int> header_columns(const std::vector<std::string_view>& fields,
                                const std::vector<std::string>& names, const std::string& path,
                                long line) {
  std::vector<int> col(names.size(), -1);
  for (std::size_t i = 0; i < fields.size(); ++i) {
    const std::string name = ascii_lower(fields[i]);
    for (std::size_t c = 0; c < names.size(); ++c)
      if (name == names[c]) {
        if (col[c] >= 0)
          throw_input_error(path, line,
                            "column " + name + " appears twice in the header (fields " +
                                std::to_string(col[c] + 1) + " and " + std::to_string(i + 1) + ")");
        col[c] = static_cast<int>(i);
      }
  }
  return col;
}

std::string missing_columns(const std::vector<int>& columns, const std::vector<std::string>& names,
                            std::size_t required) {
  std::string missing;
  for (std::size_t c = 0; c < required; ++c)
    if (columns[c] < 0)
      missing += (missing.empty() ? "" : ", ") + names[c];
  return missing;
}

} // namespace interlin
