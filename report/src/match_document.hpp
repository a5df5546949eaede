// Internal to the report module: the result document of a match as a JSON object, which
// match_json writes and the HTML report embeds.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"

#include <nlohmann/json.hpp>

#include <string>

namespace surfcomp::report::detail {

/// The fields of the result-file table of docs/usage.md: reference, probe, alignments, trace,
/// timing_ms, cliques, warnings, parameters. top 0 lists every alignment (the merge tree and the
/// repeats); top N the first N distinct ones (Alignment::repeat_of 0).
nlohmann::json match_document(const matching::InputMatch& compared,
                              const matching::MatchOptions& options, std::size_t top = 0);

/// `document` as text, indented by `indent` spaces (-1: on one line). Invalid UTF-8 (a Latin-1
/// atom name or path) becomes U+FFFD rather than an exception.
std::string json_text(const nlohmann::json& document, int indent);

}  // namespace surfcomp::report::detail
