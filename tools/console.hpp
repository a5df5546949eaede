// What a subcommand prints besides its output files: its summary on stdout, notes on stderr,
// progress lines on stderr when stderr is a terminal, and with --verbose each step as it ends.
// --quiet keeps only errors and warnings. Every subcommand takes -q/--quiet and -v/--verbose
// (parse_command_line adds them).
#pragma once

#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace surfcomp::tools::console {

enum class Level { quiet, normal, verbose };

void set_level(Level level);
Level level();

/// printf-style text on stdout, unless --quiet.
void summary(const char* format, ...) __attribute__((format(printf, 1, 2)));

/// "note: TEXT" on stderr, unless --quiet.
void note(const std::string& text);

/// "[  1.23 s] TEXT" on stderr with --verbose (seconds since the program started); nothing
/// otherwise.
void step(const std::string& text);

/// Whether progress lines are drawn: stderr is a terminal and not --quiet.
bool progress_shown();

/// A progress line on stderr ("WHAT 42% (420 of 1,000 UNIT)"), drawn once the work has run
/// for a second since its first report, at most ten times a second, and cleared when done ==
/// total; the next report starts a new run (one line may serve REF, then PROBE). Thread-safe:
/// a parallel loop may call it from every thread. Draws nothing when !progress_shown().
class ProgressLine {
 public:
  ProgressLine(std::string what, std::string unit);
  void operator()(std::int64_t done, std::int64_t total);

 private:
  std::string what_, unit_;
  bool enabled_;
  std::mutex mutex_;
  std::chrono::steady_clock::time_point start_, last_;
  bool started_ = false;  ///< a run is under way (its first report came)
  bool shown_ = false;
};

}  // namespace surfcomp::tools::console
