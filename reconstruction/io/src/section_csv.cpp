#include "interlin/reconstruction/io/section_csv.h"

#include "interlin/reconstruction/io/csv_fields.h"

#include "interlin/interflatation/read_input_file.h"
#include "interlin/reconstruction/io/atomic_file.h"
#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <istream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>

namespace interlin {

namespace {

using std::string_view;

std::string quote(string_view s) {
  return "'" + std::string(s) + "'";
}

bool is_comment(string_view trimmed) {
  return !trimmed.empty() && trimmed.front() == '#';
}

struct RawPoint {
  long index;
  double x, y, z;
  long line;
};

struct RawSection {
  std::string id;
  long first_line = 0; // first line of the section in the file
  long run_end = 0;    // last line of its latest contiguous run
  std::vector<RawPoint> points;
};

class Parser {
public:
  explicit Parser(std::string path) : path_(std::move(path)) {}

  SectionSet parse(string_view text) {
    LineReader lines(text);
    string_view line;
    while (lines.next(line)) {
      const string_view t = trim(line);
      if (t.empty() || is_comment(t))
        continue;
      start(t, lines.number());
      if (csv_)
        parse_csv(lines);
      else
        parse_plain(lines, header_ ? 0 : lines.number(), t);
      return finish();
    }
    fail(0, "no data rows (the file is empty or holds only comments and blank lines)");
  }

private:
  [[noreturn]] void fail(long line, const std::string& message) const {
    throw_input_error(path_, line, message);
  }

  // Decides the format from the first content line (trimmed, non-empty, not a comment).
  void start(string_view first, long line) {
    header_line_ = line;
    split_plain(first, fields_);
    double v;
    const bool numeric = std::any_of(fields_.begin(), fields_.end(), [&](string_view f) {
      return parse_strict_double(f, v) != NumberKind::not_number;
    });
    if (numeric) {
      if (fields_.size() != 3)
        fail(line, "no header: this first line has " + std::to_string(fields_.size()) +
                       " fields; a section file starts with a header naming the columns "
                       "section, x, y, z (index optional), a plain file has 3 numbers x y z "
                       "per line");
      csv_ = false;
      header_ = false;
      col_ = {0, 1, 2};
      return;
    }
    const bool has_comma = first.find(',') != string_view::npos;
    std::vector<std::string> names;
    if (has_comma) {
      split_commas(first, fields_);
      for (string_view f : fields_)
        names.push_back(ascii_lower(f));
    }
    if (std::find(names.begin(), names.end(), "section") != names.end()) {
      csv_ = true;
      header_ = true;
      csv_header(line);
      return;
    }
    split_plain(first, fields_);
    names.clear();
    for (string_view f : fields_)
      names.push_back(ascii_lower(f));
    if (std::find(names.begin(), names.end(), "section") != names.end())
      fail(line, "the header names a section column but has no commas: section files are "
                 "comma-separated");
    auto sorted = names;
    std::sort(sorted.begin(), sorted.end());
    if (sorted == std::vector<std::string>{"x", "y", "z"}) {
      csv_ = false;
      header_ = true;
      for (int k = 0; k < 3; ++k)
        col_[static_cast<size_t>(names[static_cast<size_t>(k)][0] - 'x')] = static_cast<size_t>(k);
      return;
    }
    fail(line, "header lacks the section column: a section file's header names the columns "
               "section, x, y, z (index optional, other columns ignored), a plain file's header "
               "names exactly x, y, z");
  }

  // The columns of a section CSV header (fields_ holds its comma-separated fields).
  void csv_header(long line) {
    ncol_ = fields_.size();
    const std::vector<std::string> names{"section", "x", "y", "z", "index"};
    const std::vector<int> col = header_columns(fields_, names, path_, line);
    size_t* where[] = {&sec_col_, &col_[0], &col_[1], &col_[2], &index_col_};
    for (size_t k = 0; k < names.size(); ++k)
      *where[k] = col[k] < 0 ? npos : static_cast<size_t>(col[k]);
    const std::string missing = missing_columns(col, names, 4);
    if (!missing.empty())
      fail(line, "header lacks the required column(s) " + missing +
                     ": a section file's header names the columns section, x, y, z (index "
                     "optional, other columns ignored)");
  }

  RawPoint point(long line) const {
    RawPoint p{};
    p.line = line;
    p.x = field_number(fields_[col_[0]], path_, line, "x");
    p.y = field_number(fields_[col_[1]], path_, line, "y");
    p.z = field_number(fields_[col_[2]], path_, line, "z");
    return p;
  }

  void parse_csv(LineReader& lines) {
    std::unordered_map<std::string, size_t> by_id;
    size_t cur = npos;
    string_view line;
    while (lines.next(line)) {
      const string_view t = trim(line);
      if (t.empty() || is_comment(t))
        continue;
      const long n = lines.number();
      split_commas(t, fields_);
      if (fields_.size() != ncol_)
        fail(n, "expected " + std::to_string(ncol_) +
                    " comma-separated fields (as in the header "
                    "on line " +
                    std::to_string(header_line_) + "), found " + std::to_string(fields_.size()));
      const string_view id = fields_[sec_col_];
      if (id.empty())
        fail(n, "column section: empty value");
      RawPoint p = point(n);
      if (index_col_ != npos)
        p.index = field_index(fields_[index_col_], path_, n);
      if (cur == npos || sections_[cur].id != id) {
        const auto [it, added] = by_id.try_emplace(std::string(id), sections_.size());
        if (added) {
          sections_.emplace_back();
          sections_.back().id = std::string(id);
          sections_.back().first_line = n;
        } else if (index_col_ == npos) {
          fail(n, "rows of section " + std::string(id) +
                      " resume here after other sections (its previous run ended at line " +
                      std::to_string(sections_[it->second].run_end) +
                      "); make them contiguous or add an index column");
        }
        cur = it->second;
      }
      sections_[cur].points.push_back(p);
      sections_[cur].run_end = n;
    }
  }

  // first_data: line number of the first content line when it is data (no header), else 0.
  void parse_plain(LineReader& lines, long first_data, string_view first) {
    bool open = false;
    auto add = [&](long n) {
      if (fields_.size() != 3)
        fail(n, "expected 3 fields (x, y, z), found " + std::to_string(fields_.size()));
      if (!open) {
        sections_.emplace_back();
        sections_.back().id = std::to_string(sections_.size());
        sections_.back().first_line = n;
        open = true;
      }
      RawPoint p = point(n);
      p.index = static_cast<long>(sections_.back().points.size());
      sections_.back().points.push_back(p);
    };
    if (first_data > 0) {
      split_plain(first, fields_);
      add(first_data);
    }
    string_view line;
    while (lines.next(line)) {
      const string_view t = trim(line);
      if (t.empty()) {
        open = false;
        continue;
      }
      if (is_comment(t))
        continue;
      split_plain(t, fields_);
      add(lines.number());
    }
  }

  void order_sections() {
    std::vector<double> key(sections_.size());
    bool numeric = true;
    for (size_t i = 0; i < sections_.size() && numeric; ++i)
      numeric = parse_strict_double(sections_[i].id, key[i]) == NumberKind::ok;
    std::vector<size_t> perm(sections_.size());
    for (size_t i = 0; i < perm.size(); ++i)
      perm[i] = i;
    if (numeric) {
      std::stable_sort(perm.begin(), perm.end(),
                       [&](size_t a, size_t b) { return key[a] < key[b]; });
      for (size_t i = 1; i < perm.size(); ++i) {
        const RawSection& a = sections_[perm[i - 1]];
        const RawSection& b = sections_[perm[i]];
        if (key[perm[i - 1]] == key[perm[i]])
          fail(0, "section ids " + quote(a.id) + " (line " + std::to_string(a.first_line) +
                      ") and " + quote(b.id) + " (line " + std::to_string(b.first_line) +
                      ") have the same numeric value");
      }
    } else {
      std::sort(perm.begin(), perm.end(),
                [&](size_t a, size_t b) { return sections_[a].id < sections_[b].id; });
    }
    std::vector<RawSection> sorted;
    sorted.reserve(sections_.size());
    for (size_t i : perm)
      sorted.push_back(std::move(sections_[i]));
    sections_ = std::move(sorted);
  }

  static bool same(const RawPoint& a, const RawPoint& b) {
    return a.x == b.x && a.y == b.y && a.z == b.z;
  }

  void warn(long line, const std::string& message) {
    out_.warnings.push_back(path_ + ":" + std::to_string(line) + ": " + message);
  }

  Section finish_section(RawSection& s) {
    auto& pts = s.points;
    if (index_col_ != npos) {
      std::stable_sort(pts.begin(), pts.end(),
                       [](const RawPoint& a, const RawPoint& b) { return a.index < b.index; });
      for (size_t i = 1; i < pts.size(); ++i)
        if (pts[i - 1].index == pts[i].index) {
          const auto [l0, l1] = std::minmax(pts[i - 1].line, pts[i].line);
          fail(l1, "duplicate index " + std::to_string(pts[i].index) + " in section " + s.id +
                       " (also on line " + std::to_string(l0) + ")");
        }
    }
    std::vector<RawPoint> kept;
    kept.reserve(pts.size());
    for (const RawPoint& p : pts) {
      if (!kept.empty() && same(kept.back(), p)) {
        warn(p.line, "point identical to the previous point of section " + s.id + " (line " +
                         std::to_string(kept.back().line) + "); dropped");
        continue;
      }
      kept.push_back(p);
    }
    if (kept.size() > 1 && same(kept.front(), kept.back())) {
      warn(kept.back().line, "last point of section " + s.id + " repeats its first point (line " +
                                 std::to_string(kept.front().line) +
                                 "); dropped (sections are closed implicitly)");
      kept.pop_back();
    }
    if (kept.size() < 4)
      fail(s.first_line, "section " + s.id + " has " + std::to_string(kept.size()) +
                             " distinct point(s) after dropping repeated points; need at least 4");
    Section r;
    r.id = s.id;
    r.points.resize(static_cast<Eigen::Index>(kept.size()), 3);
    r.lines.resize(kept.size());
    for (size_t i = 0; i < kept.size(); ++i) {
      const auto row = static_cast<Eigen::Index>(i);
      r.points(row, 0) = kept[i].x;
      r.points(row, 1) = kept[i].y;
      r.points(row, 2) = kept[i].z;
      r.lines[i] = kept[i].line;
    }
    return r;
  }

  SectionSet finish() {
    if (sections_.empty())
      fail(0, "no data rows after the header on line " + std::to_string(header_line_));
    order_sections();
    out_.path = path_;
    std::vector<long> first_lines;
    for (RawSection& s : sections_) {
      out_.sections.push_back(finish_section(s));
      first_lines.push_back(s.first_line);
    }
    if (out_.sections.size() < 2)
      fail(0, "need at least 2 sections, found " + std::to_string(out_.sections.size()));
    for (size_t i = 0; i < out_.sections.size(); ++i)
      for (size_t j = i + 1; j < out_.sections.size(); ++j) {
        const Section& a = out_.sections[i];
        const Section& b = out_.sections[j];
        if (a.points.rows() == b.points.rows() && a.points == b.points)
          fail(0, "sections " + a.id + " (line " + std::to_string(first_lines[i]) + ") and " +
                      b.id + " (line " + std::to_string(first_lines[j]) + ") are identical");
      }
    return std::move(out_);
  }

  static constexpr size_t npos = static_cast<size_t>(-1);

  std::string path_;
  bool csv_ = false, header_ = false;
  long header_line_ = 0;
  size_t ncol_ = 3, sec_col_ = npos, index_col_ = npos;
  std::array<size_t, 3> col_{0, 1, 2};
  std::vector<string_view> fields_;
  std::vector<RawSection> sections_;
  SectionSet out_;
};

} // namespace

SectionSet parse_sections(std::istream& in, const std::string& path_for_messages) {
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  return Parser(path_for_messages).parse(text);
}

SectionSet read_sections(const std::string& path) {
  return Parser(path).parse(read_input_file(path));
}

void write_sections_csv(const std::string& path, const std::vector<Section>& sections) {
  for (const Section& s : sections) {
    const string_view id = s.id;
    if (id.empty() || id.find_first_of(",\n\r") != string_view::npos || trim(id) != id ||
        id.front() == '#')
      throw std::invalid_argument("write_sections_csv: section id '" + s.id +
                                  "' is empty, has a comma, a line break, surrounding spaces or a "
                                  "leading '#'");
    if (s.points.cols() != 3)
      throw std::invalid_argument("write_sections_csv: section " + s.id +
                                  ": points must be #P by 3");
    if (!s.points.allFinite())
      throw std::invalid_argument("write_sections_csv: section " + s.id +
                                  ": points must be finite");
  }
  write_file_atomically(path, [&](std::ostream& out) {
    std::string text = "section,index,x,y,z\n";
    char buf[64];
    for (const Section& s : sections)
      for (Eigen::Index i = 0; i < s.points.rows(); ++i) {
        text += s.id;
        text += ',';
        text += std::to_string(i);
        for (int k = 0; k < 3; ++k) {
          // Same digits as printf("%.17g") in the C locale: 17 significant digits round-trip.
          const auto r =
              std::to_chars(buf, buf + sizeof buf, s.points(i, k), std::chars_format::general, 17);
          text += ',';
          text.append(buf, r.ptr);
        }
        text += '\n';
      }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

} // namespace interlin
