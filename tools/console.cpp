#include "console.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdarg>
#include <cstdio>

namespace surfcomp::tools::console {
namespace {

std::atomic<Level> current{Level::normal};  // set by a Python call while another may run
const auto program_start = std::chrono::steady_clock::now();

std::string thousands(std::int64_t value) {
  std::string digits = std::to_string(value);
  for (int at = static_cast<int>(digits.size()) - 3; at > 0; at -= 3)
    digits.insert(static_cast<std::size_t>(at), ",");
  return digits;
}

}  // namespace

void set_level(Level level) { current = level; }

Level level() { return current; }

void summary(const char* format, ...) {
  if (current == Level::quiet) return;
  va_list arguments;
  va_start(arguments, format);
  std::vprintf(format, arguments);
  va_end(arguments);
}

void note(const std::string& text) {
  if (current != Level::quiet) std::fprintf(stderr, "note: %s\n", text.c_str());
}

void step(const std::string& text) {
  if (current != Level::verbose) return;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - program_start).count();
  std::fprintf(stderr, "[%7.2f s] %s\n", seconds, text.c_str());
}

bool progress_shown() { return current != Level::quiet && isatty(STDERR_FILENO) != 0; }

ProgressLine::ProgressLine(std::string what, std::string unit)
    : what_(std::move(what)), unit_(std::move(unit)), enabled_(progress_shown()) {}

void ProgressLine::operator()(std::int64_t done, std::int64_t total) {
  if (!enabled_ || total <= 0) return;
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto now = std::chrono::steady_clock::now();
  if (done >= total) {
    if (shown_) std::fprintf(stderr, "\r\033[K");
    shown_ = false;
    started_ = false;
    std::fflush(stderr);
    return;
  }
  if (!started_) {
    started_ = true;
    start_ = now;
  }
  if (now - start_ < std::chrono::seconds(1)) return;
  if (shown_ && now - last_ < std::chrono::milliseconds(100)) return;
  shown_ = true;
  last_ = now;
  std::fprintf(stderr, "\r\033[K%s %3d%% (%s of %s %s)", what_.c_str(),
               static_cast<int>(100 * done / total), thousands(done).c_str(),
               thousands(total).c_str(), unit_.c_str());
  std::fflush(stderr);
}

}  // namespace surfcomp::tools::console
