// What the harnesses share: the fuzz input as a file, for readers that take only a path.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace surfcomp::fuzz {

/// One scratch file per process, in memory-backed /dev/shm when it exists (else the system temp
/// directory), named surfcomp-fuzz-<pid><suffix> so that parallel fuzzing jobs do not collide.
/// Removed at exit.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& suffix) {
    std::error_code error;
    const std::filesystem::path shm = "/dev/shm";
    const std::filesystem::path dir =
        std::filesystem::is_directory(shm, error) ? shm : std::filesystem::temp_directory_path();
    path_ = dir / ("surfcomp-fuzz-" + std::to_string(::getpid()) + suffix);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile() {
    std::error_code error;
    std::filesystem::remove(path_, error);
  }

  /// Replaces the file's content with `size` bytes at `data`; returns its path.
  const std::filesystem::path& write(const std::uint8_t* data, std::size_t size) {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) std::abort();  // the harness cannot run without its scratch file
    return path_;
  }

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace surfcomp::fuzz
