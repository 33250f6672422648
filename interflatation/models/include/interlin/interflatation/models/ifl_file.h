#pragma once
// The .ifl container (docs/formats.md, "Implicit model files"): a versioned file of typed,
// nested blocks that hold numbers, texts and binary arrays. One top-level block is the model;
// its kind names the evaluator that turns it into an ImplicitFunction (ifl_registry.h).
//
//   interlin-ifl 1
//   block section_body model
//   number version 1
//   text note 11
//   hello world
//   array distance f64 40 30 20
//   <40*30*20 little-endian doubles>
//   block cubic_grid far
//   ...
//   end
//   end

#include <cstdint>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace interlin {

// A typed array: f64 (IEEE doubles) or i64 (signed 64-bit integers), row-major over dims (the
// last dimension fastest). Exactly one of f64 / i64 is filled.
struct IflArray {
  enum class Type { f64, i64 };
  Type type = Type::f64;
  std::vector<long> dims;
  std::vector<double> f64;
  std::vector<std::int64_t> i64;
  long size() const;
};

// One block: its kind and name, its fields and sub-blocks (names unique per block and per field
// type; `line` is where the block starts, for messages).
struct IflBlock {
  std::string kind, name;
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> texts;
  std::map<std::string, IflArray> arrays;
  std::vector<IflBlock> blocks;
  long line = 0;
  std::string file; // the file it came from, for messages ("" when built in memory)

  // Checked access; each throws InputError "FILE:LINE: block KIND NAME: ..." naming what is
  // missing or of the wrong shape. dims = -1 in `shape` accepts any extent.
  double number(const std::string& name) const;
  const std::string& text(const std::string& name) const;
  const std::vector<double>& f64(const std::string& name, const std::vector<long>& shape) const;
  const std::vector<std::int64_t>& i64(const std::string& name,
                                       const std::vector<long>& shape) const;
  const IflArray& array(const std::string& name) const;
  const IflBlock& block(const std::string& name) const;
  // The number as an integer in [lo, hi] (InputError otherwise).
  long integer(const std::string& name, long lo, long hi) const;
  // A model block's header: this kind, and a field 'version' from 1 to `version` (the versions
  // this reader knows); InputError otherwise. Returns the block's version.
  long expect(const std::string& kind, long version) const;
  // InputError "FILE:LINE: block KIND NAME: message".
  [[noreturn]] void fail(const std::string& message) const;

  // Building: add fields (std::invalid_argument for a bad name or a name already used).
  void set(const std::string& name, double value);
  void set_text(const std::string& name, const std::string& value);
  void set_f64(const std::string& name, std::vector<long> dims, std::vector<double> values);
  void set_i64(const std::string& name, std::vector<long> dims, std::vector<std::int64_t> values);
};

// The container version this build reads and writes.
inline constexpr int kIflVersion = 1;

// Writes `model` as a whole .ifl file (header line, the block tree) to `out`. Numbers are
// written with 17 significant digits, arrays as raw little-endian bytes: reading back gives
// identical values. Throws std::invalid_argument for non-finite numbers.
void write_ifl(std::ostream& out, const IflBlock& model);

// Parses a whole .ifl file. `file` names it in messages.
// Throws InputError "FILE:LINE: message" for anything that is not a valid container: wrong magic
// or a newer version, unknown keywords, bad names, duplicate fields, arrays or texts longer than
// the rest of the file, more than 8 nested blocks, non-finite numbers, missing `end`, data after
// the model block. Never reads past the input or allocates more than the input's size.
IflBlock parse_ifl(const std::string& bytes, const std::string& file);

// read_input_file + parse_ifl.
IflBlock read_ifl(const std::string& path);

} // namespace interlin
