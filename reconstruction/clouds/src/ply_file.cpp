// PLY files: the header is parsed and validated here; the vertex element of ASCII files is
// parsed strictly here; binary payloads are decoded by PCL once the header has been checked
// against the file size. Faces and other elements are ignored (a mesh's vertices are a cloud).
#include "cloud_formats.h"

#include "interlin/reconstruction/io/csv_fields.h"
#include "interlin/reconstruction/io/input_error.h"

#include <cmath>
#include <map>

namespace interlin::detail {

namespace {

struct PlyProperty {
  std::string name;
  int size = 4;       // bytes of a scalar, or of the list items
  int count_size = 0; // lists: bytes of the item count (0 for scalars)
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

int type_size(std::string_view t) {
  static const std::map<std::string, int, std::less<>> sizes{
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

int checked_type(std::string_view t, const std::string& path, long line) {
  const int s = type_size(t);
  if (s == 0)
    throw_input_error(path, line, "unknown PLY property type '" + std::string(t) + "'");
  return s;
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
        p.count_size = checked_type(t[2], path, n);
        p.size = checked_type(t[3], path, n);
        p.name = std::string(t[4]);
      } else if (t.size() == 3) {
        p.size = checked_type(t[1], path, n);
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

void read_binary_vertices(const std::string& path, std::string_view text, const PlyHeader& h,
                          size_t vertex, CloudRows& rows) {
  // Smallest payload that can hold every element up to the vertices (lists counted empty).
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
  std::vector<std::string> names{"x", "y", "z"};
  if (normals)
    names.insert(names.end(), {"normal_x", "normal_y", "normal_z"});
  const Eigen::MatrixXd F = pcl_binary_fields(path, true, names);
  if (F.rows() != v.count)
    throw_input_error(path, 0,
                      "PCL decoded " + std::to_string(F.rows()) +
                          " vertices, the header declares " + std::to_string(v.count));
  rows.with_normals = normals;
  for (Eigen::Index i = 0; i < F.rows(); ++i) {
    double val[6];
    for (Eigen::Index c = 0; c < F.cols(); ++c)
      val[c] = F(i, c);
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(val[c]))
        throw_input_error(path, 0,
                          "vertex " + std::to_string(i + 1) + " (binary data): " + names[c] +
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
