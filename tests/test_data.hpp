// GoogleTest's side of the test data: ending a test whose data set is absent (a skip, or a
// failure under SURFCOMP_REQUIRE_DATA=1) (the paths are
// in support/test_support.hpp, shared with the benchmarks) and a temporary directory per test.
#pragma once

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include <unistd.h>

namespace surfcomp::test {

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
  /// Writes `content` to the file `name` in the directory; returns its path.
  std::filesystem::path write(const std::string& name, const std::string& content) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream(file, std::ios::binary) << content;
    return file;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace surfcomp::test

/// Ends the test for data it lacks, saying why: a skip, or a failure under
/// SURFCOMP_REQUIRE_DATA=1.
#define SURFCOMP_DATA_ABSENT(message)                                        \
  do {                                                                       \
    if (::surfcomp::test::data_required()) {                                 \
      GTEST_FAIL() << (message) << " (SURFCOMP_REQUIRE_DATA=1 requires it)"; \
    }                                                                        \
    GTEST_SKIP() << (message);                                               \
  } while (false)

/// Binds `var` to the shared data set <relative> or ends the test (SURFCOMP_DATA_ABSENT), saying
/// which file is missing.
#define SURFCOMP_SHARED_OR_SKIP(var, relative)                                             \
  const auto var##_opt = ::surfcomp::test::shared_dataset(relative);                       \
  if (!var##_opt) SURFCOMP_DATA_ABSENT(::surfcomp::test::shared_absent_message(relative)); \
  const std::filesystem::path var = *var##_opt

/// Binds `var` to datasets/cache/<relative> or ends the test, telling the user to run the
/// fetch script.
#define SURFCOMP_FETCHED_OR_SKIP(var, relative)                                             \
  const auto var##_opt = ::surfcomp::test::fetched_dataset(relative);                       \
  if (!var##_opt) SURFCOMP_DATA_ABSENT(::surfcomp::test::fetched_absent_message(relative)); \
  const std::filesystem::path var = *var##_opt
