#pragma once
// Output files appear whole or not at all: everything is written to a temporary file next to the
// target and renamed into place only after the writer succeeded.

#include <functional>
#include <iosfwd>
#include <string>

namespace interlin {

// A temporary path beside `target` with the same extension (writers that choose the format by
// extension, such as OpenMesh, keep working). commit() renames it onto the target; if commit()
// is never reached the destructor removes the temporary file.
class AtomicPath {
public:
  explicit AtomicPath(std::string target);
  AtomicPath(const AtomicPath&) = delete;
  AtomicPath& operator=(const AtomicPath&) = delete;
  ~AtomicPath();
  const std::string& temp() const { return temp_; }
  void commit(); // throws std::runtime_error naming the target when the rename fails
private:
  std::string target_, temp_;
  bool committed_ = false;
};

// Opens the temporary file, calls write(stream), checks the stream and commits.
// Throws std::runtime_error("cannot write TARGET: reason") on failure, leaving no file behind.
void write_file_atomically(const std::string& target,
                           const std::function<void(std::ostream&)>& write);

} // namespace interlin
