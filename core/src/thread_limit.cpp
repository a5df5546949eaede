#include "surfcomp/core/thread_limit.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <tbb/global_control.h>

#include <string>

namespace surfcomp {

struct ThreadLimit::Control {
  explicit Control(std::size_t threads)
      : control(tbb::global_control::max_allowed_parallelism, threads) {}
  tbb::global_control control;
};

ThreadLimit::ThreadLimit(int threads) {
  constexpr int most = 1024;
  if (threads < 0 || threads > most) {
    throw OptionError(options::named("threads") + ": value " + std::to_string(threads) +
                      " is outside [0, " + std::to_string(most) + "]");
  }
  if (threads > 0) {
    control_ = std::make_unique<Control>(static_cast<std::size_t>(threads));
  }
}

ThreadLimit::~ThreadLimit() = default;

}  // namespace surfcomp
