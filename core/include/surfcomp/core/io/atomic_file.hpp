// Writing an output file so that a failure never leaves a partial file behind.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>

namespace surfcomp::io {

/// Calls `write` with a binary stream to a temporary file beside `path`, then renames it onto
/// `path`. If `write` throws or the stream fails, the temporary file is removed, `path` is
/// untouched, and the exception propagates (stream failures as FileError naming `path`).
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

/// Whether `path` is named as write_file_atomically names its temporary files
/// (".surfcomp-PID-N-HASH.tmp"): what an interrupted write that no signal handler could clean up
/// (SIGKILL, a crash) leaves beside its output.
bool is_temporary_file(const std::filesystem::path& path);

/// Makes SIGINT, SIGTERM and SIGHUP remove the temporary files of the writes in progress before
/// the process ends by the signal as it would have without this. A signal the process ignores
/// or handles already is left as it is. For a program's `main`: a library leaves the process's
/// signal handling to its host (Python keeps its own SIGINT).
void remove_temporary_files_on_signals();

}  // namespace surfcomp::io
