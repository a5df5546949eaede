// A library build's log (the records it skipped, and why) and the input hashes by which a
// resumed build knows its shards.
#include "library_build_items.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace surfcomp::screening {

namespace {

/// `text` as one field of a log line: a tab, like a line break, becomes a space.
std::string log_field(std::string text) {
  text = detail::one_line(std::move(text));
  std::replace(text.begin(), text.end(), '\t', ' ');
  return text;
}

constexpr const char* kLogColumns = "# source\trecord\tname\treason";

}  // namespace

void detail::file_identity(const std::filesystem::path& file, io::BinaryWriter& bytes) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file, error);
  bytes.string(file.string());
  bytes.u64(error ? 0 : static_cast<std::uint64_t>(size));
  const auto modified = std::filesystem::last_write_time(file, error);
  bytes.u64(error ? 0 : static_cast<std::uint64_t>(modified.time_since_epoch().count()));
}

LibraryBuildResult detail::read_build_log(const std::filesystem::path& path) {
  std::istringstream lines(io::read_input_file(path));
  LibraryBuildResult result;
  std::string line;
  const auto fail = [&](std::size_t number, const std::string& reason) {
    throw FormatError(path.string(), number, reason);
  };
  std::size_t skipped = 0;
  const std::size_t summary_at = std::getline(lines, line) ? line.rfind(": ") : std::string::npos;
  if (line.rfind("# surfcomp library build -> ", 0) != 0 || summary_at == std::string::npos ||
      std::sscanf(line.c_str() + summary_at, ": %zu records, %zu entries, %zu skipped",
                  &result.records, &result.entries, &skipped) != 3)
    fail(1, "not the first line of a library build's log");
  if (!std::getline(lines, line) || line != kLogColumns) fail(2, "not the log's column line");
  for (std::size_t number = 3; std::getline(lines, line); ++number) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, '\t');) fields.push_back(cell);
    char* rest = nullptr;
    const std::size_t record = fields.size() == 4 ? std::strtoull(fields[1].c_str(), &rest, 10) : 0;
    if (fields.size() != 4 || rest == fields[1].c_str() || *rest != '\0')
      fail(number, "not a skipped record (source, record, name, reason, tab-separated)");
    result.skipped.push_back({fields[0], record, fields[2], fields[3]});
  }
  if (result.skipped.size() != skipped) {
    fail(1, "says " + std::to_string(skipped) + " records were skipped, the log lists " +
                std::to_string(result.skipped.size()));
  }
  return result;
}

std::string detail::hex64(std::uint64_t value) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

std::uint64_t detail::input_hash(const BuildItems& items, std::size_t begin, std::size_t end) {
  io::BinaryWriter bytes;
  for (std::size_t i = begin; i < end; ++i) items.identity(i, bytes);
  return io::xxh3_64(bytes.bytes().data(), bytes.bytes().size());
}

void write_build_log(std::ostream& out, const std::filesystem::path& library,
                     const LibraryBuildResult& result) {
  out << "# surfcomp library build -> " << library.string() << ": " << result.records
      << " records, " << result.entries << " entries, " << result.skipped.size() << " skipped\n"
      << kLogColumns << '\n';
  for (const SkippedRecord& s : result.skipped) {
    out << log_field(s.source) << '\t' << s.record << '\t' << log_field(s.name) << '\t'
        << log_field(s.reason) << '\n';
  }
}

}  // namespace surfcomp::screening
