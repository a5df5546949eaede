// The project's exception hierarchy. Every error a library function throws derives from
// surfcomp::Error, so a tool can turn any of them into a one-line message and a non-zero exit.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace surfcomp {

/// Base of every exception the library throws. what() is one line, no trailing newline.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input data or options (not a bug, not a numerical failure).
class InputError : public Error {
 public:
  using Error::Error;
};

/// A file that cannot be opened, read or written. Message: "FILE: reason".
class FileError : public InputError {
 public:
  FileError(const std::string& file, const std::string& reason);
};

/// A file whose contents do not follow its format. Message: "FILE:LINE: reason"
/// (line 0 means the position is not a line, e.g. in a binary file).
class FormatError : public InputError {
 public:
  FormatError(const std::string& file, std::size_t line, const std::string& reason);
  FormatError(const std::string& file, const std::string& reason);
};

/// A command-line option or Options field with a value outside its domain.
class OptionError : public InputError {
 public:
  using InputError::InputError;
};

/// A mesh that is not what an algorithm requires (non-manifold, open, empty, degenerate).
class TopologyError : public Error {
 public:
  using Error::Error;
};

/// A numerical failure: a singular system, a non-finite value where a finite one is needed.
class NumericError : public Error {
 public:
  using Error::Error;
};

}  // namespace surfcomp
