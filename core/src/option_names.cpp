#include "surfcomp/core/option_names.hpp"

#include <algorithm>
#include <atomic>

namespace surfcomp::options {
namespace {

std::string field_spelling(const std::string& field) { return field; }

std::atomic<Spelling> installed{&field_spelling};

}  // namespace

void set_spelling(Spelling spelling) {
  installed.store(spelling != nullptr ? spelling : &field_spelling);
}

Spelling spelling() { return installed.load(); }

std::string named(const std::string& field) { return installed.load()(field); }

std::string command_line_spelling(const std::string& field) {
  std::string name = "--" + field;
  std::replace(name.begin(), name.end(), '_', '-');
  return name;
}

}  // namespace surfcomp::options
