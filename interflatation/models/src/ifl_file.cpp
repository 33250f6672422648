// The .ifl container: writer and strict parser (docs/formats.md, "Implicit model files").
#include "interlin/interflatation/models/ifl_file.h"

#include "interlin/interflatation/input_error.h"
#include "interlin/interflatation/read_input_file.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
#include <ostream>
#include <stdexcept>

namespace interlin {

namespace {

constexpr int kMaxDepth = 8;    // nested blocks
constexpr int kMaxDims = 4;     // array dimensions
constexpr size_t kMaxName = 64; // characters of a name or kind
const char* const kMagic = "interlin-ifl";

bool valid_name(const std::string& s) {
  if (s.empty() || s.size() > kMaxName)
    return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-' || c == '.';
  });
}

std::string where(const std::string& file, long line) {
  return (file.empty() ? std::string("<ifl>") : file) + ":" + std::to_string(line) + ": ";
}

std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

template <class T>
void put_raw(std::ostream& out, const std::vector<T>& v) {
  static_assert(sizeof(T) == 8);
  if constexpr (std::endian::native == std::endian::little) {
    out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * 8));
  } else {
    for (const T& x : v) {
      unsigned char b[8];
      std::memcpy(b, &x, 8);
      std::reverse(b, b + 8);
      out.write(reinterpret_cast<const char*>(b), 8);
    }
  }
}

template <class T>
void get_raw(const char* src, size_t count, std::vector<T>& v) {
  v.resize(count);
  if (count == 0)
    return; // memcpy needs non-null pointers even for zero bytes
  std::memcpy(v.data(), src, count * 8);
  if constexpr (std::endian::native != std::endian::little)
    for (T& x : v) {
      unsigned char b[8];
      std::memcpy(b, &x, 8);
      std::reverse(b, b + 8);
      std::memcpy(&x, b, 8);
    }
}

void write_block(std::ostream& out, const IflBlock& b) {
  out << "block " << b.kind << ' ' << b.name << '\n';
  for (const auto& [name, v] : b.numbers) {
    if (!std::isfinite(v))
      throw std::invalid_argument("write_ifl: number " + name + " is not finite");
    out << "number " << name << ' ' << number_text(v) << '\n';
  }
  for (const auto& [name, t] : b.texts) {
    out << "text " << name << ' ' << t.size() << '\n';
    out.write(t.data(), static_cast<std::streamsize>(t.size()));
    out << '\n';
  }
  for (const auto& [name, a] : b.arrays) {
    out << "array " << name << (a.type == IflArray::Type::f64 ? " f64" : " i64");
    for (long d : a.dims)
      out << ' ' << d;
    out << '\n';
    if (a.type == IflArray::Type::f64)
      put_raw(out, a.f64);
    else
      put_raw(out, a.i64);
    out << '\n';
  }
  for (const IflBlock& sub : b.blocks)
    write_block(out, sub);
  out << "end\n";
}

// A cursor over the file's bytes that knows its line number.
class Parser {
public:
  Parser(const std::string& bytes, const std::string& file) : s_(bytes), file_(file) {}

  IflBlock parse() {
    const std::vector<std::string> head = next_line("the header line 'interlin-ifl 1'");
    if (head.size() != 2 || head[0] != kMagic)
      fail("not an interlin implicit model file (the first line must be 'interlin-ifl " +
           std::to_string(kIflVersion) + "')");
    const long version = parse_long(head[1], "version");
    if (version < 1)
      fail("invalid container version " + head[1]);
    if (version > kIflVersion)
      fail("container version " + head[1] + " is newer than this interlin reads (" +
           std::to_string(kIflVersion) + ")");
    const std::vector<std::string> first = next_line("the model block");
    if (first.empty() || first[0] != "block")
      fail("expected 'block KIND NAME', got '" + first[0] + "'");
    IflBlock model = parse_block(first, 1);
    skip_blank_tail();
    if (pos_ < s_.size())
      fail("unexpected data after the model block");
    return model;
  }

private:
  [[noreturn]] void fail(const std::string& m) const { throw InputError(where(file_, line_) + m); }

  // The next line's tokens (separated by single spaces); `what` names what is expected at EOF.
  std::vector<std::string> next_line(const std::string& what) {
    ++line_; // at the end of the file: the line that is missing
    if (pos_ >= s_.size())
      fail("unexpected end of file; expected " + what);
    const size_t end = s_.find('\n', pos_);
    if (end == std::string::npos)
      fail("unexpected end of file (the last line has no line break); expected " + what);
    std::string text = s_.substr(pos_, end - pos_);
    pos_ = end + 1;
    if (!text.empty() && text.back() == '\r')
      text.pop_back();
    std::vector<std::string> tok;
    size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && (text[i] == ' ' || text[i] == '\t'))
        ++i;
      size_t j = i;
      while (j < text.size() && text[j] != ' ' && text[j] != '\t')
        ++j;
      if (j > i)
        tok.push_back(text.substr(i, j - i));
      i = j;
    }
    if (tok.empty())
      fail("empty line; expected " + what);
    return tok;
  }

  // `count` raw bytes followed by a line break (the payload of a text or array).
  const char* take(size_t count, const std::string& what) {
    if (count > s_.size() - pos_ || s_.size() - pos_ - count < 1)
      fail(what + ": the file ends before its " + std::to_string(count) + " bytes");
    const char* p = s_.data() + pos_;
    line_ += static_cast<long>(std::count(p, p + count, '\n'));
    pos_ += count;
    if (s_[pos_] != '\n')
      fail(what + ": expected a line break after its " + std::to_string(count) + " bytes");
    ++pos_;
    ++line_;
    return p;
  }

  void skip_blank_tail() {
    while (pos_ < s_.size() && (s_[pos_] == '\n' || s_[pos_] == '\r' || s_[pos_] == ' '))
      ++pos_;
  }

  long parse_long(const std::string& t, const std::string& what) const {
    long v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(what + ": '" + t + "' is not an integer");
    return v;
  }

  double parse_double(const std::string& t, const std::string& what) const {
    double v = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size())
      fail(what + ": '" + t + "' is not a number");
    if (!std::isfinite(v))
      fail(what + ": '" + t + "' is not finite");
    return v;
  }

  void check_name(const std::string& n, const std::string& what) const {
    if (!valid_name(n))
      fail(what + " '" + n.substr(0, kMaxName) +
           "' is not a valid name (1 to 64 of A-Z a-z 0-9 _ - .)");
  }

  IflBlock parse_block(const std::vector<std::string>& head, int depth) {
    if (depth > kMaxDepth)
      fail("blocks nested deeper than " + std::to_string(kMaxDepth));
    if (head.size() != 3)
      fail("expected 'block KIND NAME'");
    check_name(head[1], "block kind");
    check_name(head[2], "block name");
    IflBlock b;
    b.kind = head[1];
    b.name = head[2];
    b.line = line_;
    b.file = file_;
    auto unique = [&](const std::string& n, bool taken) {
      if (taken)
        fail("block " + b.kind + " " + b.name + ": '" + n + "' appears twice");
    };
    for (;;) {
      const std::vector<std::string> t = next_line("'end' of block " + b.kind + " " + b.name);
      const std::string& key = t[0];
      if (key == "end") {
        if (t.size() != 1)
          fail("'end' takes no arguments");
        return b;
      }
      if (key == "number") {
        if (t.size() != 3)
          fail("expected 'number NAME VALUE'");
        check_name(t[1], "number");
        unique(t[1], b.numbers.count(t[1]) > 0);
        b.numbers[t[1]] = parse_double(t[2], "number " + t[1]);
      } else if (key == "text") {
        if (t.size() != 3)
          fail("expected 'text NAME BYTES'");
        check_name(t[1], "text");
        unique(t[1], b.texts.count(t[1]) > 0);
        const long n = parse_long(t[2], "text " + t[1] + " length");
        if (n < 0)
          fail("text " + t[1] + ": negative length");
        const char* p = take(static_cast<size_t>(n), "text " + t[1]);
        b.texts[t[1]] = std::string(p, static_cast<size_t>(n));
      } else if (key == "array") {
        if (t.size() < 4 || t.size() > 3 + kMaxDims)
          fail("expected 'array NAME f64|i64 D1 [... D" + std::to_string(kMaxDims) + "]'");
        check_name(t[1], "array");
        unique(t[1], b.arrays.count(t[1]) > 0);
        IflArray a;
        if (t[2] == "f64")
          a.type = IflArray::Type::f64;
        else if (t[2] == "i64")
          a.type = IflArray::Type::i64;
        else
          fail("array " + t[1] + ": unknown type '" + t[2] + "' (f64 or i64)");
        size_t count = 1;
        const size_t limit = (s_.size() - pos_) / 8;
        for (size_t k = 3; k < t.size(); ++k) {
          const long d = parse_long(t[k], "array " + t[1] + " dimension");
          if (d < 0)
            fail("array " + t[1] + ": negative dimension");
          a.dims.push_back(d);
          if (d > 0 && count > limit / static_cast<size_t>(d))
            fail("array " + t[1] + ": the file ends before its data");
          count *= static_cast<size_t>(d);
        }
        const char* p = take(count * 8, "array " + t[1]);
        if (a.type == IflArray::Type::f64) {
          get_raw(p, count, a.f64);
          for (size_t k = 0; k < count; ++k)
            if (!std::isfinite(a.f64[k]))
              fail("array " + t[1] + ": value " + std::to_string(k) + " is not finite");
        } else {
          get_raw(p, count, a.i64);
        }
        b.arrays[t[1]] = std::move(a);
      } else if (key == "block") {
        IflBlock sub = parse_block(t, depth + 1);
        for (const IflBlock& o : b.blocks)
          unique(sub.name, o.name == sub.name);
        b.blocks.push_back(std::move(sub));
      } else {
        fail("unknown keyword '" + key.substr(0, kMaxName) +
             "' (expected number, text, array, block or end)");
      }
    }
  }

  const std::string& s_;
  const std::string& file_;
  size_t pos_ = 0;
  long line_ = 0;
};

std::string describe(const IflBlock& b) {
  return "block " + b.kind + " " + b.name + ": ";
}

} // namespace

long IflArray::size() const {
  long n = 1;
  for (long d : dims)
    n *= d;
  return n;
}

void IflBlock::fail(const std::string& message) const {
  throw InputError(where(file, line) + describe(*this) + message);
}

double IflBlock::number(const std::string& n) const {
  const auto it = numbers.find(n);
  if (it == numbers.end())
    fail("missing number '" + n + "'");
  return it->second;
}

long IflBlock::integer(const std::string& n, long lo, long hi) const {
  const double v = number(n);
  if (!(v >= static_cast<double>(lo) && v <= static_cast<double>(hi)) || v != std::floor(v))
    fail("number '" + n + "' must be an integer from " + std::to_string(lo) + " to " +
         std::to_string(hi) + ", got " + number_text(v));
  return static_cast<long>(v);
}

long IflBlock::expect(const std::string& k, long version) const {
  if (kind != k)
    fail("expected a " + k + " block");
  return integer("version", 1, version);
}

const std::string& IflBlock::text(const std::string& n) const {
  const auto it = texts.find(n);
  if (it == texts.end())
    fail("missing text '" + n + "'");
  return it->second;
}

const IflArray& IflBlock::array(const std::string& n) const {
  const auto it = arrays.find(n);
  if (it == arrays.end())
    fail("missing array '" + n + "'");
  return it->second;
}

namespace {

void check_shape(const IflBlock& b, const std::string& n, const IflArray& a,
                 const std::vector<long>& shape) {
  bool ok = a.dims.size() == shape.size();
  for (size_t k = 0; ok && k < shape.size(); ++k)
    ok = shape[k] < 0 || shape[k] == a.dims[k];
  if (ok)
    return;
  std::string want, got;
  for (long d : shape)
    want += (want.empty() ? "" : " x ") + (d < 0 ? std::string("any") : std::to_string(d));
  for (long d : a.dims)
    got += (got.empty() ? "" : " x ") + std::to_string(d);
  b.fail("array '" + n + "' must be " + want + ", got " + (got.empty() ? "a scalar" : got));
}

} // namespace

const std::vector<double>& IflBlock::f64(const std::string& n,
                                         const std::vector<long>& shape) const {
  const IflArray& a = array(n);
  if (a.type != IflArray::Type::f64)
    fail("array '" + n + "' must be f64");
  check_shape(*this, n, a, shape);
  return a.f64;
}

const std::vector<std::int64_t>& IflBlock::i64(const std::string& n,
                                               const std::vector<long>& shape) const {
  const IflArray& a = array(n);
  if (a.type != IflArray::Type::i64)
    fail("array '" + n + "' must be i64");
  check_shape(*this, n, a, shape);
  return a.i64;
}

const IflBlock& IflBlock::block(const std::string& n) const {
  for (const IflBlock& b : blocks)
    if (b.name == n)
      return b;
  fail("missing block '" + n + "'");
}

namespace {

void check_new(const IflBlock& b, const std::string& n) {
  if (!valid_name(n))
    throw std::invalid_argument("ifl: invalid field name '" + n + "'");
  if (b.numbers.count(n) || b.texts.count(n) || b.arrays.count(n))
    throw std::invalid_argument("ifl: field '" + n + "' set twice");
}

} // namespace

void IflBlock::set(const std::string& n, double value) {
  check_new(*this, n);
  numbers[n] = value;
}

void IflBlock::set_text(const std::string& n, const std::string& value) {
  check_new(*this, n);
  texts[n] = value;
}

void IflBlock::set_f64(const std::string& n, std::vector<long> dims, std::vector<double> values) {
  check_new(*this, n);
  IflArray a;
  a.type = IflArray::Type::f64;
  a.dims = std::move(dims);
  a.f64 = std::move(values);
  if (a.size() != static_cast<long>(a.f64.size()))
    throw std::invalid_argument("ifl: array '" + n + "' has the wrong number of values");
  arrays[n] = std::move(a);
}

void IflBlock::set_i64(const std::string& n, std::vector<long> dims,
                       std::vector<std::int64_t> values) {
  check_new(*this, n);
  IflArray a;
  a.type = IflArray::Type::i64;
  a.dims = std::move(dims);
  a.i64 = std::move(values);
  if (a.size() != static_cast<long>(a.i64.size()))
    throw std::invalid_argument("ifl: array '" + n + "' has the wrong number of values");
  arrays[n] = std::move(a);
}

void write_ifl(std::ostream& out, const IflBlock& model) {
  out << kMagic << ' ' << kIflVersion << '\n';
  write_block(out, model);
}

IflBlock parse_ifl(const std::string& bytes, const std::string& file) {
  return Parser(bytes, file).parse();
}

IflBlock read_ifl(const std::string& path) {
  return parse_ifl(read_input_file(path), path);
}

} // namespace interlin
