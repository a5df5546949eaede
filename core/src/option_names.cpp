#include "surfcomp/core/option_names.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>

namespace surfcomp::options {
namespace {

std::string field_spelling(const std::string& field) { return field; }

std::atomic<Spelling> installed{&field_spelling};

std::mutex scopes_mutex;
int open_scopes = 0;                   // guarded by scopes_mutex
Spelling before_the_scopes = nullptr;  // guarded by scopes_mutex

}  // namespace

void set_spelling(Spelling spelling) {
  installed.store(spelling != nullptr ? spelling : &field_spelling);
}

Spelling spelling() { return installed.load(); }

std::string named(const std::string& field) { return installed.load()(field); }

ScopedSpelling::ScopedSpelling(Spelling spelling) {
  const std::lock_guard<std::mutex> lock(scopes_mutex);
  if (open_scopes++ == 0) {
    before_the_scopes = installed.load();
    set_spelling(spelling);
  }
}

ScopedSpelling::~ScopedSpelling() {
  const std::lock_guard<std::mutex> lock(scopes_mutex);
  if (--open_scopes == 0) set_spelling(before_the_scopes);
}

std::string command_line_spelling(const std::string& field) {
  std::string name = "--" + field;
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

}  // namespace surfcomp::options
