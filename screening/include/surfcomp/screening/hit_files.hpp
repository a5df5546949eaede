// A screen's hits as files: the molecules moved onto the query as SDF records tagged with their
// rank and score, or a pocket library's structures as PDB models, and a library's summary.
// `surfcomp screen`, `surfcomp library info` and the Python module use these functions.
#pragma once

#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/screening/library.hpp"
#include "surfcomp/screening/screen.hpp"

#include <cstddef>
#include <cstdint>
#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::screening {

/// `text` as one CSV field: as it is, or quoted (quotes doubled) when it holds a comma, a quote
/// or a line break.
std::string csv_field(const std::string& text);

/// Hit `hit` (row `rank`, 1-based) as one SDF record: its stored molecule moved into the
/// query's frame as an MDL block (io::moved_record_block: bonds and hydrogens as stored) with
/// the data items surfcomp_rank, surfcomp_entry (1-based), surfcomp_name, surfcomp_conformer
/// and surfcomp_score, ending with "$$$$".
std::string aligned_hit_record(const Library& library, const Hit& hit, std::size_t rank);

/// The first `count` hits as SDF records (aligned_hit_record).
void write_aligned_hits_sdf(std::ostream& out, const Library& library, const std::vector<Hit>& hits,
                            std::size_t count);

/// Hit `hit` (row `rank`, 1-based) of a pocket library as one PDB model: the atoms its entry
/// keeps (the site's neighbourhood, molsurf::site_neighbourhood; read with
/// site_entry_read_options(read)) moved into the query's frame, with a REMARK giving rank, entry,
/// name and score.
std::string aligned_site_model(const Library& library, const Hit& hit, std::size_t rank,
                               const io::MoleculeReadOptions& read);

/// The first `count` hits of a pocket library as PDB models (aligned_site_model), then END.
void write_aligned_sites_pdb(std::ostream& out, const Library& library,
                             const std::vector<Hit>& hits, std::size_t count,
                             const io::MoleculeReadOptions& read);

/// Every entry of `library` as an SDF record in its stored frame, with the data items
/// surfcomp_entry (1-based), surfcomp_name and surfcomp_conformer (`surfcomp library export`).
void write_library_sdf(std::ostream& out, const Library& library);

/// What `surfcomp library info` reports of a library.
struct LibrarySummary {
  std::size_t entries = 0;                                ///< conformers (entries) of the library
  std::size_t molecules = 0;                              ///< molecules (molecule_start_at)
  std::map<std::string, std::size_t> entries_per_source;  ///< input file -> its entries
  std::uint64_t file_bytes = 0;                           ///< the .sclib file's size, bytes
  std::uint64_t largest_entry_bytes = 0;                  ///< the largest encoded entry, bytes
};

/// The summary of `library`, read from its index and its entries' sizes.
LibrarySummary summarize_library(const Library& library);

}  // namespace surfcomp::screening
