// The one line every docking option check throws: "name: value is not domain".
#pragma once

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <string>

namespace surfcomp::docking::detail {

/// Throws OptionError naming `field` (in the caller's spelling) unless `ok`.
inline void require_option(bool ok, const char* field, double value, const char* domain) {
  if (!ok) {
    throw OptionError(options::named(field) + ": " + std::to_string(value) + " is not " + domain);
  }
}

}  // namespace surfcomp::docking::detail
