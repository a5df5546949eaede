#include "surfcomp/core/io/atomic_file.hpp"

#include "surfcomp/core/error.hpp"

#include <array>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <string_view>
#include <system_error>
#include <thread>

#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

namespace surfcomp::io {
namespace {

/// How a temporary file's name begins and ends (is_temporary_file).
constexpr std::string_view kTemporaryPrefix = ".surfcomp-", kTemporarySuffix = ".tmp";

/// A hidden name beside `path` that no other writer uses at the same time: the process id, a
/// count of this process's writes and a hash of the file name. It is short whatever the length
/// of the name, so any name the file system accepts can be written.
std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> writes{0};
  char name[64];
  std::snprintf(name, sizeof name, "%s%ld-%u-%016zx%s", kTemporaryPrefix.data(),
                static_cast<long>(::getpid()), writes++,
                std::hash<std::string>{}(path.filename().string()), kTemporarySuffix.data());
  return path.parent_path() / name;
}

/// The names of the temporary files being written, where a signal handler can read them: static
/// storage (never freed), each slot published by its state only once its name is complete, and
/// taken by the handler (live -> removing) before it reads the name, so that no writer reuses a
/// slot while the handler reads it.
struct TemporarySlot {
  enum State : int { vacant, claimed, live, removing };
  std::atomic<int> state{vacant};
  char name[PATH_MAX] = {};
};
std::array<TemporarySlot, 64> temporary_slots;

/// Holds a slot with the name of one temporary file while the file may exist. A name longer
/// than a slot, or a 65th write at once, goes unlisted: a signal then leaves that file behind.
class ListedTemporary {
 public:
  explicit ListedTemporary(const std::filesystem::path& temp) {
    const std::string name = temp.string();
    if (name.size() >= sizeof(TemporarySlot::name)) return;
    for (TemporarySlot& slot : temporary_slots) {
      int expected = TemporarySlot::vacant;
      if (!slot.state.compare_exchange_strong(expected, TemporarySlot::claimed)) continue;
      std::memcpy(slot.name, name.c_str(), name.size() + 1);
      slot.state.store(TemporarySlot::live);
      slot_ = &slot;
      return;
    }
  }
  /// If a handler has taken the slot, the process is ending: wait for it.
  ~ListedTemporary() {
    if (!slot_) return;
    for (int expected = TemporarySlot::live;
         !slot_->state.compare_exchange_weak(expected, TemporarySlot::vacant);
         expected = TemporarySlot::live) {
      std::this_thread::yield();
    }
  }
  ListedTemporary(const ListedTemporary&) = delete;
  ListedTemporary& operator=(const ListedTemporary&) = delete;

 private:
  TemporarySlot* slot_ = nullptr;
};

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the states");

constexpr std::array<int, 3> kRemovingSignals{SIGINT, SIGTERM, SIGHUP};

/// Removes the listed temporaries, then ends the process by the signal's default action (or,
/// where that does nothing, as PID 1 in a container, by _exit with the shell's 128 + signal).
/// Only async-signal-safe calls; it never returns.
void remove_temporaries_and_end(int signal_number) {
  for (TemporarySlot& slot : temporary_slots) {
    int expected = TemporarySlot::live;
    if (slot.state.compare_exchange_strong(expected, TemporarySlot::removing)) {
      ::unlink(slot.name);
    }
  }
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  sigset_t just_this;
  sigemptyset(&just_this);
  sigaddset(&just_this, signal_number);
  ::raise(signal_number);
  ::pthread_sigmask(SIG_UNBLOCK, &just_this, nullptr);
  ::_exit(128 + signal_number);
}

}  // namespace

bool is_temporary_file(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  return name.size() > kTemporaryPrefix.size() + kTemporarySuffix.size() &&
         name.compare(0, kTemporaryPrefix.size(), kTemporaryPrefix) == 0 &&
         name.compare(name.size() - kTemporarySuffix.size(), kTemporarySuffix.size(),
                      kTemporarySuffix) == 0;
}

void remove_temporary_files_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_temporaries_and_end;
  sigemptyset(&action.sa_mask);
  for (const int signal_number : kRemovingSignals) sigaddset(&action.sa_mask, signal_number);
  for (const int signal_number : kRemovingSignals) {
    // A signal the process was started to ignore (nohup, `&` in a script) stays ignored.
    struct sigaction inherited {};
    if (::sigaction(signal_number, nullptr, &inherited) != 0) continue;
    if ((inherited.sa_flags & SA_SIGINFO) != 0 || inherited.sa_handler != SIG_DFL) continue;
    ::sigaction(signal_number, &action, nullptr);
  }
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  namespace fs = std::filesystem;
  const fs::path temp = temporary_beside(path);
  const ListedTemporary listed(temp);
  auto discard = [&temp] {
    std::error_code ignored;
    fs::remove(temp, ignored);
  };
  try {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw FileError(path.string(), "cannot open for writing");
    write(out);
    out.flush();
    if (!out) throw FileError(path.string(), "write failed (disk full?)");
    out.close();
    std::error_code ec;
    fs::rename(temp, path, ec);
    if (ec) throw FileError(path.string(), "cannot rename the finished file: " + ec.message());
  } catch (...) {
    discard();
    throw;
  }
}

}  // namespace surfcomp::io
