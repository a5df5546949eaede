// A match as JSON, the result file of `surfcomp match -o` (its fields are documented in
// docs/usage.md): the alignments, the graph trace, the timings, the clique search, the warnings and
// the parameters. The HTML report embeds the same objects.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"

#include <string>

namespace surfcomp::report {

/// The result document of `compared` (matched with `options`), as JSON text indented by two
/// spaces, ending with a newline: its first `top` distinct alignments (Alignment::repeat_of 0),
/// or with top 0 every alignment, the whole merge tree and the repeats.
std::string match_json(const matching::InputMatch& compared, const matching::MatchOptions& options,
                       std::size_t top = 0);

}  // namespace surfcomp::report
