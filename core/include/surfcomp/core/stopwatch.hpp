// A wall-clock stopwatch on the monotonic clock, for the timings the program reports and the
// benchmarks measure.
#pragma once

#include <chrono>

namespace surfcomp {

/// Time since construction or the last restart(), on std::chrono::steady_clock (never goes
/// back when the system clock is set).
class Stopwatch {
 public:
  /// Starts from now.
  void restart() { start_ = std::chrono::steady_clock::now(); }

  /// Milliseconds since the start.
  double elapsed_ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }

  /// Seconds since the start.
  double elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace surfcomp
