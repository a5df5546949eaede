// `surfcomp screen --receptor`: the screen's structure-based form, in its own file.
#pragma once

#include <string>
#include <vector>

namespace surfcomp::tools {

/// True when `args` ask for a receptor screen (--receptor given).
bool asks_receptor_screen(const std::vector<std::string>& args);

/// `surfcomp screen --receptor RECEPTOR LIB.sclib -o hits.csv [options]`.
int screen_receptor(const std::vector<std::string>& args);

}  // namespace surfcomp::tools
