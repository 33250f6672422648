#include "interlin/reconstruction/io/atomic_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <unistd.h>

namespace interlin {

namespace fs = std::filesystem;

AtomicPath::AtomicPath(std::string target) : target_(std::move(target)) {
  const fs::path t(target_);
  const fs::path dir = t.has_parent_path() ? t.parent_path() : fs::path(".");
  // ".name.tmp-PID.ext": hidden, unique per process, same extension as the target.
  temp_ = (dir / ("." + t.stem().string() + ".tmp-" + std::to_string(::getpid()) +
                  t.extension().string()))
              .string();
}

AtomicPath::~AtomicPath() {
  if (!committed_)
    std::remove(temp_.c_str());
}

void AtomicPath::commit() {
  if (std::rename(temp_.c_str(), target_.c_str()) != 0)
    throw std::runtime_error("cannot write " + target_ + ": " + std::strerror(errno));
  committed_ = true;
}

void write_file_atomically(const std::string& target,
                           const std::function<void(std::ostream&)>& write) {
  AtomicPath path(target);
  {
    std::ofstream out(path.temp(), std::ios::binary);
    if (!out)
      throw std::runtime_error("cannot write " + target + ": " + std::strerror(errno));
    write(out);
    out.flush();
    if (!out)
      throw std::runtime_error("cannot write " + target + ": write failed");
  }
  path.commit();
}

} // namespace interlin
