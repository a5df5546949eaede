#include "surfcomp/core/io/atomic_file.hpp"

#include "surfcomp/core/error.hpp"

#include <fstream>
#include <system_error>
#include <unistd.h>

namespace surfcomp::io {

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path temp = path.string() + ".tmp" + std::to_string(::getpid());
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
