// The file extension that picks a reader or writer.
#pragma once

#include <filesystem>
#include <string>

namespace surfcomp::io {

/// The extension of `path` with its dot, in ASCII lower case ("1THL.SDF" -> ".sdf"); empty when
/// the file name has none. Readers and writers choose a format by it, so "X.PLY" reads as PLY.
std::string lowercase_extension(const std::filesystem::path& path);

}  // namespace surfcomp::io
