// Private helpers shared by the mesh readers: whole-file input, a line cursor with 1-based line
// numbers, whitespace tokenising and checked number parsing that throws FormatError naming the
// file, the line, what was expected and what was found.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <istream>
#include <string>
#include <string_view>
#include <vector>

namespace surfcomp::mesh::io::detail {

/// Everything left in `in`, at most surfcomp::io::max_input_file_bytes. Throws FileError naming
/// `name` if the stream fails or holds more. (Files are read with surfcomp::io::read_input_file.)
std::string read_whole_stream(std::istream& in, const std::string& name);

/// `token` made safe for a one-line message: at most 40 characters, non-printable bytes as '?',
/// in single quotes.
std::string quote(std::string_view token);

/// Walks the lines of a text buffer. Lines end at '\n'; a trailing '\r' is dropped.
class LineCursor {
 public:
  /// `first_line` is the number of the line that starts at `text[0]`.
  explicit LineCursor(std::string_view text, std::size_t first_line = 1)
      : text_(text), next_line_(first_line) {}

  /// Stores the next line in `line` and returns true, or returns false at the end of the text.
  bool next(std::string_view& line);
  /// Like next(), but skips lines that hold only whitespace.
  bool next_non_blank(std::string_view& line);
  /// Number of the line last returned by next() (the line after it at the end of the text).
  std::size_t line_number() const { return next_line_ - 1; }
  /// Bytes not yet returned.
  std::size_t remaining_bytes() const { return text_.size() - position_; }
  /// Offset of the first byte not yet returned.
  std::size_t position() const { return position_; }

 private:
  std::string_view text_;
  std::size_t position_ = 0;
  std::size_t next_line_;
};

/// True for ' ', '\t', '\r', '\n', '\v' and '\f'.
inline bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

/// Replaces `tokens` with the whitespace-separated words of `line`.
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens);

/// `line` up to (not including) the first `marker`.
std::string_view strip_comment(std::string_view line, char marker = '#');

/// Where a value comes from, for messages: file name and line (0: not a line).
struct Location {
  const std::string& file;
  std::size_t line;
};

/// Parses `token` as a decimal number (a leading '+' is allowed). Throws FormatError at `at`
/// saying that `what` was expected and `token` was found. `finite` also rejects nan and inf
/// (then `what` should say "finite").
double parse_double(std::string_view token, const Location& at, const std::string& what,
                    bool finite = true);
/// As parse_double, rounded to the nearest float (so that a file's float32 text gives the same
/// double as its binary float would).
double parse_float(std::string_view token, const Location& at, const std::string& what,
                   bool finite = true);
/// Parses `token` as a decimal integer in [min, max].
std::int64_t parse_integer(std::string_view token, const Location& at, const std::string& what,
                           std::int64_t min, std::int64_t max);

/// Throws FormatError at `at` unless `count` items of at least `min_bytes_each` bytes fit in
/// `remaining_bytes`; `what` names the items ("vertices"). Guards allocations against headers
/// that claim absurd counts.
void check_count_fits(std::uint64_t count, std::uint64_t min_bytes_each,
                      std::uint64_t remaining_bytes, const Location& at, const std::string& what);

/// Appends the shortest decimal text that reads back (from_chars, strtod) to exactly `value`.
void append_number(std::string& out, double value);
/// Appends the shortest decimal text that reads back as a float to exactly `value`.
void append_number(std::string& out, float value);
/// Appends `value` in decimal.
void append_number(std::string& out, std::int64_t value);

}  // namespace surfcomp::mesh::io::detail
