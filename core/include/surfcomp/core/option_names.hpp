// Options named inside library messages. The library names an option by its field
// ("max_vertices"); each front end installs its own spelling once, before any work, so that a
// message reads as its user types the option: the command line "--max-vertices", Python
// "max_vertices" (a switch "repair=True"), C++ the field itself.
#pragma once

#include <string>

namespace surfcomp::options {

/// A front end's spelling of the option whose field is `field` (words joined by '_').
using Spelling = std::string (*)(const std::string& field);

/// Installs `spelling` for every later message, in every thread; nullptr restores the field's
/// own name. Front ends call it at start-up, before any thread of work begins.
void set_spelling(Spelling spelling);

/// The installed spelling's.
Spelling spelling();

/// The option of field `field` ("max_vertices") as the installed spelling writes it.
std::string named(const std::string& field);

/// The command line's spelling: "--" and the field's words joined by '-' ("--max-vertices").
std::string command_line_spelling(const std::string& field);

/// `spelling` installed for as long as the object lives, for a front end run inside another's
/// process (Python's surfcomp.main() runs the command line). Scopes may overlap, in one thread
/// or several: the first installs, the last to end restores what was installed before the
/// first. While one lives, messages of every thread take its spelling.
class ScopedSpelling {
 public:
  explicit ScopedSpelling(Spelling spelling);
  ~ScopedSpelling();
  ScopedSpelling(const ScopedSpelling&) = delete;
  ScopedSpelling& operator=(const ScopedSpelling&) = delete;
};

}  // namespace surfcomp::options
