// The JSON documents the subcommands write (cp-detect's points, patch-map's index).
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace surfcomp::tools {

/// `document` as text indented by two spaces, ending with a newline. Invalid UTF-8 (a Latin-1
/// file name, say) becomes U+FFFD rather than an exception.
inline std::string json_text(const nlohmann::json& document) {
  return document.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace surfcomp::tools
