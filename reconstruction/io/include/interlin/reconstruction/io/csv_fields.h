#pragma once
// Lines and fields of the text readers (section, guide and points CSV; the ASCII point-cloud
// formats of reconstruction/clouds): line iteration, ASCII lower case for header names, and the
// strict number and integer rules with their error messages (docs/formats.md, "Section files").

#include <string>
#include <string_view>
#include <vector>

namespace interlin {

// Iterates over the lines of a buffer: strips a UTF-8 BOM and the '\r' of CRLF endings.
class LineReader {
public:
  explicit LineReader(std::string_view text);
  // The next line into `line`; false at the end of the text.
  bool next(std::string_view& line);
  // The 1-based number of the line last returned.
  long number() const { return number_; }
  // The offset in the text (BOM included) of the next line: where binary data after a text
  // header starts.
  std::size_t position() const { return pos_; }

private:
  std::string_view text_;
  std::size_t pos_ = 0;
  long number_ = 0;
};

// Space, \t, \r, \v or \f: what trim removes and what separates plain-format fields.
bool is_blank(char c);

// `s` without leading and trailing blanks.
std::string_view trim(std::string_view s);

// The comma-separated fields of `line`, each trimmed, into `out` ("1,,2" has three fields).
void split_commas(std::string_view line, std::vector<std::string_view>& out);

// Fields separated by commas and/or whitespace: the line is cut at commas and each piece at
// whitespace; a piece holding only whitespace is one empty field ("1,,2" has three fields).
void split_plain(std::string_view line, std::vector<std::string_view>& out);

// `s` with A-Z lowered (header names are matched case-insensitively, independent of locale).
std::string ascii_lower(std::string_view s);

enum class NumberKind { ok, not_number, out_of_range, not_finite };

// The whole field as one number (std::from_chars, general format), one leading '+' allowed.
// `v` holds the value when the result is ok (or not_finite).
NumberKind parse_strict_double(std::string_view field, double& v);

// The whole field as one integer, one leading '+' allowed.
bool parse_strict_long(std::string_view field, long& v);

// parse_strict_double, or an InputError "PATH:LINE: column COLUMN: 'FIELD' is not a number"
// (is out of the range of a double / is not a finite value ...).
double field_number(std::string_view field, const std::string& path, long line, const char* column);

// parse_strict_long, or an InputError "PATH:LINE: column index: 'FIELD' is not an integer".
long field_index(std::string_view field, const std::string& path, long line);

// The column of each of `names` (lower case) among the header `fields` (compared in ASCII lower
// case), -1 when absent; or an InputError "PATH:LINE: column NAME appears twice in the header
// (fields I and J)".
std::vector<int> header_columns(const std::vector<std::string_view>& fields,
                                const std::vector<std::string>& names, const std::string& path,
                                long line);

// "x, z": the first `required` of `names` whose column header_columns did not find ("" when
// every one was found).
std::string missing_columns(const std::vector<int>& columns, const std::vector<std::string>& names,
                            std::size_t required);

} // namespace interlin
