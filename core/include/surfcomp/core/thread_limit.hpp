// How many threads the library's parallel loops may use, as a front end sets it for one run.
#pragma once

#include <memory>

namespace surfcomp {

/// Limits TBB's parallel loops to `threads` worker threads while it lives; 0 leaves them every
/// core. Throws OptionError, naming the option as options::named("threads") does, when
/// `threads` is outside [0, 1024].
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

 private:
  struct Control;
  std::unique_ptr<Control> control_;
};

}  // namespace surfcomp
