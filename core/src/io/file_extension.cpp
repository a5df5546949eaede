#include "surfcomp/core/io/file_extension.hpp"

#include <algorithm>
#include <cctype>

namespace surfcomp::io {

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace surfcomp::io
