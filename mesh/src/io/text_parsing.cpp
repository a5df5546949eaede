#include "text_parsing.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"

#include <array>
#include <charconv>
#include <cmath>

namespace surfcomp::mesh::io::detail {

std::string read_whole_stream(std::istream& in, const std::string& name) {
  // Through a fixed buffer, appending only what was read: a small file costs a small string
  // (growing the string by a large chunk before each read would zero-fill the whole chunk).
  std::string data;
  std::array<char, std::size_t{1} << 16> buffer;
  while (in) {
    if (data.size() > surfcomp::io::max_input_file_bytes) {
      throw FileError(name, "more than the limit of " +
                                std::to_string(surfcomp::io::max_input_file_bytes) +
                                " bytes (4 GiB) an input may have");
    }
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    data.append(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw FileError(name, "read failed");
  return data;
}

std::string quote(std::string_view token) {
  constexpr std::size_t max_length = 40;
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < max_length; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (token.size() > max_length) out += "...";
  out += "'";
  return out;
}

bool LineCursor::next(std::string_view& line) {
  if (position_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', position_);
  std::size_t after = end == std::string_view::npos ? text_.size() : end + 1;
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(position_, end - position_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  position_ = after;
  ++next_line_;
  return true;
}

bool LineCursor::next_non_blank(std::string_view& line) {
  while (next(line)) {
    for (char c : line) {
      if (!is_space(c)) return true;
    }
  }
  return false;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

std::string_view strip_comment(std::string_view line, char marker) {
  const std::size_t at = line.find(marker);
  return at == std::string_view::npos ? line : line.substr(0, at);
}

namespace {

[[noreturn]] void fail(const Location& at, const std::string& what, std::string_view token) {
  throw FormatError(at.file, at.line, "expected " + what + ", found " + quote(token));
}

std::string_view without_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-' && token[1] != '+') {
    token.remove_prefix(1);
  }
  return token;
}

template <class T>
T parse_real(std::string_view token, const Location& at, const std::string& what, bool finite) {
  const std::string_view digits = without_plus(token);
  T value{};
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || end != digits.data() + digits.size()) fail(at, what, token);
  if (finite && !std::isfinite(value)) fail(at, what, token);
  return value;
}

}  // namespace

double parse_double(std::string_view token, const Location& at, const std::string& what,
                    bool finite) {
  return parse_real<double>(token, at, what, finite);
}

double parse_float(std::string_view token, const Location& at, const std::string& what,
                   bool finite) {
  return static_cast<double>(parse_real<float>(token, at, what, finite));
}

std::int64_t parse_integer(std::string_view token, const Location& at, const std::string& what,
                           std::int64_t min, std::int64_t max) {
  const std::string_view digits = without_plus(token);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (ec != std::errc() || end != digits.data() + digits.size() || value < min || value > max) {
    fail(at, what + " (an integer in " + std::to_string(min) + ".." + std::to_string(max) + ")",
         token);
  }
  return value;
}

void check_count_fits(std::uint64_t count, std::uint64_t min_bytes_each,
                      std::uint64_t remaining_bytes, const Location& at, const std::string& what) {
  if (min_bytes_each == 0 || count <= remaining_bytes / min_bytes_each) return;
  throw FormatError(at.file, at.line,
                    "the header claims " + std::to_string(count) + " " + what + " (at least " +
                        std::to_string(min_bytes_each) + " bytes each), but only " +
                        std::to_string(remaining_bytes) + " bytes follow");
}

namespace {

template <class T>
void append_with_to_chars(std::string& out, T value) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof(text), value);
  out.append(text, result.ptr);
}

}  // namespace

void append_number(std::string& out, double value) { append_with_to_chars(out, value); }
void append_number(std::string& out, float value) { append_with_to_chars(out, value); }
void append_number(std::string& out, std::int64_t value) { append_with_to_chars(out, value); }

}  // namespace surfcomp::mesh::io::detail
