// Building a screening library from molecule files: each record read (or its conformers
// generated), its surface built and sampled as `surfcomp match` does, in parallel (TBB), the
// entries written in input order whatever the thread count. A build of many records is cut into
// shards of consecutive records, which several processes can build (ShardedLibraryBuild) and an
// interrupted build can resume. A pocket library is built the same way from a site list, or from
// structures whose every detected pocket is a site: each site's structure surfaced and its
// pocket lining sampled as a binding-site match does.
#pragma once

#include "surfcomp/core/conformers.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/option_table.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "surfcomp/molsurf/pockets.hpp"
#include "surfcomp/screening/library.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace surfcomp::screening {

/// How far a build has come, for a progress line.
struct BuildProgress {
  std::size_t records_done = 0;
  std::size_t records = 0;
  std::size_t entries = 0;  ///< entries written so far
  std::size_t skipped = 0;  ///< records skipped so far
  double seconds = 0.0;     ///< since the build started
};

struct LibraryBuildOptions {
  /// Default none: each record's own coordinates make one entry (conformer 0). With a value,
  /// ETKDG + MMFF conformers (generate_conformers) make the entries; SMILES records need this.
  std::optional<ConformerOptions> conformers;
  /// How the molecules are read (charges, lipophilicity); default as `surfcomp match`.
  io::MoleculeReadOptions read;
  /// The surface built for each entry; default as `surfcomp match`.
  molsurf::MolecularSurfaceOptions surface;
  /// Default OverlayOptions::spacing. Cell edge of the surface sample, A; a screen refuses a
  /// library sampled otherwise than its overlay. > 0.
  double spacing = matching::OverlayOptions{}.spacing;
  /// Default OverlayOptions::sigma. The Gaussian width (A) the samples' self-overlaps are
  /// packed with; a screen at another width packs them again as it reads them. > 0.
  double sigma = matching::OverlayOptions{}.sigma;
  /// Sites (build_site_library): the spheres around a site ligand's atoms (sphere_radius,
  /// default 4 A, as `surfcomp match --site-radius`) and the chains kept.
  molsurf::BindingSiteOptions site;
  /// Sites: the pocket lining sampled is the vertices within this distance of the site's
  /// critical points (default as `surfcomp match --site-overlay-radius`). Finite, > 0.
  double lining_radius = matching::SiteMatchOptions{}.overlay_radius;
  /// Pockets (build_pocket_library): how each structure's pockets are detected.
  molsurf::PocketOptions pockets;
  /// Default false. Mesh inputs are repaired first (molsurf::SurfaceInputOptions::repair).
  bool repair = false;
  /// Default 64. Most records in flight (being built or waiting for their turn to be written):
  /// bounds the memory a build holds. >= 1.
  std::size_t batch = 64;
  /// Default 1000. Consecutive input records per shard: a build of more records writes a
  /// sharded library (an index at the output, the shards in the folder beside it,
  /// shard_folder), of at most this many one library file. >= 1.
  std::size_t shard_records = 1000;
  /// Default false. A sharded build continues the build an interrupted run left in the shard
  /// folder (ShardedLibraryBuild::prepare); without it an existing shard folder is refused.
  bool resume = false;
  /// Default none. Called after each record is written or skipped, one call at a time.
  std::function<void(const BuildProgress&)> progress;
};

/// The user's options of LibraryBuildOptions: --conformers (0: the records' own coordinates,
/// else that many ETKDG + MMFF conformers), --seed (ETKDG's, with --conformers),
/// --shard-records, --resume, --site-radius and --site-margin (a pocket library).
const options::Table<LibraryBuildOptions>& library_build_option_table();

/// A record the build left out, and why.
struct SkippedRecord {
  std::string source;
  std::size_t record = 0;
  std::string name;
  std::string reason;  ///< the error's message, one line
};

/// Where a build's time goes, seconds summed over the threads (core-seconds).
struct BuildTimes {
  double conformers = 0.0;  ///< generating conformers (RDKit ETKDG + MMFF, their mol blocks)
  double entries = 0.0;     ///< the rest of each entry: reading, sampling, packing
};

struct LibraryBuildResult {
  std::size_t records = 0;  ///< records read from the inputs
  std::size_t entries = 0;  ///< entries written
  std::uint64_t bytes = 0;  ///< size of the library file (a sharded library: index and shards)
  std::vector<SkippedRecord> skipped;
  double seconds = 0.0;             ///< wall-clock
  BuildTimes times;                 ///< of the records built and skipped
  std::size_t shards = 1;           ///< the shards the records were cut into; 1: one file
  std::size_t shards_resumed = 0;   ///< shards an interrupted build had finished (resume)
  std::size_t entries_resumed = 0;  ///< the entries of those shards
};

/// Writes the log of a build that made `library`: a line "# surfcomp library build -> LIBRARY:
/// R records, E entries, S skipped", a header line "# source<TAB>record<TAB>name<TAB>reason",
/// then one line per skipped record in that order (a tab or line break inside a field written as
/// a space).
void write_build_log(std::ostream& out, const std::filesystem::path& library,
                     const LibraryBuildResult& result);

/// The records of `inputs` in order: each file's records (io::read_molecule_records), for a
/// .hsi file one io::RecordFormat::descriptors record and for a mesh file one
/// io::RecordFormat::mesh record (both read when their entry is built); a directory stands for
/// those files (io::is_record_file, .hsi, mesh::io::is_mesh_file) directly inside it, in name
/// order. Throws as read_molecule_records, InputError for a path that is none of these or for
/// meshes mixed with molecules (a library holds one kind), and FileError naming the inputs when
/// they hold no record at all.
std::vector<io::MoleculeRecord> read_library_inputs(
    const std::vector<std::filesystem::path>& inputs);

/// The entries of one record: its own coordinates, or its conformers, each with its screening
/// sample (matching::sample_molecule) and heteroatoms, packed; for a .hsi file, one entry with
/// the sample of the file's surface (read_hsi) and its heavy atoms (LibraryEntry::surface); for
/// a mesh, one entry holding the mesh as read (with options.repair, repaired). Adds
/// its time to `times` when given. Throws what reading the record, generating its conformers or
/// building a surface throws (surfcomp::Error).
std::vector<LibraryEntry> build_entries(const io::MoleculeRecord& record,
                                        const LibraryBuildOptions& options = {},
                                        BuildTimes* times = nullptr);

/// One line of a site list: a structure and a binding site on it.
struct SiteRequest {
  std::size_t line = 0;             ///< 1-based line number
  std::filesystem::path structure;  ///< PDB/PQR file; relative paths are the list's folder's
  /// The site ligand (residue name, chain if given), or none when the site is `spheres`.
  std::optional<LigandSelector> ligand;
  std::vector<molsurf::SiteSphere> spheres;
  /// "<structure's stem>:<ligand>[:<chain>]", "<stem>:spheres<line>" or, for a pocket,
  /// "<stem>:pocket<rank>"
  std::string name;
  /// The spheres are a detected pocket's: the site's structure is the structure's ATOM records
  /// (molsurf::pocket_structure), as the pocket was found on them.
  bool pocket = false;
  /// A site list's `STRUCTURE pocket N`: pocket N of the structure (molsurf::pocket_site with
  /// LibraryBuildOptions::pockets), found when the entry is built; 0 otherwise.
  int pocket_rank = 0;
};

/// The structure files of `inputs` (PDB .pdb .ent, mmCIF .cif .mmcif .cif.gz); a directory
/// stands for those directly inside it, in name order. Throws InputError for a path that is
/// neither, FileError naming the inputs when they hold none.
std::vector<std::filesystem::path> structure_files(
    const std::vector<std::filesystem::path>& inputs);

/// The structures of a pocket library: every pocket molsurf::detect_pockets finds in each (on
/// its ATOM records, options.pockets) is one site entry, named "<stem>:pocket<rank>".
struct PocketStructures {
  std::vector<std::filesystem::path> files;  ///< structure_files' order
};

/// The sites of a site list: one per line, `STRUCTURE LIGAND [CHAIN]` (LIGAND as
/// parse_ligand_selector reads it, RES[:CHAIN[:NUMBER]]; a third word sets the chain),
/// `STRUCTURE x,y,z,r [x,y,z,r ...]` or `STRUCTURE pocket N` (the structure's pocket N, named
/// "<stem>:pocketN"; whitespace-separated; blank lines and lines starting with '#' are skipped).
/// Throws FileError when the list cannot be read or lists no site, and InputError naming the list
/// and line for a line of neither form or with a sphere whose radius is not > 0; the structures are
/// read only when their entries are built.
std::vector<SiteRequest> read_site_list(const std::filesystem::path& list);

/// The entry of one site: its structure read (`options.read`), the site built
/// (molsurf::binding_site with options.site), the site's structure surfaced
/// (options.surface) and described at the site's critical points (matching::describe_site),
/// and its pocket lining (matching::pocket_lining, options.lining_radius) sampled. The entry's
/// molecule is the site's structure as PDB text (water and the site ligand's copy removed), its
/// spheres the site's. Throws what those steps throw (surfcomp::Error).
LibraryEntry build_site_entry(const SiteRequest& request, const LibraryBuildOptions& options = {});

/// build_library for a pocket library: one entry per site, in list order; a site whose entry
/// cannot be built is skipped and listed (SkippedRecord::source the structure, record the
/// list's line, name the site's name). More sites than options.shard_records make a sharded
/// library, as build_library.
LibraryBuildResult build_site_library(const std::vector<SiteRequest>& sites,
                                      const std::filesystem::path& output,
                                      const LibraryBuildOptions& options = {});

/// build_library for a pocket library of structures: the entries of each structure's pockets in
/// rank order, the structures in order (a structure is one record: options.shard_records counts
/// structures). A structure that cannot be read or holds no pocket is skipped and listed (record
/// 0, name its stem), as is a pocket whose entry cannot be built (record its rank, name its
/// site's name).
LibraryBuildResult build_pocket_library(const PocketStructures& structures,
                                        const std::filesystem::path& output,
                                        const LibraryBuildOptions& options = {});

/// The `settings` text a build with `options` stores in its library.
std::string build_settings(const LibraryBuildOptions& options, bool sites = false);

/// Builds the entries of every record (in parallel, TBB) and writes them, in record order then
/// conformer order, to `output` atomically: an interrupted or failed build leaves no file
/// there. A record whose entries cannot be built is skipped and listed in the result; the build
/// goes on. When no entry is built (result.entries 0), nothing is written: a file already at
/// `output` is left as it was. The file's bytes do not depend on the thread count. Throws
/// OptionError for options outside their domain (before any work), FileError when `output` cannot
/// be written. More records than options.shard_records make a sharded library, built shard by
/// shard in this process (ShardedLibraryBuild: prepare, build, finish), which throws as those do.
LibraryBuildResult build_library(const std::vector<io::MoleculeRecord>& records,
                                 const std::filesystem::path& output,
                                 const LibraryBuildOptions& options = {});

/// The folder of the shards of the sharded library whose index is `output`: "OUTPUT.d" beside
/// it (target.sclib -> target.sclib.d).
std::filesystem::path shard_folder(const std::filesystem::path& output);

/// A build cut into shards of options.shard_records consecutive records (molecule records, sites
/// or structures), shard k (0-based)
/// holding records [k N, (k + 1) N): a format-5 library file in shard_folder(output) named by
/// its 1-based number (000001.sclib ...), with a log of its skipped records beside it
/// (000001.log), written once the shard is complete. A shard whose records were all skipped has
/// a log and no library file. The output is the index of the shards that have entries
/// (write_library_index). A shard's bytes do not depend on which process built it, on the number
/// of processes or on the thread count: its settings are the build's settings and its number,
/// records and input hash (a 64-bit hash of its records' source, record number, name, format and
/// text; of a site's structure path, size and modification time, line, name, ligand and
/// spheres; of a structure's path, size and modification time). A manifest (manifest.txt in the
/// folder: the settings, the shard size and count, the record count and each shard's input hash)
/// records what the folder is being built from.
///
/// One process calls prepare(), then build() on every process (each building its share of the
/// shards), then, once all have returned, finish() on the process that called prepare().
class ShardedLibraryBuild {
 public:
  /// The plan of a build of `records` (kept by reference: they must outlive this object) to
  /// `output`. Reads and writes nothing. Throws OptionError for options outside their domain,
  /// InputError for no record.
  ShardedLibraryBuild(const std::vector<io::MoleculeRecord>& records, std::filesystem::path output,
                      LibraryBuildOptions options);
  /// The plan of a pocket library of `sites` (kept by reference), as build_site_library. Throws
  /// OptionError as above and for options.conformers, InputError for no site.
  ShardedLibraryBuild(const std::vector<SiteRequest>& sites, std::filesystem::path output,
                      LibraryBuildOptions options);
  /// The plan of a pocket library of `structures` (kept by reference), as build_pocket_library.
  /// Throws as the sites' plan, InputError for no structure.
  ShardedLibraryBuild(const PocketStructures& structures, std::filesystem::path output,
                      LibraryBuildOptions options);
  // The inputs are kept by reference: a temporary would not outlive the plan.
  ShardedLibraryBuild(std::vector<io::MoleculeRecord>&&, std::filesystem::path,
                      LibraryBuildOptions) = delete;
  ShardedLibraryBuild(std::vector<SiteRequest>&&, std::filesystem::path,
                      LibraryBuildOptions) = delete;
  ShardedLibraryBuild(PocketStructures&&, std::filesystem::path, LibraryBuildOptions) = delete;
  ShardedLibraryBuild(const ShardedLibraryBuild&) = delete;
  ShardedLibraryBuild& operator=(const ShardedLibraryBuild&) = delete;
  ~ShardedLibraryBuild();

  std::size_t shards() const;
  const std::filesystem::path& folder() const;

  /// Before any shard is built. A fresh build creates the folder and writes the manifest; when
  /// the folder exists it throws FileError naming it unless options.resume. Resuming (the folder
  /// exists): throws InputError naming the manifest when it is missing or records other inputs
  /// or options (the first line that differs), FileError or FormatError naming a shard file
  /// that does not open, whose settings are not its own or whose entries do not match their
  /// checksums; after those checks, removes the temporary files an interrupted write left in the
  /// folder (io::is_temporary_file). Nothing in the folder is changed when it throws.
  void prepare();
  /// Builds the shards k with k % ranks == rank that are not finished (a shard is finished when
  /// its log is written and, unless all its records were skipped, its library file exists),
  /// writing each shard's file and then its log atomically. options.progress sees this call's
  /// records (records_done of records, over its shards). Returns this call's records, entries,
  /// bytes, skipped records, times and seconds. Throws what building a shard throws (FileError
  /// when a file cannot be written).
  LibraryBuildResult build(std::size_t rank = 0, std::size_t ranks = 1);
  /// Once every shard is finished: writes the index at the output atomically (none when no
  /// shard has an entry) and returns the build's records, entries, bytes (index and shards),
  /// skipped records of every shard in record order, shard counts and, when prepare() ran in
  /// this object, the shards it found finished; times and seconds are left 0 (the builders').
  /// Throws FileError naming the log of a shard that is not finished, and what
  /// write_library_index throws.
  LibraryBuildResult finish() const;
  /// The whole build in this process: one library file at the output when there is one shard,
  /// else prepare(), build() and finish(), with the builders' times and the wall-clock.
  LibraryBuildResult run();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace surfcomp::screening
