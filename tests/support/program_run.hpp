// The surfcomp program run as a user runs it, for the tests of the command line: one helper that
// every CLI test calls, so that how a run is started and what it returns is defined once.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>

namespace surfcomp::test {

/// What one run of the program gave.
struct ProgramRun {
  int status = -1;  ///< exit status; -1 when a signal ended it
  std::string out;  ///< its stdout
  std::string err;  ///< its stderr
};

/// How run_program starts the program.
struct RunOptions {
  std::filesystem::path folder;  ///< working folder; empty: the test's own
  /// Put before the program on the shell's command line: environment assignments
  /// ("SURFCOMP_MODULE_DIR=/x ") or a launcher ("mpirun -n 2 ").
  std::string prefix;
};

/// The surfcomp program of this build.
inline std::filesystem::path program_path() {
  return std::filesystem::path(SURFCOMP_BINARY_DIR) / "tools" / "surfcomp";
}

/// The bytes of `path` ("" when it cannot be read).
inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// The width and height of the PNG file at `path`, from its IHDR chunk (bytes 16 to 23,
/// big-endian); {0, 0} when it does not start as a PNG file does.
inline std::pair<std::uint32_t, std::uint32_t> png_size(const std::filesystem::path& path) {
  const std::string bytes = file_bytes(path);
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0) return {0, 0};
  const auto word = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t k = 0; k < 4; ++k)
      value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
    return value;
  };
  return {word(16), word(20)};
}

/// Every file under `folder` (recursively) by its path relative to it, with its bytes: what a
/// run wrote, to compare with another run's.
inline std::map<std::string, std::string> files_under(const std::filesystem::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& item : std::filesystem::recursive_directory_iterator(folder)) {
    if (item.is_regular_file())
      files[std::filesystem::relative(item.path(), folder).string()] = file_bytes(item.path());
  }
  return files;
}

/// Runs `PREFIX surfcomp ARGUMENTS` through the shell (ARGUMENTS as a user types them) and
/// returns its exit status, stdout and stderr. Both streams go through files in a folder of the
/// run's own under the system's temporary folder, removed afterwards, so that runs side by side
/// (ctest -j) and the listing of the working folder are not disturbed.
inline ProgramRun run_program(const std::string& arguments, const RunOptions& options = {}) {
  static std::atomic<int> runs{0};
  namespace fs = std::filesystem;
  const fs::path streams =
      fs::temp_directory_path() /
      ("surfcomp_run_" + std::to_string(::getpid()) + "_" + std::to_string(runs.fetch_add(1)));
  fs::create_directories(streams);
  std::string command = options.prefix + program_path().string() + " " + arguments + " >" +
                        (streams / "out").string() + " 2>" + (streams / "err").string();
  if (!options.folder.empty()) command = "cd " + options.folder.string() + " && " + command;
  const int raw = std::system(command.c_str());
  ProgramRun run;
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = file_bytes(streams / "out");
  run.err = file_bytes(streams / "err");
  std::error_code ignored;
  fs::remove_all(streams, ignored);
  return run;
}

}  // namespace surfcomp::test
