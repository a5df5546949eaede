#include "surfcomp/core/io/atomic_file.hpp"

#include "surfcomp/core/error.hpp"

#include <array>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <system_error>

#include <limits.h>
#include <signal.h>
#include <unistd.h>

namespace surfcomp::io {
namespace {

/// A hidden name beside `path` that no other writer uses at the same time: the process id, a
/// count of this process's writes and a hash of the file name. It is short whatever the length
/// of the name, so any name the file system accepts can be written.
std::filesystem::path temporary_beside(const std::filesystem::path& path) {
  static std::atomic<unsigned> writes{0};
  char name[64];
  std::snprintf(name, sizeof name, ".surfcomp-%ld-%u-%016zx.tmp", static_cast<long>(::getpid()),
                writes++, std::hash<std::string>{}(path.filename().string()));
  return path.parent_path() / name;
}

/// The names of the temporary files being written, where a signal handler can read them: static
/// storage (never freed), each slot published by its state only once its name is complete.
struct TemporarySlot {
  enum State : int { vacant, claimed, live };
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
  ~ListedTemporary() {
    if (slot_) slot_->state.store(TemporarySlot::vacant);
  }
  ListedTemporary(const ListedTemporary&) = delete;
  ListedTemporary& operator=(const ListedTemporary&) = delete;

 private:
  TemporarySlot* slot_ = nullptr;
};

static_assert(std::atomic<int>::is_always_lock_free, "the signal handler reads the states");

/// Only async-signal-safe calls: unlink, sigaction, raise.
void remove_temporaries_and_raise(int signal_number) {
  for (TemporarySlot& slot : temporary_slots) {
    if (slot.state.load() == TemporarySlot::live) ::unlink(slot.name);
  }
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  std::raise(signal_number);
}

}  // namespace

void remove_temporary_files_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_temporaries_and_raise;
  sigemptyset(&action.sa_mask);
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
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
