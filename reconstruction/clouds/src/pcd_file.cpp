// PCD files (PCL's Point Cloud Data format, v0.5-v0.7): the header parsed and validated line by
// line, ASCII data parsed strictly, binary records decoded after the header has been checked
// against the payload size; binary_compressed blocks are decompressed by PCL's LZF codec.
#include "cloud_formats.h"

#include "interlin/reconstruction/io/csv_fields.h"
#include "interlin/reconstruction/io/input_error.h"

#include <pcl/io/lzf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace interlin::detail {

namespace {

struct PcdField {
  std::string name;
  int size = 4, count = 1;
  char type = 'F';
};

struct PcdHeader {
  std::vector<PcdField> fields;
  long width = -1, height = 1, points = -1;
  long fields_line = 0, points_line = 0, data_line = 0;
  std::string data;
  size_t payload = 0; // offset of the data in the file
  size_t record() const {
    size_t r = 0;
    for (const PcdField& f : fields)
      r += static_cast<size_t>(f.size) * static_cast<size_t>(f.count);
    return r;
  }
  int find(const std::string& name) const {
    for (size_t i = 0; i < fields.size(); ++i)
      if (fields[i].name == name)
        return static_cast<int>(i);
    return -1;
  }
};

std::string upper(std::string_view s) {
  std::string r(s);
  for (char& c : r)
    if (c >= 'a' && c <= 'z')
      c = static_cast<char>(c - 'a' + 'A');
  return r;
}

long header_count(std::string_view tok, const std::string& path, long line, const char* key) {
  long v = 0;
  if (!parse_strict_long(tok, v) || v < 0)
    throw_input_error(path, line,
                      std::string(key) + ": '" + std::string(tok) +
                          "' is not a non-negative integer");
  return v;
}

// One header line "KEY values...": stores what it says or throws.
void header_line(PcdHeader& h, const std::vector<std::string_view>& t, const std::string& path,
                 long line) {
  const std::string key = upper(t[0]);
  const size_t nv = t.size() - 1;
  auto per_field = [&](const char* what) {
    if (h.fields.empty())
      throw_input_error(path, line, key + " before FIELDS");
    if (nv != h.fields.size())
      throw_input_error(path, line,
                        key + " has " + std::to_string(nv) + " values for " +
                            std::to_string(h.fields.size()) + " fields (line " +
                            std::to_string(h.fields_line) + ")" + what);
  };
  if (key == "VERSION") {
    return;
  } else if (key == "FIELDS" || key == "COLUMNS") {
    if (nv == 0)
      throw_input_error(path, line, "FIELDS names no field");
    h.fields.assign(nv, PcdField{});
    for (size_t i = 0; i < nv; ++i)
      h.fields[i].name = std::string(t[i + 1]);
    h.fields_line = line;
  } else if (key == "SIZE") {
    per_field("");
    for (size_t i = 0; i < nv; ++i) {
      const long s = header_count(t[i + 1], path, line, "SIZE");
      if (s != 1 && s != 2 && s != 4 && s != 8)
        throw_input_error(path, line, "SIZE " + std::to_string(s) + " is not 1, 2, 4 or 8");
      h.fields[i].size = static_cast<int>(s);
    }
  } else if (key == "TYPE") {
    per_field("");
    for (size_t i = 0; i < nv; ++i) {
      const std::string ty = upper(t[i + 1]);
      if (ty != "F" && ty != "I" && ty != "U")
        throw_input_error(path, line, "TYPE '" + std::string(t[i + 1]) + "' is not F, I or U");
      h.fields[i].type = ty[0];
    }
  } else if (key == "COUNT") {
    per_field("");
    for (size_t i = 0; i < nv; ++i) {
      const long c = header_count(t[i + 1], path, line, "COUNT");
      if (c < 1 || c > 1'000'000)
        throw_input_error(path, line, "COUNT " + std::to_string(c) + " is out of [1, 1000000]");
      h.fields[i].count = static_cast<int>(c);
    }
  } else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS") {
    if (nv != 1)
      throw_input_error(path, line, key + " takes one value");
    const long v = header_count(t[1], path, line, key.c_str());
    (key == "WIDTH" ? h.width : key == "HEIGHT" ? h.height : h.points) = v;
    if (key == "POINTS")
      h.points_line = line;
  } else if (key == "VIEWPOINT") {
    return;
  } else if (key == "DATA") {
    if (nv != 1)
      throw_input_error(path, line, "DATA takes one value (ascii, binary or binary_compressed)");
    h.data = ascii_lower(t[1]);
    if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed")
      throw_input_error(
          path, line, "DATA '" + std::string(t[1]) + "' is not ascii, binary or binary_compressed");
    h.data_line = line;
  } else {
    throw_input_error(path, line, "unknown PCD header keyword '" + std::string(t[0]) + "'");
  }
}

// The header up to and including DATA, checked for consistency.
PcdHeader parse_header(const std::string& path, std::string_view text) {
  PcdHeader h;
  LineReader lines(text);
  std::string_view line;
  std::vector<std::string_view> t;
  bool any = false;
  while (h.data_line == 0 && lines.next(line)) {
    const std::string_view s = trim(line);
    if (s.empty() || s.front() == '#')
      continue;
    split_plain(s, t);
    if (!any && upper(t[0]) != "VERSION" && upper(t[0]) != "FIELDS")
      throw_input_error(path, lines.number(),
                        "not a PCD file: expected the header to start with VERSION or FIELDS");
    any = true;
    header_line(h, t, path, lines.number());
  }
  if (h.data_line == 0)
    throw_input_error(path, 0, any ? "PCD header has no DATA line" : "empty file");
  h.payload = lines.position();
  if (h.fields.empty())
    throw_input_error(path, h.data_line, "PCD header has no FIELDS line");
  for (const PcdField& f : h.fields)
    if (f.type == 'F' && f.size != 4 && f.size != 8)
      throw_input_error(path, h.fields_line,
                        "field " + f.name + ": floating-point fields have SIZE 4 or 8");
  for (const char* c : {"x", "y", "z"}) {
    const int i = h.find(c);
    if (i < 0)
      throw_input_error(path, h.fields_line, std::string("FIELDS lacks ") + c);
    if (h.fields[static_cast<size_t>(i)].count != 1)
      throw_input_error(path, h.fields_line, std::string("field ") + c + " must have COUNT 1");
  }
  if (h.width < 0)
    throw_input_error(path, h.data_line, "PCD header has no WIDTH line");
  if (h.height < 1)
    throw_input_error(path, h.data_line, "HEIGHT must be at least 1");
  const double wh = double(h.width) * double(h.height);
  if (h.points < 0)
    h.points = static_cast<long>(wh);
  else if (double(h.points) != wh)
    throw_input_error(path, h.points_line,
                      "POINTS " + std::to_string(h.points) + " differs from WIDTH x HEIGHT = " +
                          std::to_string(h.width) + " x " + std::to_string(h.height));
  return h;
}

// Token index of each field's first value in an ASCII data line.
std::vector<size_t> token_offsets(const PcdHeader& h) {
  std::vector<size_t> o(h.fields.size());
  size_t k = 0;
  for (size_t i = 0; i < h.fields.size(); ++i) {
    o[i] = k;
    k += static_cast<size_t>(h.fields[i].count);
  }
  return o;
}

// The wanted fields: x, y, z and, when all present with COUNT 1, the normal components.
std::vector<int> wanted_fields(const PcdHeader& h, bool& normals) {
  std::vector<int> w{h.find("x"), h.find("y"), h.find("z")};
  const std::vector<int> n{h.find("normal_x"), h.find("normal_y"), h.find("normal_z")};
  normals = std::all_of(n.begin(), n.end(), [&](int i) {
    return i >= 0 && h.fields[static_cast<size_t>(i)].count == 1;
  });
  if (normals)
    w.insert(w.end(), n.begin(), n.end());
  return w;
}

// Organised clouds (HEIGHT > 1) mark missing measurements with NaN coordinates: such points are
// skipped. Anything else non-finite is an error.
bool skip_invalid(const PcdHeader& h, const double* p) {
  return h.height > 1 && std::isnan(p[0]) && std::isnan(p[1]) && std::isnan(p[2]);
}

void read_ascii(const std::string& path, std::string_view text, const PcdHeader& h, CloudRows& rows,
                long& skipped) {
  bool normals = false;
  const std::vector<int> w = wanted_fields(h, normals);
  rows.with_normals = normals;
  const std::vector<size_t> off = token_offsets(h);
  const size_t tokens = off.back() + static_cast<size_t>(h.fields.back().count);
  LineReader lines(text.substr(h.payload));
  std::string_view line;
  std::vector<std::string_view> t;
  long read = 0;
  while (lines.next(line)) {
    const long number = h.data_line + lines.number();
    const std::string_view s = trim(line);
    if (s.empty())
      continue;
    if (read == h.points)
      throw_input_error(path, number,
                        "more data lines than POINTS " + std::to_string(h.points) + " (line " +
                            std::to_string(h.points_line) + ")");
    split_plain(s, t);
    if (t.size() != tokens)
      throw_input_error(path, number,
                        "expected " + std::to_string(tokens) + " values (FIELDS, COUNT), found " +
                            std::to_string(t.size()));
    ++read;
    double v[6] = {0, 0, 0, 0, 0, 0};
    for (size_t c = 0; c < w.size(); ++c) {
      const PcdField& f = h.fields[static_cast<size_t>(w[c])];
      const std::string_view tok = t[off[static_cast<size_t>(w[c])]];
      // NaN and infinity are decided below (skipped point, dropped normals or an error)
      if (parse_strict_double(tok, v[c]) != NumberKind::ok && !std::isinf(v[c]) &&
          !std::isnan(v[c]))
        field_number(tok, path, number, f.name.c_str()); // throws the reader's message
    }
    if (skip_invalid(h, v)) {
      ++skipped;
      continue;
    }
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(v[c]))
        field_number(t[off[static_cast<size_t>(w[static_cast<size_t>(c)])]], path, number,
                     h.fields[static_cast<size_t>(w[static_cast<size_t>(c)])].name.c_str());
    rows.add(v, v + 3);
  }
  if (read < h.points)
    throw_input_error(path, h.points_line,
                      "POINTS " + std::to_string(h.points) + " but the data holds " +
                          std::to_string(read) + " points");
}

// Byte offset of each field within a record (binary) or within the field-major block of all
// points (binary_compressed, where each field's values for all points are contiguous).
std::vector<size_t> byte_offsets(const PcdHeader& h, bool field_major) {
  std::vector<size_t> o(h.fields.size());
  size_t k = 0;
  for (size_t i = 0; i < h.fields.size(); ++i) {
    o[i] = k;
    const size_t bytes =
        static_cast<size_t>(h.fields[i].size) * static_cast<size_t>(h.fields[i].count);
    k += field_major ? bytes * static_cast<size_t>(h.points) : bytes;
  }
  return o;
}

// The binary_compressed payload decompressed (PCL's LZF codec), after checking its two sizes
// against the header and the file.
std::string decompress(const std::string& path, std::string_view text, const PcdHeader& h) {
  const size_t available = text.size() - h.payload;
  if (available < 8)
    throw_input_error(path, h.data_line, "binary_compressed data lacks its 8-byte size header");
  std::uint32_t sz[2]; // compressed and uncompressed sizes, little-endian
  for (int k = 0; k < 2; ++k)
    sz[k] = static_cast<std::uint32_t>(binary_value(text.data() + h.payload + 4 * k, 'U', 4));
  require_payload(path, h.data_line, "the compressed block", 1.0, double(sz[0]) + 8, available);
  const double expected = double(h.points) * double(h.record());
  if (double(sz[1]) != expected)
    throw_input_error(path, h.data_line,
                      "binary_compressed data decompresses to " + std::to_string(sz[1]) +
                          " bytes, POINTS x record size is " + std::to_string(expected));
  // LZF expands at most 88 times (a 3-byte back reference copies 264 bytes): a larger claim is a
  // corrupt header, refused before allocating it.
  constexpr double kLzfMaxExpansion = 88;
  if (double(sz[1]) > kLzfMaxExpansion * double(sz[0]) + 64)
    throw_input_error(path, h.data_line,
                      "binary_compressed data claims " + std::to_string(sz[1]) + " bytes from " +
                          std::to_string(sz[0]) +
                          " compressed bytes (LZF expands at most 88 times)");
  std::string out(sz[1], '\0');
  if (sz[1] > 0 &&
      pcl::lzfDecompress(text.data() + h.payload + 8, sz[0], out.data(), sz[1]) != sz[1])
    throw_input_error(path, h.data_line, "binary_compressed data is corrupt (LZF)");
  return out;
}

void read_binary(const std::string& path, std::string_view text, const PcdHeader& h,
                 CloudRows& rows, long& skipped) {
  const bool compressed = h.data == "binary_compressed";
  std::string block;
  std::string_view data = text.substr(h.payload);
  if (compressed) {
    block = decompress(path, text, h);
    data = block;
  } else {
    require_payload(path, h.points_line, "POINTS " + std::to_string(h.points), double(h.points),
                    double(h.record()), data.size());
  }
  bool normals = false;
  const std::vector<int> w = wanted_fields(h, normals);
  rows.with_normals = normals;
  const std::vector<size_t> off = byte_offsets(h, compressed);
  const size_t record = h.record();
  for (long i = 0; i < h.points; ++i) {
    double v[6] = {0, 0, 0, 0, 0, 0};
    for (size_t c = 0; c < w.size(); ++c) {
      const PcdField& f = h.fields[static_cast<size_t>(w[c])];
      const size_t at = compressed ? off[static_cast<size_t>(w[c])] + size_t(i) * size_t(f.size)
                                   : size_t(i) * record + off[static_cast<size_t>(w[c])];
      v[c] = binary_value(data.data() + at, f.type, f.size);
    }
    if (skip_invalid(h, v)) {
      ++skipped;
      continue;
    }
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(v[c]))
        throw_input_error(path, 0,
                          "point " + std::to_string(i + 1) + " (binary data): " +
                              h.fields[static_cast<size_t>(w[static_cast<size_t>(c)])].name +
                              " is not a finite value (NaN and infinity are not allowed)");
    rows.add(v, v + 3);
  }
}

} // namespace

void read_pcd(const std::string& path, std::string_view text, CloudRows& rows,
              std::vector<std::string>& notes) {
  const PcdHeader h = parse_header(path, text);
  long skipped = 0;
  if (h.data == "ascii")
    read_ascii(path, text, h, rows, skipped);
  else
    read_binary(path, text, h, rows, skipped);
  if (skipped > 0)
    notes.push_back(path + ": " + std::to_string(skipped) +
                    " invalid (NaN) points of the organised cloud skipped");
}

} // namespace interlin::detail
