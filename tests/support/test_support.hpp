// What the tests and the benchmarks share: where the data sets are, how a run that lacks one
// says so, and the median they report. Free of GoogleTest and Google Benchmark, so both use it.
#pragma once

#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace surfcomp::test {

/// The repository's root (set by CMake).
inline std::filesystem::path source_dir() { return SURFCOMP_SOURCE_DIR; }

/// The shared data sets: $SURFCOMP_SHARED_DATASETS when set, else ../shared/datasets beside the
/// repository (never copied into it).
inline std::filesystem::path shared_datasets_root() {
  if (const char* env = std::getenv("SURFCOMP_SHARED_DATASETS")) return env;
  return source_dir().parent_path() / "shared" / "datasets";
}

/// Whether a test that lacks its data fails instead of skipping: $SURFCOMP_REQUIRE_DATA is 1
/// (CI sets it, since it has the data beside the repository and a skip would pass unnoticed).
inline bool data_required() {
  const char* env = std::getenv("SURFCOMP_REQUIRE_DATA");
  return env != nullptr && std::string(env) == "1";
}

/// shared_datasets_root()/<relative>; nullopt if absent.
inline std::optional<std::filesystem::path> shared_dataset(const std::string& relative) {
  const auto path = shared_datasets_root() / relative;
  if (!std::filesystem::exists(path)) return std::nullopt;
  return path;
}

/// datasets/cache/<relative> (run datasets/fetch.sh to fill it); nullopt if absent.
inline std::optional<std::filesystem::path> fetched_dataset(const std::string& relative) {
  const auto path = source_dir() / "datasets" / "cache" / relative;
  if (!std::filesystem::exists(path)) return std::nullopt;
  return path;
}

/// Why a run that needs shared_datasets_root()/<relative> is skipped.
inline std::string shared_absent_message(const std::string& relative) {
  return (shared_datasets_root() / relative).string() +
         " is absent (set SURFCOMP_SHARED_DATASETS to the shared data sets)";
}

/// Why a run that needs datasets/cache/<relative> is skipped.
inline std::string fetched_absent_message(const std::string& relative) {
  return "datasets/cache/" + relative + " is absent: run datasets/fetch.sh";
}

/// For a benchmark: shared_datasets_root()/<relative>, or nullopt after printing
/// "skipped: <why>" on stdout.
inline std::optional<std::filesystem::path> shared_dataset_or_report(const std::string& relative) {
  auto path = shared_dataset(relative);
  if (!path) std::printf("skipped: %s\n", shared_absent_message(relative).c_str());
  return path;
}

/// The median of `values` (the mean of the middle two for an even count); NaN when empty.
inline double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t n = values.size();
  std::sort(values.begin(), values.end());
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// The message of the surfcomp::Error that `run` throws, or "" when it throws none.
template <class Run>
std::string error_of(Run run) {
  try {
    run();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace surfcomp::test
