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
//             from version 2, then the heavy atoms (count, then element and position each)
// The file is a pure function of the SurfaceDescriptors: byte-identical for identical input.
#pragma once

#include "surfcomp/harmonic/surface_descriptors.hpp"

#include <cstdint>
#include <filesystem>
#include <vector>

namespace surfcomp::harmonic::io {

/// The version written. Version 1 files (no atoms) are still read, with no atoms.
inline constexpr std::uint32_t hsi_format_version = 2;

/// Encodes `descriptors` as the bytes of a .hsi file.
std::vector<std::uint8_t> encode_hsi(const SurfaceDescriptors& descriptors);

/// Decodes the bytes of a .hsi file (version 1 or 2). Throws FormatError naming `source` for a
/// wrong magic, a byte-swapped or unknown-version file, a size or checksum mismatch (truncated or
/// corrupt), or any inconsistent count or index inside.
SurfaceDescriptors decode_hsi(const std::vector<std::uint8_t>& bytes, const std::string& source);

/// Writes `descriptors` to `path` atomically (no partial file on failure).
void write_hsi(const SurfaceDescriptors& descriptors, const std::filesystem::path& path);

/// Reads a .hsi file. Throws FileError when it cannot be read, FormatError as decode_hsi.
SurfaceDescriptors read_hsi(const std::filesystem::path& path);

/// True for the extension .hsi (case-insensitive).
bool is_hsi_file(const std::filesystem::path& path);

}  // namespace surfcomp::harmonic::io
