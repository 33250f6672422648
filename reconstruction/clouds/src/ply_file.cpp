// PLY files: the header parsed and validated; the vertex element of ASCII files parsed strictly;
// binary payloads decoded with every read bounds-checked, after the header's counts have been
// checked against the payload size. Faces and other elements are skipped (a mesh's vertices are
// a cloud).
#include "cloud_formats.h"

#include "interlin/reconstruction/io/csv_fields.h"
#include "interlin/reconstruction/io/input_error.h"

#include <cmath>
#include <map>

namespace interlin::detail {

namespace {

struct PlyProperty {
  std::string name;
  int size = 4;          // bytes of a scalar, or of the list items
  char type = 'F';       // 'F' float, 'I' signed, 'U' unsigned (binary_value)
  int count_size = 0;    // lists: bytes of the item count (0 for scalars) ...
  char count_type = 'U'; // ... and its type
};

struct PlyElement {
  std::string name;
  long count = 0, line = 0;
  std::vector<PlyProperty> props;
  int find(const std::string& n) const {
    for (size_t i = 0; i < props.size(); ++i)
      if (props[i].name == n && props[i].count_size == 0)
        return static_cast<int>(i);
    return -1;
  }
};

struct PlyHeader {
  std::string format;
  std::vector<PlyElement> elements;
  size_t payload = 0;
  long end_line = 0;
};

// Bytes and kind ('F', 'I', 'U') of a PLY type name; false for an unknown name.
bool type_of(std::string_view t, int& size, char& kind) {
  static const std::map<std::string, std::pair<int, char>, std::less<>> types{
      {"char", {1, 'I'}},  {"uchar", {1, 'U'}},   {"int8", {1, 'I'}},   {"uint8", {1, 'U'}},
      {"short", {2, 'I'}}, {"ushort", {2, 'U'}},  {"int16", {2, 'I'}},  {"uint16", {2, 'U'}},
      {"int", {4, 'I'}},   {"uint", {4, 'U'}},    {"int32", {4, 'I'}},  {"uint32", {4, 'U'}},
      {"float", {4, 'F'}}, {"float32", {4, 'F'}}, {"double", {8, 'F'}}, {"float64", {8, 'F'}}};
  const auto it = types.find(t);
  if (it == types.end())
    return false;
  size = it->second.first;
  kind = it->second.second;
  return true;
}

void checked_type(std::string_view t, const std::string& path, long line, int& size, char& kind) {
  if (!type_of(t, size, kind))
    throw_input_error(path, line, "unknown PLY property type '" + std::string(t) + "'");
}

PlyHeader parse_header(const std::string& path, std::string_view text) {
  PlyHeader h;
  LineReader lines(text);
  std::string_view line;
  std::vector<std::string_view> t;
  if (!lines.next(line) || trim(line) != "ply")
    throw_input_error(path, 1, "not a PLY file: the first line must be 'ply'");
  while (h.end_line == 0 && lines.next(line)) {
    const long n = lines.number();
    split_plain(trim(line), t);
    if (t.empty())
      continue;
    const std::string_view key = t[0];
    if (key == "comment" || key == "obj_info") {
      continue;
    } else if (key == "format") {
      if (t.size() != 3 ||
          (t[1] != "ascii" && t[1] != "binary_little_endian" && t[1] != "binary_big_endian"))
        throw_input_error(path, n,
                          "format must be 'format ascii|binary_little_endian|binary_big_endian "
                          "1.0'");
      h.format = std::string(t[1]);
    } else if (key == "element") {
      long count = 0;
      if (t.size() != 3 || !parse_strict_long(t[2], count) || count < 0)
        throw_input_error(path, n, "element takes a name and a non-negative count");
      h.elements.push_back({std::string(t[1]), count, n, {}});
    } else if (key == "property") {
      if (h.elements.empty())
        throw_input_error(path, n, "property before any element");
      PlyProperty p;
      if (t.size() == 5 && t[1] == "list") {
        checked_type(t[2], path, n, p.count_size, p.count_type);
        checked_type(t[3], path, n, p.size, p.type);
        if (p.count_type == 'F')
          throw_input_error(path, n, "a list's length type must be an integer type");
        p.name = std::string(t[4]);
      } else if (t.size() == 3) {
        checked_type(t[1], path, n, p.size, p.type);
        p.name = std::string(t[2]);
      } else {
        throw_input_error(path, n, "property takes a type and a name (or list COUNT ITEM NAME)");
      }
      h.elements.back().props.push_back(p);
    } else if (key == "end_header") {
      h.end_line = n;
    } else {
      throw_input_error(path, n, "unknown PLY header keyword '" + std::string(key) + "'");
    }
  }
  if (h.end_line == 0)
    throw_input_error(path, 0, "PLY header has no end_header line");
  if (h.format.empty())
    throw_input_error(path, h.end_line, "PLY header has no format line");
  h.payload = lines.position();
  return h;
}

// Scalar property indices of x, y, z and, when present, of the normal (nx ny nz or normal_x ...).
std::vector<int> wanted(const std::string& path, const PlyElement& v, bool& normals) {
  std::vector<int> w;
  for (const char* c : {"x", "y", "z"}) {
    w.push_back(v.find(c));
    if (w.back() < 0)
      throw_input_error(path, v.line, std::string("element vertex has no scalar property ") + c);
  }
  for (const auto& names : {std::vector<std::string>{"nx", "ny", "nz"},
                            std::vector<std::string>{"normal_x", "normal_y", "normal_z"}}) {
    std::vector<int> n;
    for (const std::string& c : names)
      if (v.find(c) >= 0)
        n.push_back(v.find(c));
    normals = n.size() == 3;
    if (normals) {
      w.insert(w.end(), n.begin(), n.end());
      return w;
    }
  }
  return w;
}

void read_ascii_vertices(const std::string& path, std::string_view text, const PlyHeader& h,
                         size_t vertex, CloudRows& rows) {
  const PlyElement& v = h.elements[vertex];
  bool normals = false;
  const std::vector<int> w = wanted(path, v, normals);
  rows.with_normals = normals;
  LineReader lines(text.substr(h.payload));
  std::string_view line;
  std::vector<std::string_view> t;
  long before = 0; // instances of the elements before the vertex element (one line each)
  for (size_t e = 0; e < vertex; ++e)
    if (!h.elements[e].props.empty())
      before += h.elements[e].count;
  long read = 0;
  while (read < v.count && lines.next(line)) {
    const long number = h.end_line + lines.number();
    if (trim(line).empty())
      continue;
    if (before > 0) {
      --before;
      continue;
    }
    split_plain(trim(line), t);
    std::vector<size_t> at(v.props.size()); // token index of each property
    size_t k = 0;
    for (size_t p = 0; p < v.props.size(); ++p) {
      at[p] = k;
      long items = 0;
      if (v.props[p].count_size > 0 &&
          (k >= t.size() || !parse_strict_long(t[k], items) || items < 0))
        throw_input_error(path, number, "property " + v.props[p].name + ": bad list length");
      k += 1 + static_cast<size_t>(items);
    }
    if (t.size() != k)
      throw_input_error(path, number,
                        "expected " + std::to_string(k) + " values for a vertex, found " +
                            std::to_string(t.size()));
    double val[6] = {0, 0, 0, 0, 0, 0};
    for (size_t c = 0; c < w.size(); ++c) {
      const std::string_view tok = t[at[static_cast<size_t>(w[c])]];
      const NumberKind kind = parse_strict_double(tok, val[c]);
      // non-finite normals are dropped later; everything else must be a finite number
      if (kind != NumberKind::ok && !(c >= 3 && kind == NumberKind::not_finite))
        field_number(tok, path, number, v.props[static_cast<size_t>(w[c])].name.c_str());
    }
    rows.add(val, val + 3);
    ++read;
  }
  if (read < v.count)
    throw_input_error(path, v.line,
                      "element vertex declares " + std::to_string(v.count) +
                          " vertices, the file holds " + std::to_string(read));
}

// Reads binary element instances from `data` at `at`, bounds-checked against the payload.
class BinaryCursor {
public:
  BinaryCursor(const std::string& path, std::string_view data, bool big)
      : path_(path), data_(data), big_(big) {}
  // Skips or reads one instance of e; values[p] receives scalar property p (lists skipped).
  void instance(const PlyElement& e, long index, std::vector<double>* values) {
    for (size_t p = 0; p < e.props.size(); ++p) {
      const PlyProperty& q = e.props[p];
      if (q.count_size == 0) {
        const double v = value(q.size, q.type, e, index);
        if (values)
          (*values)[p] = v;
        continue;
      }
      const double items = value(q.count_size, q.count_type, e, index);
      if (!(items >= 0))
        throw_input_error(path_, 0,
                          "element " + e.name + " " + std::to_string(index + 1) +
                              " (binary data): list " + q.name + " has a negative length");
      need(items * q.size, e, index);
      at_ += size_t(items) * size_t(q.size);
    }
  }

private:
  const std::string& path_;
  std::string_view data_;
  bool big_;
  size_t at_ = 0;
  void need(double bytes, const PlyElement& e, long index) const {
    if (bytes > double(data_.size() - at_))
      throw_input_error(path_, 0,
                        "element " + e.name + " " + std::to_string(index + 1) +
                            " (binary data): the file ends inside it");
  }
  double value(int size, char type, const PlyElement& e, long index) {
    need(size, e, index);
    const double v = binary_value(data_.data() + at_, type, size, big_);
    at_ += size_t(size);
    return v;
  }
};

void read_binary_vertices(const std::string& path, std::string_view text, const PlyHeader& h,
                          size_t vertex, CloudRows& rows) {
  // Smallest payload that can hold every element up to the vertices (lists counted empty):
  // checked before anything is allocated from the counts.
  double need = 0;
  for (size_t e = 0; e <= vertex; ++e) {
    double record = 0;
    for (const PlyProperty& p : h.elements[e].props)
      record += p.count_size > 0 ? p.count_size : p.size;
    need += double(h.elements[e].count) * record;
  }
  const PlyElement& v = h.elements[vertex];
  require_payload(path, v.line, "element vertex " + std::to_string(v.count), 1.0, need,
                  text.size() - h.payload);
  bool normals = false;
  const std::vector<int> w = wanted(path, v, normals);
  rows.with_normals = normals;
  BinaryCursor cursor(path, text.substr(h.payload), h.format == "binary_big_endian");
  for (size_t e = 0; e < vertex; ++e)
    for (long i = 0; i < h.elements[e].count && !h.elements[e].props.empty(); ++i)
      cursor.instance(h.elements[e], i, nullptr);
  std::vector<double> values(v.props.size());
  for (long i = 0; i < v.count; ++i) {
    cursor.instance(v, i, &values);
    double val[6] = {0, 0, 0, 0, 0, 0};
    for (size_t c = 0; c < w.size(); ++c)
      val[c] = values[static_cast<size_t>(w[c])];
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(val[c]))
        throw_input_error(path, 0,
                          "vertex " + std::to_string(i + 1) + " (binary data): " +
                              v.props[static_cast<size_t>(w[static_cast<size_t>(c)])].name +
                              " is not a finite value (NaN and infinity are not allowed)");
    rows.add(val, val + 3);
  }
}

} // namespace

void read_ply(const std::string& path, std::string_view text, CloudRows& rows,
              std::vector<std::string>& notes) {
  const PlyHeader h = parse_header(path, text);
  size_t vertex = h.elements.size();
  for (size_t e = 0; e < h.elements.size(); ++e)
    if (h.elements[e].name == "vertex")
      vertex = e;
  if (vertex == h.elements.size())
    throw_input_error(path, h.end_line, "PLY header has no element vertex");
  if (h.format == "ascii")
    read_ascii_vertices(path, text, h, vertex, rows);
  else
    read_binary_vertices(path, text, h, vertex, rows);
  if (h.elements.size() > 1)
    notes.push_back(path + ": only the vertices are read (other elements ignored)");
}

} // namespace interlin::detail
