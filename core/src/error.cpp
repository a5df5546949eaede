#include "surfcomp/core/error.hpp"

namespace surfcomp {

FileError::FileError(const std::string& file, const std::string& reason)
    : InputError(file + ": " + reason) {}

FormatError::FormatError(const std::string& file, std::size_t line, const std::string& reason)
    : InputError(line > 0 ? file + ":" + std::to_string(line) + ": " + reason
                          : file + ": " + reason) {}

FormatError::FormatError(const std::string& file, const std::string& reason)
    : FormatError(file, 0, reason) {}

}  // namespace surfcomp
