// The .hsi file: a surface with its critical points, patches, harmonic maps, images and the
// parameters that made them, so that a comparison never rebuilds them.
//
// Layout (all integers and doubles little-endian, whatever the host):
//   8 bytes   magic "SURFHSI\n"
//   u32       format version (hsi_format_version)
//   u32       0x01020304, the byte-order mark (reads 0x04030201 on a byte-swapped file)
//   u64       payload size in bytes
//   u64       FNV-1a 64 checksum of the payload
//   payload   parameters, surface (positions, normals, faces, named properties with their
//             stored types), critical points, then per point: status, patch, map, image;
//             from version 2, then the heavy atoms (count, then element and position each);
//             from version 3, then the length unit (f64) of a general mesh described in one
//             (written only then: a description in A is written as version 2)
// The file is a pure function of the SurfaceDescriptors: byte-identical for identical input.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace surfcomp::harmonic::io {

/// The newest version, written for a description whose length_unit is not 1 (version 2
/// otherwise). Version 1 files (no atoms) are still read, with no atoms.
inline constexpr std::uint32_t hsi_format_version = 3;

/// Largest stored length unit.
inline constexpr double max_stored_unit = 1e12;

/// Encodes `descriptors` as the bytes of a .hsi file.
std::vector<std::uint8_t> encode_hsi(const SurfaceDescriptors& descriptors);

/// Largest stored length parameter (critical point, disc and patch radii), A; radii must be
/// positive (at least 1e-6 of this), the disc radius may be 0, the patch margin is in [0, 1].
inline constexpr double max_stored_length = 1000.0;
/// Largest stored image grid: the ranges surfcomp hsi-build accepts.
inline constexpr int max_stored_rings = 1024;
inline constexpr int max_stored_sectors = 4096;

/// Decodes the bytes of a .hsi file (version 1, 2 or 3). Throws FormatError naming `source` for a
/// wrong magic, a byte-swapped or unknown-version file, a size or checksum mismatch (truncated or
/// corrupt), any count that cannot fit in the bytes left (checked before allocating), any index
/// outside its array, a parameter out of range (see the limits above), a non-finite stored
/// value (a critical point's esp and lp may be NaN where the surface lacks that property), or
/// a vertex or critical point position beyond surfcomp::io::max_coordinate_magnitude.
SurfaceDescriptors decode_hsi(const std::vector<std::uint8_t>& bytes, const std::string& source);
/// As above, on `n_bytes` bytes at `data`.
SurfaceDescriptors decode_hsi(const std::uint8_t* data, std::size_t n_bytes,
                              const std::string& source);

/// Writes `descriptors` to `path` atomically (no partial file on failure).
void write_hsi(const SurfaceDescriptors& descriptors, const std::filesystem::path& path);

/// Reads a .hsi file with surfcomp::io::read_input_file. Throws FileError when it cannot be
/// read (missing, not a regular file, larger than surfcomp::io::max_input_file_bytes),
/// FormatError as decode_hsi.
SurfaceDescriptors read_hsi(const std::filesystem::path& path);

/// True for the extension .hsi (case-insensitive).
bool is_hsi_file(const std::filesystem::path& path);

}  // namespace surfcomp::harmonic::io
