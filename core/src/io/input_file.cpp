#include "surfcomp/core/io/input_file.hpp"

#include "surfcomp/core/error.hpp"

#include <boost/iostreams/device/back_inserter.hpp>
#include <boost/iostreams/filter/gzip.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace surfcomp::io {
namespace {

/// Closes a POSIX file descriptor when it goes out of scope.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

std::string describe_errno(int error) { return std::strerror(error); }

std::string number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

}  // namespace

std::string read_input_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  // O_NONBLOCK: opening a FIFO must not wait for a writer; it is refused below anyway.
  const Descriptor file(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (file.get() < 0) {
    const int error = errno;
    if (error == ENOENT) throw FileError(name, "no such file");
    throw FileError(name, "cannot open for reading (" + describe_errno(error) + ")");
  }
  // The checks are made on the opened file, so the path cannot change between them and the read.
  struct stat status {};
  if (::fstat(file.get(), &status) != 0) {
    throw FileError(name, "cannot read its status (" + describe_errno(errno) + ")");
  }
  if (!S_ISREG(status.st_mode)) throw FileError(name, "not a regular file");
  const auto size = static_cast<std::uint64_t>(status.st_size);
  if (size > max_input_file_bytes) {
    throw FileError(name,
                    "the file has " + std::to_string(size) + " bytes, more than the limit of " +
                        std::to_string(max_input_file_bytes) + " bytes (4 GiB) an input may have");
  }
  std::string data(static_cast<std::size_t>(size), '\0');
  std::size_t used = 0;
  while (used < data.size()) {
    const ssize_t got = ::read(file.get(), data.data() + used, data.size() - used);
    if (got < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      throw FileError(name, "read error (" + describe_errno(errno) + ")");
    }
    if (got == 0) break;  // the file shrank while being read: keep what it holds now
    used += static_cast<std::size_t>(got);
  }
  data.resize(used);
  return data;
}

std::string read_gzip_input_file(const std::filesystem::path& path) {
  return gunzip(read_input_file(path), path.string());
}

std::string gzip(const std::string& text) {
  namespace bio = boost::iostreams;
  std::string compressed;
  bio::gzip_compressor compressor;
  bio::back_insert_device<std::string> sink(compressed);
  for (std::size_t at = 0; at < text.size();) {
    const std::streamsize taken = compressor.write(
        sink, text.data() + at,
        static_cast<std::streamsize>(std::min(std::size_t{1} << 16, text.size() - at)));
    if (taken <= 0) throw Error("gzip: the compressor made no progress");
    at += static_cast<std::size_t>(taken);
  }
  compressor.close(sink, std::ios_base::out);
  return compressed;
}

std::string gunzip(const std::string& compressed, const std::string& source) {
  namespace bio = boost::iostreams;
  // The decompressor is driven as an output filter: its close() is where a stream cut short is
  // caught (no end-of-stream marker, or a missing or partial trailer), which reading it as an
  // input filter lets pass as a shorter text.
  std::string text;
  bio::gzip_decompressor decompressor;
  bio::back_insert_device<std::string> sink(text);
  if (compressed.empty()) throw FileError(source, "the file is empty");
  constexpr std::size_t chunk = std::size_t{1} << 16;
  bool closing = false;
  try {
    for (std::size_t at = 0; at < compressed.size();) {
      const std::streamsize taken =
          decompressor.write(sink, compressed.data() + at,
                             static_cast<std::streamsize>(std::min(chunk, compressed.size() - at)));
      if (taken <= 0) throw FileError(source, "cannot decompress (gzip): no progress");
      at += static_cast<std::size_t>(taken);
      if (text.size() > max_input_file_bytes) {
        throw FileError(source, "decompresses to more than the limit of " +
                                    std::to_string(max_input_file_bytes) + " bytes");
      }
    }
    closing = true;
    decompressor.close(sink, std::ios_base::out);
  } catch (const Error&) {
    throw;
  } catch (const bio::gzip_error& e) {
    if (closing) {
      throw FileError(source,
                      "the compressed file is cut short: its gzip stream stops before its end "
                      "(a partial download or copy?)");
    }
    throw FileError(source, std::string("cannot decompress (gzip): ") + e.what());
  } catch (const std::exception& e) {
    throw FileError(source, std::string("cannot decompress (gzip): ") + e.what());
  }
  return text;
}

void check_read_position(const Eigen::Vector3d& position, const std::string& file,
                         const std::string& item) {
  for (int k = 0; k < 3; ++k) {
    const double value = position(k);
    const char axis = static_cast<char>('x' + k);
    if (!std::isfinite(value)) {
      throw FormatError(file,
                        item + " has a non-finite coordinate " + axis + " = " + number(value));
    }
    if (std::fabs(value) > max_coordinate_magnitude) {
      throw FormatError(file, item + " has coordinate " + axis + " = " + number(value) +
                                  " A, beyond the accepted magnitude " +
                                  number(max_coordinate_magnitude) + " A");
    }
  }
}

void check_read_value(double value, const std::string& file, const std::string& item,
                      const std::string& name) {
  if (!std::isfinite(value)) {
    throw FormatError(file, item + " has a non-finite " + name + " (" + number(value) + ")");
  }
}

void check_read_charge(double charge, const std::string& file, std::size_t line,
                       const std::string& item) {
  if (!std::isfinite(charge))
    throw FormatError(file, line, item + " has a non-finite charge (" + number(charge) + ")");
  if (std::fabs(charge) > max_charge_magnitude) {
    throw FormatError(file, line,
                      item + " has charge " + number(charge) +
                          " e, beyond the accepted magnitude " + number(max_charge_magnitude) +
                          " e");
  }
}

void check_read_radius(double radius, const std::string& file, std::size_t line,
                       const std::string& item) {
  if (!(radius > 0.0)) {
    throw FormatError(file, line, item + " has radius " + number(radius) + ", not positive");
  }
  if (radius > max_atom_radius) {
    throw FormatError(file, line,
                      item + " has radius " + number(radius) + " A, beyond the accepted " +
                          number(max_atom_radius) + " A");
  }
}

}  // namespace surfcomp::io
