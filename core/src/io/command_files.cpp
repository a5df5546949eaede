#include "surfcomp/core/io/command_files.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"

#include <algorithm>
#include <system_error>

#include <unistd.h>

namespace surfcomp::io {
namespace {

namespace fs = std::filesystem;

std::string listed(const std::vector<std::string>& formats) {
  std::string text;
  for (std::size_t i = 0; i < formats.size(); ++i) {
    if (i > 0) text += i + 1 == formats.size() ? " or " : ", ";
    text += formats[i];
  }
  return text;
}

void check_format(const OutputFile& output) {
  if (output.formats.empty()) return;
  const std::string extension = io::lowercase_extension(output.path);
  if (std::find(output.formats.begin(), output.formats.end(), extension) != output.formats.end())
    return;
  std::string message =
      output.option + " " + output.path.string() + ": use " + listed(output.formats);
  if (!output.formats_reason.empty()) message += " (" + output.formats_reason + ")";
  throw OptionError(message);
}

/// The output's folder exists and may be written; the output itself, if present, is a file the
/// finished one can replace.
void check_writable(const OutputFile& output) {
  std::error_code ec;
  const fs::file_status status = fs::status(output.path, ec);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    throw FileError(output.path.string(),
                    "exists and is not a regular file (" + output.option + ")");
  }
  const fs::path folder = output.path.has_parent_path() ? output.path.parent_path() : ".";
  if (!fs::is_directory(folder, ec)) {
    throw FileError(output.path.string(),
                    "the folder " + folder.string() + " does not exist (" + output.option + ")");
  }
  if (::access(folder.c_str(), W_OK | X_OK) != 0) {
    throw FileError(output.path.string(),
                    "the folder " + folder.string() + " is not writable (" + output.option + ")");
  }
}

}  // namespace

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    const bool equivalent = fs::equivalent(a, b, ec);
    if (!ec) return equivalent;
  }
  // Absolute first: the weakly canonical form of a relative path whose first part does not
  // exist stays relative, so "x.pdb" and "./x.pdb" would differ.
  std::error_code ec_a, ec_b;
  const fs::path canonical_a = fs::weakly_canonical(fs::absolute(a, ec_a), ec_a);
  const fs::path canonical_b = fs::weakly_canonical(fs::absolute(b, ec_b), ec_b);
  if (ec_a || ec_b) return a.lexically_normal() == b.lexically_normal();
  return canonical_a.lexically_normal() == canonical_b.lexically_normal();
}

void check_command_files(const CommandFiles& files) {
  std::vector<const OutputFile*> given;
  for (const OutputFile& output : files.outputs) {
    if (!output.path.empty()) given.push_back(&output);
  }
  for (const OutputFile* output : given) check_format(*output);
  for (std::size_t i = 0; i < given.size(); ++i) {
    const OutputFile& output = *given[i];
    for (const InputFile& input : files.inputs) {
      if (!input.path.empty() && same_file(output.path, input.path)) {
        throw OptionError(output.option + " " + output.path.string() + " is the same file as " +
                          input.name + " " + input.path.string() +
                          ": refusing to overwrite an input");
      }
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (same_file(output.path, given[j]->path)) {
        throw OptionError(given[j]->option + " " + given[j]->path.string() + " and " +
                          output.option + " " + output.path.string() +
                          " are the same file: give each output its own name");
      }
    }
  }
  for (const OutputFile* output : given) check_writable(*output);
}

}  // namespace surfcomp::io
