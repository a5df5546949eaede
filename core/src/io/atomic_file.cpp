#include "surfcomp/core/io/atomic_file.hpp"

#include "surfcomp/core/error.hpp"

#include <atomic>
#include <cstdio>
#include <fstream>
#include <functional>
#include <system_error>
#include <unistd.h>

namespace surfcomp::io {
namespace {

/// A hidden name beside `path` that no other writer uses at the same time: the process id, a
/// count of this process's writes and a hash of the file name. It is short whatever the length
/// of the name, so any name the file system accepts can be written.
std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> writes{0};
  char name[64];
  std::snprintf(name, sizeof name, ".surfcomp-%ld-%u-%016zx.tmp", static_cast<long>(::getpid()),
                writes++, std::hash<std::string>{}(path.filename().string()));
  return path.parent_path() / name;
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path temp = temporary_beside(path);
  auto discard = [&temp] {
    std::error_code ignored;
    fs::remove(temp, ignored);
  };
  try {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError(path.string(), "cannot open for writing");
    write(out);
    out.flush();
    if (!out) throw FileError(path.string(), "write failed (disk full?)");
    out.close();
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) throw FileError(path.string(), "cannot rename the finished file: " + ec.message());
  } catch (...) {
    discard();
    throw;
  }
}

}  // namespace surfcomp::io
