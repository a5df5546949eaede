// Where tests find their data: ../shared/datasets beside the repository (never copied into it)
// and datasets/cache, filled by datasets/fetch.sh from Debian packages.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

#include <unistd.h>

namespace surfcomp::test {

/// The repository's root (set by CMake).
inline std::filesystem::path source_dir() { return SURFCOMP_SOURCE_DIR; }

/// ../shared/datasets/<relative>, or $SURFCOMP_SHARED_DATASETS/<relative>; nullopt if absent.
inline std::optional<std::filesystem::path> shared_dataset(const std::string& relative) {
  std::filesystem::path root = source_dir().parent_path() / "shared" / "datasets";
  if (const char* env = std::getenv("SURFCOMP_SHARED_DATASETS")) root = env;
  const auto path = root / relative;
  if (!std::filesystem::exists(path)) return std::nullopt;
  return path;
}

/// datasets/cache/<relative> (run datasets/fetch.sh to fill it); nullopt if absent.
inline std::optional<std::filesystem::path> fetched_dataset(const std::string& relative) {
  const auto path = source_dir() / "datasets" / "cache" / relative;
  if (!std::filesystem::exists(path)) return std::nullopt;
  return path;
}

/// A fresh directory under the system temp dir, named after the running test, removed when the
/// test ends.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("surfcomp_" + std::string(info->test_suite_name()) + "_" + info->name() + "_" +
             std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace surfcomp::test

/// Binds `var` to ../shared/datasets/<relative> or skips the test, saying which file is missing.
#define SURFCOMP_SHARED_OR_SKIP(var, relative)                                         \
  const auto var##_opt = ::surfcomp::test::shared_dataset(relative);                   \
  if (!var##_opt) GTEST_SKIP() << "../shared/datasets/" << (relative) << " is absent"; \
  const std::filesystem::path var = *var##_opt

/// Binds `var` to datasets/cache/<relative> or skips, telling the user to run the fetch script.
#define SURFCOMP_FETCHED_OR_SKIP(var, relative)                                             \
  const auto var##_opt = ::surfcomp::test::fetched_dataset(relative);                       \
  if (!var##_opt)                                                                           \
    GTEST_SKIP() << "datasets/cache/" << (relative) << " is absent: run datasets/fetch.sh"; \
  const std::filesystem::path var = *var##_opt
