// The files one run of a front end (a subcommand, a Python call) reads and writes, declared in
// one place before any work so that one check refuses every output that could destroy an input
// or another output, or that could not be written at the end of a long run.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::io {

/// A file the subcommand reads.
struct InputFile {
  std::string name;            ///< how messages name it: "INPUT", "REF", "PROBE", "--molecule"
  std::filesystem::path path;  ///< empty when the option was not given
};

/// A file the subcommand writes.
struct OutputFile {
  std::string option;                ///< the option naming it: "--output", "--points-out"
  std::filesystem::path path;        ///< empty when the option was not given
  std::vector<std::string> formats;  ///< the extensions it may have, lower case with the dot;
                                     ///< empty: any name (a JSON document)
  std::string formats_reason;        ///< why only these formats, for the message; may be empty
};

/// Every file one run of a subcommand reads and writes.
struct CommandFiles {
  std::vector<InputFile> inputs;
  std::vector<OutputFile> outputs;
};

/// Whether `a` and `b` name one file: std::filesystem::equivalent when both exist (hard and
/// symbolic links included), otherwise their absolute, weakly canonical paths are equal (so
/// "./l.pdb", "l.pdb" and "dir/../l.pdb" are one file, and so are paths through a linked folder).
bool same_file(const std::filesystem::path& a, const std::filesystem::path& b);

/// The check every subcommand makes once its options are parsed and before it reads or builds
/// anything. Throws OptionError (exit status 2) when an output's extension is not one of its
/// formats, when an output is the same file as an input ("--output l.pdb is the same file as
/// INPUT ./l.pdb: ..."), or when two outputs are one file; FileError (exit status 1) when an
/// output exists but is not a regular file, or its folder does not exist or cannot be written.
void check_command_files(const CommandFiles& files);

}  // namespace surfcomp::io
