// Opening an input file for reading, and the limits every reader applies to what it reads:
// the one home of "is this a file we may read" and "is this value a plausible coordinate".
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace surfcomp::io {

/// Largest input file a reader accepts: 4 GiB. A molecule, mesh or .hsi file this large would
/// need several times its size in memory once parsed.
inline constexpr std::uint64_t max_input_file_bytes = std::uint64_t{4} << 30;

/// Largest magnitude of a coordinate read from a file, A. A molecule or a surface spanning
/// more than 2 km is a corrupt file (a PDB's coordinate columns hold at most 1e4 A), and the
/// grids built over it would not fit in memory.
inline constexpr double max_coordinate_magnitude = 1e6;

/// Largest magnitude of an atom's charge read from a file, e. Real atoms carry at most a few
/// elementary charges (metal ions +4); a larger value is a corrupt or misaligned column.
inline constexpr double max_charge_magnitude = 10.0;

/// Largest atom radius read from a file, A. Atoms are 1-3 A and coarse-grained beads a few A;
/// a larger value is a corrupt or misaligned column, and the surface grid around it would not
/// fit in memory.
inline constexpr double max_atom_radius = 100.0;

/// The whole content of `path`, read with one bounded read of at most its size. Refuses,
/// with FileError "PATH: reason", a path that does not exist, is not a regular file (a
/// directory, FIFO, socket or device such as /dev/zero: "not a regular file"), cannot be
/// opened or read, or is larger than max_input_file_bytes. A FIFO is refused without waiting
/// for a writer. Every reader (molecules, meshes, .hsi) reads its input through this.
std::string read_input_file(const std::filesystem::path& path);

/// The decompressed content of the gzip file `path` (read with read_input_file), at most
/// max_input_file_bytes: FileError "PATH: decompresses to more than the limit ..." beyond it,
/// "PATH: cannot decompress (gzip): reason" for a damaged file.
std::string read_gzip_input_file(const std::filesystem::path& path);

/// `compressed` (a gzip stream) decompressed, with read_gzip_input_file's limit and messages,
/// naming `source`.
std::string gunzip(const std::string& compressed, const std::string& source);

/// `text` as a gzip stream (no file name, time 0: the same bytes for the same text).
std::string gzip(const std::string& text);

/// Checks a position read from `file`: every coordinate finite and of magnitude at most
/// max_coordinate_magnitude. `item` names what the position belongs to ("vertex 12",
/// "atom 3 (C C1)"). Throws FormatError "FILE: ITEM has a non-finite coordinate" or
/// "FILE: ITEM has coordinate z = 1e+30 A, beyond the accepted magnitude 1e+06 A".
void check_read_position(const Eigen::Vector3d& position, const std::string& file,
                         const std::string& item);

/// Checks a per-item value read from `file` (a vertex property, an atom charge) is finite.
/// `name` says what the value is ("property 'charge'"). Throws FormatError
/// "FILE: ITEM has a non-finite NAME (nan)".
void check_read_value(double value, const std::string& file, const std::string& item,
                      const std::string& name);

/// Checks an atom charge read from line `line` of `file` (0: no line): finite and of magnitude
/// at most max_charge_magnitude. Throws FormatError "FILE:LINE: ITEM has charge 1e+30 e, beyond
/// the accepted magnitude 10 e" (or "a non-finite charge").
void check_read_charge(double charge, const std::string& file, std::size_t line,
                       const std::string& item);

/// Checks an atom radius read from line `line` of `file` (0: no line): finite, > 0 and at most
/// max_atom_radius. Throws FormatError "FILE:LINE: ITEM has radius 1e+30 A, beyond the accepted
/// 100 A" (or "a radius that is not positive").
void check_read_radius(double radius, const std::string& file, std::size_t line,
                       const std::string& item);

}  // namespace surfcomp::io
