// PLY and OBJ in full double precision (mesh_formats.h).
#include "mesh_formats.h"

#include "interlin/reconstruction/io/mesh_io.h"

#include "interlin/reconstruction/io/csv_fields.h"

#include "interlin/reconstruction/io/input_error.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <ostream>
#include <vector>

namespace interlin::detail {

namespace {

using std::string_view;

// ------------------------------------------------------------------------------ writing --

// Appends the bytes of `v` in little-endian order.
template <class T>
void put_le(std::string& out, T v) {
  std::array<char, sizeof(T)> b;
  std::memcpy(b.data(), &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big)
    std::reverse(b.begin(), b.end());
  out.append(b.data(), b.size());
}

// The shortest decimal that reads back to `v` (as a double, or as a float).
void put_number(std::string& out, double v, bool double_precision) {
  char buf[32];
  const auto r = double_precision ? std::to_chars(buf, buf + sizeof buf, v)
                                  : std::to_chars(buf, buf + sizeof buf, static_cast<float>(v));
  out.append(buf, r.ptr);
}

} // namespace

void write_ply(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
               bool double_precision) {
  const char* type = double_precision ? "double" : "float";
  std::string s = "ply\nformat binary_little_endian 1.0\ncomment interlin\nelement vertex " +
                  std::to_string(V.rows()) + "\n";
  for (const char* axis : {"x", "y", "z"})
    s += std::string("property ") + type + " " + axis + "\n";
  s += "element face " + std::to_string(F.rows()) +
       "\nproperty list uchar int vertex_indices\nend_header\n";
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      double_precision ? put_le(s, V(i, k)) : put_le(s, static_cast<float>(V(i, k)));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    s += static_cast<char>(3);
    for (int k = 0; k < 3; ++k)
      put_le(s, static_cast<std::int32_t>(F(f, k)));
  }
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

void write_obj(std::ostream& out, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
               bool double_precision) {
  std::string s = "# interlin\n";
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    s += "v";
    for (int k = 0; k < 3; ++k) {
      s += ' ';
      put_number(s, V(i, k), double_precision);
    }
    s += '\n';
  }
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    s += "f " + std::to_string(F(f, 0) + 1) + " " + std::to_string(F(f, 1) + 1) + " " +
         std::to_string(F(f, 2) + 1) + "\n";
  out.write(s.data(), static_cast<std::streamsize>(s.size()));
}

// ------------------------------------------------------------------------------ reading --

namespace {

// A PLY list length or index as read (any PLY scalar type, held as a double) for an error
// message: shortest round-trip text, since casting one beyond long long's range is undefined.
std::string scalar_text(double v) {
  std::string out;
  put_number(out, v, true);
  return out;
}

// Triangles of a polygon as a fan from its first corner.
void add_fan(const std::vector<long>& corners, std::vector<std::array<int, 3>>& tris) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k)
    tris.push_back({static_cast<int>(corners[0]), static_cast<int>(corners[k]),
                    static_cast<int>(corners[k + 1])});
}

void to_matrices(const std::vector<double>& xyz, const std::vector<std::array<int, 3>>& tris,
                 Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  V.resize(static_cast<Eigen::Index>(xyz.size() / 3), 3);
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    for (int k = 0; k < 3; ++k)
      V(i, k) = xyz[static_cast<std::size_t>(3 * i + k)];
  F.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      F(f, k) = tris[static_cast<std::size_t>(f)][static_cast<std::size_t>(k)];
}

// Splits `line` at blanks into `out`.
void split_blanks(string_view line, std::vector<string_view>& out) {
  out.clear();
  line = trim(line);
  while (!line.empty()) {
    std::size_t e = 0;
    while (e < line.size() && !is_blank(line[e]))
      ++e;
    out.push_back(line.substr(0, e));
    line = trim(line.substr(e));
  }
}

// ---- PLY

// Vertex indices are int (Eigen::MatrixXi).
constexpr long long kMaxIndex = std::numeric_limits<int>::max();

enum class Scalar { int8, uint8, int16, uint16, int32, uint32, float32, float64 };

bool scalar_of(string_view name, Scalar& s) {
  static const std::pair<const char*, Scalar> names[] = {
      {"char", Scalar::int8},      {"int8", Scalar::int8},       {"uchar", Scalar::uint8},
      {"uint8", Scalar::uint8},    {"short", Scalar::int16},     {"int16", Scalar::int16},
      {"ushort", Scalar::uint16},  {"uint16", Scalar::uint16},   {"int", Scalar::int32},
      {"int32", Scalar::int32},    {"uint", Scalar::uint32},     {"uint32", Scalar::uint32},
      {"float", Scalar::float32},  {"float32", Scalar::float32}, {"double", Scalar::float64},
      {"float64", Scalar::float64}};
  for (const auto& [n, v] : names)
    if (name == n) {
      s = v;
      return true;
    }
  return false;
}

std::size_t scalar_size(Scalar s) {
  switch (s) {
  case Scalar::int8:
  case Scalar::uint8:
    return 1;
  case Scalar::int16:
  case Scalar::uint16:
    return 2;
  case Scalar::float64:
    return 8;
  default:
    return 4;
  }
}

struct PlyProperty {
  std::string name;
  Scalar type = Scalar::float32; // the value, or the list items
  bool list = false;
  Scalar count_type = Scalar::uint8;
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> props;
};

enum class PlyFormat { ascii, little, big };

// Reads the values of a PLY body, binary or ASCII, with bounds checks.
class PlyData {
public:
  // `first_line`: the line number of the body's first line (ASCII messages name lines).
  PlyData(string_view body, PlyFormat format, const std::string& path, long first_line)
      : body_(body), format_(format), path_(path), line_(first_line) {}

  double scalar(Scalar type) {
    if (format_ == PlyFormat::ascii)
      return ascii_number();
    const std::size_t n = scalar_size(type);
    if (pos_ + n > body_.size())
      fail("the data ends before the elements the header declares (truncated?)");
    std::array<unsigned char, 8> b{};
    std::memcpy(b.data(), body_.data() + pos_, n);
    pos_ += n;
    if ((format_ == PlyFormat::big) != (std::endian::native == std::endian::big))
      std::reverse(b.begin(), b.begin() + static_cast<long>(n));
    switch (type) {
    case Scalar::int8:
      return static_cast<double>(static_cast<std::int8_t>(b[0]));
    case Scalar::uint8:
      return b[0];
    case Scalar::int16:
      return from_bytes<std::int16_t>(b);
    case Scalar::uint16:
      return from_bytes<std::uint16_t>(b);
    case Scalar::int32:
      return from_bytes<std::int32_t>(b);
    case Scalar::uint32:
      return from_bytes<std::uint32_t>(b);
    case Scalar::float32:
      return from_bytes<float>(b);
    case Scalar::float64:
      return from_bytes<double>(b);
    }
    return 0;
  }
  // ASCII: the rest of the current element's line must be empty.
  void end_element() {
    if (format_ != PlyFormat::ascii)
      return;
    while (pos_ < body_.size() && body_[pos_] != '\n') {
      if (!is_blank(body_[pos_]))
        fail("more values on an element line than its properties");
      ++pos_;
    }
    pos_ = std::min(pos_ + 1, body_.size()); // past the '\n'; the last line may lack one
    ++line_;
  }
  std::size_t remaining() const { return body_.size() - std::min(pos_, body_.size()); }
  // "PATH:LINE: what" in ASCII bodies, "PATH: what" in binary ones.
  [[noreturn]] void fail(const std::string& what) const {
    throw_input_error(path_, format_ == PlyFormat::ascii ? line_ : 0, what);
  }
  bool ascii() const { return format_ == PlyFormat::ascii; }

private:
  template <class T>
  static double from_bytes(const std::array<unsigned char, 8>& b) {
    T v;
    std::memcpy(&v, b.data(), sizeof(T));
    return static_cast<double>(v);
  }
  double ascii_number() {
    while (pos_ < body_.size() && is_blank(body_[pos_]))
      ++pos_;
    std::size_t e = pos_;
    while (e < body_.size() && !is_blank(body_[e]) && body_[e] != '\n')
      ++e;
    double v = 0;
    if (parse_strict_double(body_.substr(pos_, e - pos_), v) != NumberKind::ok)
      fail(e == pos_
               ? "a line ends before the properties its element declares"
               : "'" + std::string(body_.substr(pos_, e - pos_)) + "' is not a finite number");
    pos_ = e;
    return v;
  }

  string_view body_;
  PlyFormat format_;
  const std::string& path_;
  long line_;
  std::size_t pos_ = 0;
};

// The header: format and elements; `body` receives the bytes after "end_header\n" and
// `end_line` the number of the end_header line.
std::vector<PlyElement> ply_header(string_view text, const std::string& path, PlyFormat& format,
                                   string_view& body, long& end_line) {
  LineReader lines(text);
  string_view line;
  std::vector<string_view> w;
  if (!lines.next(line) || trim(line) != "ply")
    throw_input_error(path, 1, "not a PLY file (the first line is not 'ply')");
  std::vector<PlyElement> elements;
  bool has_format = false;
  while (lines.next(line)) {
    const long n = lines.number();
    split_blanks(line, w);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info")
      continue;
    if (w[0] == "end_header") {
      if (!has_format)
        throw_input_error(path, n, "the header has no format line");
      end_line = n;
      const std::size_t at = static_cast<std::size_t>(line.data() - text.data()) + line.size();
      body = text.substr(std::min(text.size(), at + (text.substr(at, 1) == "\r" ? 2 : 1)));
      return elements;
    }
    if (w[0] == "format") {
      if (w.size() != 3 || w[2] != "1.0")
        throw_input_error(path, n,
                          "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      if (w[1] == "ascii")
        format = PlyFormat::ascii;
      else if (w[1] == "binary_little_endian")
        format = PlyFormat::little;
      else if (w[1] == "binary_big_endian")
        format = PlyFormat::big;
      else
        throw_input_error(path, n, "unknown PLY format '" + std::string(w[1]) + "'");
      has_format = true;
    } else if (w[0] == "element") {
      unsigned long long count = 0;
      const auto r = w.size() == 3 ? std::from_chars(w[2].data(), w[2].data() + w[2].size(), count)
                                   : std::from_chars_result{nullptr, std::errc::invalid_argument};
      if (r.ec != std::errc() || r.ptr != w[2].data() + w[2].size())
        throw_input_error(path, n, "expected 'element NAME COUNT'");
      elements.push_back({std::string(w[1]), count, {}});
    } else if (w[0] == "property") {
      if (elements.empty())
        throw_input_error(path, n, "a property before any element");
      PlyProperty p;
      const bool ok = w.size() == 3 ? scalar_of(w[1], p.type)
                      : w.size() == 5
                          ? w[1] == "list" && scalar_of(w[2], p.count_type) &&
                                scalar_of(w[3], p.type) && p.count_type != Scalar::float32 &&
                                p.count_type != Scalar::float64
                          : false;
      if (!ok)
        throw_input_error(path, n,
                          "expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME' "
                          "with PLY scalar types (integer count type)");
      p.list = w.size() == 5;
      p.name = std::string(w.back());
      elements.back().props.push_back(p);
    } else {
      throw_input_error(path, n, "unknown header line '" + std::string(trim(line)) + "'");
    }
  }
  throw_input_error(path, 0, "the header does not end (no 'end_header' line)");
}

// The fewest bytes one element can take: what the header's counts are checked against.
std::size_t min_element_bytes(const PlyElement& e, PlyFormat format) {
  if (format == PlyFormat::ascii) // one character and a separator per value (a list: its count)
    return std::max<std::size_t>(1, 2 * e.props.size());
  std::size_t b = 0;
  for (const PlyProperty& p : e.props)
    b += scalar_size(p.list ? p.count_type : p.type);
  return std::max<std::size_t>(1, b);
}

// Counts against the file size before anything is allocated: a header may declare billions.
void check_counts(const std::vector<PlyElement>& elements, PlyFormat format, string_view body,
                  const std::string& path) {
  unsigned long long need = 0;
  for (const PlyElement& e : elements) {
    if (e.name == "vertex" && e.count > static_cast<unsigned long long>(kMaxIndex))
      throw_input_error(path, 0, "more than " + std::to_string(kMaxIndex) + " vertices");
    const unsigned long long per = min_element_bytes(e, format);
    if (e.count > (std::numeric_limits<unsigned long long>::max() - need) / per ||
        (need += e.count * per) > body.size())
      throw_input_error(path, 0,
                        "the header declares " + std::to_string(e.count) + " " + e.name +
                            " elements, more than the " + std::to_string(body.size()) +
                            " bytes after the header can hold");
  }
}

// Reads one element instance: its scalar properties into `scalars` (when not null), lists
// skipped with their lengths checked against the data.
void read_instance(PlyData& data, const PlyElement& e, std::uint64_t i,
                   std::vector<double>* scalars) {
  for (std::size_t k = 0; k < e.props.size(); ++k) {
    const PlyProperty& prop = e.props[k];
    if (!prop.list) {
      const double v = data.scalar(prop.type);
      if (scalars)
        (*scalars)[k] = v;
      continue;
    }
    const double n = data.scalar(prop.count_type);
    if (!(n >= 0) || n != std::floor(n) || n > static_cast<double>(data.remaining()))
      data.fail(e.name + " " + std::to_string(i) + ": list length " + scalar_text(n) +
                " beyond the data");
    for (long c = 0; c < static_cast<long>(n); ++c)
      data.scalar(prop.type);
  }
  data.end_element();
}

} // namespace

void parse_ply(string_view text, const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  PlyFormat format = PlyFormat::ascii;
  string_view body;
  long end_line = 0;
  const std::vector<PlyElement> elements = ply_header(text, path, format, body, end_line);
  check_counts(elements, format, body, path);
  PlyData data(body, format, path, end_line + 1);
  std::vector<double> xyz;
  std::vector<std::array<int, 3>> tris;
  std::vector<long> corners;
  bool has_vertex = false;
  for (const PlyElement& e : elements) {
    int axis[3] = {-1, -1, -1}, indices = -1;
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const PlyProperty& p = e.props[k];
      for (int a = 0; a < 3; ++a)
        if (!p.list && p.name == std::string(1, static_cast<char>('x' + a)))
          axis[a] = static_cast<int>(k);
      if (p.list && (p.name == "vertex_indices" || p.name == "vertex_index"))
        indices = static_cast<int>(k);
    }
    const bool vertex = e.name == "vertex", face = e.name == "face";
    if (vertex && (axis[0] < 0 || axis[1] < 0 || axis[2] < 0))
      data.fail("the vertex element lacks the property x, y or z");
    if (face && indices < 0)
      data.fail("the face element lacks the list property vertex_indices");
    has_vertex = has_vertex || vertex;
    if (vertex)
      xyz.reserve(3 * e.count);
    for (std::uint64_t i = 0; i < e.count; ++i) {
      double p[3] = {0, 0, 0};
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const PlyProperty& prop = e.props[k];
        if (!prop.list) {
          const double v = data.scalar(prop.type);
          for (int a = 0; a < 3; ++a)
            if (axis[a] == static_cast<int>(k))
              p[a] = v;
          continue;
        }
        const double n = data.scalar(prop.count_type);
        if (!(n >= 0) || n != std::floor(n) || n > static_cast<double>(data.remaining()))
          data.fail(e.name + " " + std::to_string(i) + ": list length " + scalar_text(n) +
                    " beyond the data");
        corners.clear();
        for (long c = 0; c < static_cast<long>(n); ++c) {
          const double idx = data.scalar(prop.type);
          if (face && static_cast<int>(k) == indices) {
            if (!(idx >= 0 && idx < static_cast<double>(xyz.size() / 3)) || idx != std::floor(idx))
              data.fail("face " + std::to_string(i) + ": vertex index " + scalar_text(idx) +
                        " outside [0, " + std::to_string(xyz.size() / 3) + ")");
            corners.push_back(static_cast<long>(idx));
          }
        }
        if (face && static_cast<int>(k) == indices) {
          if (corners.size() < 3)
            data.fail("face " + std::to_string(i) + " has fewer than 3 vertices");
          add_fan(corners, tris);
        }
      }
      data.end_element();
      if (vertex) {
        if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
          data.fail("vertex " + std::to_string(i) + " is not finite");
        xyz.insert(xyz.end(), p, p + 3);
      }
    }
  }
  if (!has_vertex)
    data.fail("no vertex element");
  to_matrices(xyz, tris, V, F);
}

void parse_obj(string_view text, const std::string& path, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  LineReader lines(text);
  string_view line;
  std::vector<string_view> w;
  std::vector<double> xyz;
  std::vector<std::array<int, 3>> tris;
  std::vector<long> corners;
  while (lines.next(line)) {
    const long n = lines.number();
    split_blanks(line, w);
    if (w.empty())
      continue;
    if (w[0] == "v") {
      if (w.size() != 4 && w.size() != 5)
        throw_input_error(path, n, "expected 'v x y z' (or 'v x y z w')");
      if (static_cast<long long>(xyz.size() / 3) >= kMaxIndex)
        throw_input_error(path, n, "more than " + std::to_string(kMaxIndex) + " vertices");
      for (int k = 0; k < 3; ++k)
        xyz.push_back(field_number(w[static_cast<std::size_t>(k + 1)], path, n,
                                   k == 0   ? "x"
                                   : k == 1 ? "y"
                                            : "z"));
    } else if (w[0] == "f") {
      if (w.size() < 4)
        throw_input_error(path, n, "a face needs at least 3 vertices");
      corners.clear();
      const long count = static_cast<long>(xyz.size() / 3);
      for (std::size_t k = 1; k < w.size(); ++k) {
        const string_view ref = w[k].substr(0, w[k].find('/')); // a/t/n: the vertex is a
        long idx = 0;
        if (!parse_strict_long(ref, idx) || idx == 0 || idx > count || idx < -count)
          throw_input_error(path, n,
                            "vertex reference '" + std::string(w[k]) + "' is not in 1.." +
                                std::to_string(count) + " (or -1..-" + std::to_string(count) + ")");
        corners.push_back(idx > 0 ? idx - 1 : count + idx);
      }
      add_fan(corners, tris);
    }
  }
  if (xyz.empty())
    throw_input_error(path, 0, "no vertex ('v' line)");
  to_matrices(xyz, tris, V, F);
}

} // namespace interlin::detail

namespace interlin {

Eigen::MatrixXd parse_ply_vertices(std::string_view text, const std::string& path,
                                   const std::vector<std::string>& names,
                                   std::vector<bool>& found) {
  using namespace detail;
  PlyFormat format = PlyFormat::ascii;
  std::string_view body;
  long end_line = 0;
  const std::vector<PlyElement> elements = ply_header(text, path, format, body, end_line);
  check_counts(elements, format, body, path);
  PlyData data(body, format, path, end_line + 1);
  for (const PlyElement& e : elements) {
    if (e.name != "vertex") {
      for (std::uint64_t i = 0; i < e.count && !e.props.empty(); ++i)
        read_instance(data, e, i, nullptr);
      continue;
    }
    std::vector<int> col(names.size(), -1);
    found.assign(names.size(), false);
    for (std::size_t k = 0; k < e.props.size(); ++k)
      for (std::size_t c = 0; c < names.size(); ++c)
        if (!e.props[k].list && e.props[k].name == names[c]) {
          col[c] = static_cast<int>(k);
          found[c] = true;
        }
    Eigen::MatrixXd out(static_cast<Eigen::Index>(e.count),
                        static_cast<Eigen::Index>(names.size()));
    std::vector<double> scalars(e.props.size());
    for (std::uint64_t i = 0; i < e.count; ++i) {
      read_instance(data, e, i, &scalars);
      for (std::size_t c = 0; c < names.size(); ++c)
        out(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) =
            col[c] >= 0 ? scalars[static_cast<std::size_t>(col[c])] : 0.0;
    }
    return out;
  }
  data.fail("no vertex element");
}

} // namespace interlin
