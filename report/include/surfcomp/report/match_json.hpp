// A match as JSON, the result file of `surfcomp match -o` (its fields are documented in
// docs/usage.md): the alignments, the graph trace, the timings, the clique search, the warnings and
// the parameters. The HTML report embeds the same objects.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"

#include <string>

namespace surfcomp::report {

/// The result document of `compared` (matched with `options`), as JSON text indented by two
/// spaces, ending with a newline.
std::string match_json(const matching::InputMatch& compared, const matching::MatchOptions& options);

}  // namespace surfcomp::report
