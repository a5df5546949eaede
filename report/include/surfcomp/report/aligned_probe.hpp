// A match's probe moved by an alignment, as a file: its surface (PLY), its molecule (PDB) or,
// for an SDF, MOL or MOL2 probe, its record with bonds kept (SDF). `surfcomp match
// --aligned-out` writes it with these functions.
#pragma once

#include "surfcomp/matching/match_inputs.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace surfcomp::report {

/// The extensions the moved probe can be written as: ".ply" for any probe, ".pdb" for a
/// molecule file, ".sdf" for an SDF, MOL or MOL2 file too.
std::vector<std::string> aligned_probe_formats(const std::filesystem::path& probe_path);

/// Writes `probe` (read from `probe_path`, its record `record`; 0: the file's only one) moved by
/// `transform` to `output`, in the format of its extension (aligned_probe_formats). Atomic.
void write_aligned_probe(const std::filesystem::path& output,
                         const std::filesystem::path& probe_path, std::size_t record,
                         const matching::PreparedInput& probe, const Eigen::Matrix4d& transform);

}  // namespace surfcomp::report
