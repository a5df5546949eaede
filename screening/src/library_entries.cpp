// A library's inputs and entries: the records of its input files and folders, the entries of
// one record (its conformers, or a mesh's or a .hsi file's surface), and a build's settings.
#include "library_build_items.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/overlay_sample.hpp"
#include "surfcomp/mesh/io/formats.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/mesh/length_unit.hpp"
#include "surfcomp/molsurf/load_surface.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::screening {

namespace {

bool is_library_input(const std::filesystem::path& path) {
  return io::is_record_file(path) || harmonic::io::is_hsi_file(path) ||
         mesh::io::is_mesh_file(path);
}

/// The entry of a mesh file: the mesh as read (repaired with options.repair; held to the
/// surface's vertex limit) with the normals and curvature molsurf::load_mesh_surface gives it (its
/// length unit automatic; a .hsi file's surface carries them), and the sample of its surface
/// pooled in cells of options.spacing of that unit, which the format keeps for every entry; a
/// shape screen matches the meshes themselves.
LibraryEntry mesh_entry(const io::MoleculeRecord& record, const LibraryBuildOptions& options) {
  const std::string extension = io::lowercase_extension(record.source);
  if (extension == ".vert" || extension == ".face") {
    throw InputError(record.source.string() +
                     ": an MSMS surface is a molecule's, in A: build the library from the "
                     "molecule");
  }
  molsurf::SurfaceInputOptions input;
  input.surface = options.surface;
  input.repair = options.repair;
  molsurf::LoadedSurface loaded =
      molsurf::load_mesh_surface(molsurf::read_mesh_input(record.source, input).surface, input);
  mesh::Surface& surface = loaded.surface;
  const mesh::LengthUnit unit = loaded.unit;
  LibraryEntry entry;
  entry.info.name = record.name;
  entry.info.source = record.source.string();
  entry.info.record = static_cast<std::uint32_t>(record.record);
  entry.molecule = record;
  entry.sample = matching::sample_surface(surface, options.spacing * unit.value);
  entry.kind = matching::SampleKind::surface;
  entry.packed =
      matching::PackedSample(entry.sample, entry.atoms, options.sigma * unit.value, entry.kind);
  harmonic::SurfaceDescriptors stored;
  stored.surface = std::move(surface);
  entry.surface = harmonic::io::encode_hsi(stored);
  return entry;
}

/// The entry of a .hsi file: its surface's samples, its heavy atoms as an MDL block, and its
/// surface without critical points for the last stage (the full match).
LibraryEntry hsi_entry(const io::MoleculeRecord& record, const LibraryBuildOptions& options) {
  harmonic::SurfaceDescriptors described = harmonic::io::read_hsi(record.source);
  // A .hsi made from a mesh has neither: the entry would be scored without chemistry.
  if (described.atoms.empty())
    throw InputError(record.source.string() + ": the .hsi keeps no atoms (made from a mesh?)");
  for (const char* property : {mesh::property::esp, mesh::property::lp}) {
    if (!described.surface.has_property(property))
      throw InputError(record.source.string() + ": the .hsi surface has no " + property);
  }
  Molecule atoms;
  for (const harmonic::SurfaceAtom& atom : described.atoms) {
    Atom a;
    a.element = atom.element;
    a.position = atom.position;
    atoms.atoms.push_back(std::move(a));
  }
  LibraryEntry entry;
  entry.info.name = record.name;
  entry.info.source = record.source.string();
  entry.info.record = static_cast<std::uint32_t>(record.record);
  entry.info.heavy_atoms = static_cast<std::uint32_t>(described.atoms.size());
  entry.molecule = record;
  entry.molecule.format = io::RecordFormat::mdl;
  entry.molecule.text = io::atoms_mol_block(atoms, record.name) + "$$$$\n";
  entry.sample = matching::sample_surface(described.surface, options.spacing);
  entry.atoms = matching::sample_atoms(described.atoms);
  entry.kind = matching::SampleKind::surface;
  entry.packed = matching::PackedSample(entry.sample, entry.atoms, options.sigma, entry.kind);
  described.critical_points.clear();
  entry.surface = harmonic::io::encode_hsi(described);
  return entry;
}

}  // namespace

std::uint32_t detail::heavy_atom_count(const Molecule& molecule) {
  return static_cast<std::uint32_t>(
      std::count_if(molecule.atoms.begin(), molecule.atoms.end(),
                    [](const Atom& atom) { return atom.element != "H"; }));
}

std::vector<io::MoleculeRecord> read_library_inputs(
    const std::vector<std::filesystem::path>& inputs) {
  std::vector<io::MoleculeRecord> records;
  const auto append = [&](const std::filesystem::path& file) {
    // A mesh or a .hsi file is one record, read when its entry is built.
    const bool is_mesh = mesh::io::is_mesh_file(file);
    if (is_mesh || harmonic::io::is_hsi_file(file)) {
      io::MoleculeRecord record;
      record.source = file;
      record.name = file.stem().string();
      record.format = is_mesh ? io::RecordFormat::mesh : io::RecordFormat::descriptors;
      records.push_back(std::move(record));
      return;
    }
    std::vector<io::MoleculeRecord> read = io::read_molecule_records(file);
    records.insert(records.end(), std::make_move_iterator(read.begin()),
                   std::make_move_iterator(read.end()));
  };
  for (const std::filesystem::path& input : inputs) {
    if (std::filesystem::is_directory(input)) {
      std::vector<std::filesystem::path> files;
      for (const auto& item : std::filesystem::directory_iterator(input)) {
        // An MSMS surface is a .vert and a .face file: one record, its .vert.
        if (item.is_regular_file() && is_library_input(item.path()) &&
            io::lowercase_extension(item.path()) != ".face")
          files.push_back(item.path());
      }
      std::sort(files.begin(), files.end());
      for (const auto& file : files) append(file);
    } else if (is_library_input(input)) {
      append(input);
    } else {
      throw InputError(input.string() + ": not a molecule file or list (" +
                       io::molecule_extensions(io::MoleculeUse::records) +
                       "), a .hsi file, a mesh (" +
                       mesh::io::mesh_extensions(mesh::io::MeshUse::read) + ") nor a directory");
    }
  }
  const auto is_mesh = [](const io::MoleculeRecord& r) {
    return r.format == io::RecordFormat::mesh;
  };
  const auto meshes = std::count_if(records.begin(), records.end(), is_mesh);
  if (meshes > 0 && static_cast<std::size_t>(meshes) < records.size()) {
    const auto other = std::find_if_not(records.begin(), records.end(), is_mesh);
    throw InputError("a library holds molecules or meshes, not both: " + other->source.string() +
                     " is not a mesh, " +
                     std::find_if(records.begin(), records.end(), is_mesh)->source.string() +
                     " is");
  }
  if (records.empty()) {
    std::string names;
    for (const std::filesystem::path& input : inputs)
      names += (names.empty() ? "" : ", ") + input.string();
    throw FileError(names,
                    inputs.size() == 1 ? "holds no molecule record" : "hold no molecule record");
  }
  return records;
}

std::vector<LibraryEntry> build_entries(const io::MoleculeRecord& record,
                                        const LibraryBuildOptions& options, BuildTimes* times) {
  const bool is_mesh = record.format == io::RecordFormat::mesh;
  if (is_mesh || record.format == io::RecordFormat::descriptors) {
    if (options.conformers) {
      throw InputError(std::string(is_mesh ? "a mesh" : "a .hsi file") +
                       " has fixed coordinates: " + options::named("conformers") +
                       " does not apply to it");
    }
    const Stopwatch clock;
    std::vector<LibraryEntry> entries{is_mesh ? mesh_entry(record, options)
                                              : hsi_entry(record, options)};
    if (times != nullptr) times->entries += clock.elapsed_s();
    return entries;
  }
  std::vector<io::MoleculeRecord> conformations;
  if (options.conformers) {
    const Stopwatch clock;
    for (std::string& block : generate_conformers(record, *options.conformers)) {
      io::MoleculeRecord conformer = record;
      conformer.format = io::RecordFormat::mdl;
      conformer.text = std::move(block);
      conformations.push_back(std::move(conformer));
    }
    if (times != nullptr) times->conformers += clock.elapsed_s();
  } else if (record.format == io::RecordFormat::smiles) {
    throw InputError("a SMILES record has no coordinates: generate conformers (" +
                     options::named("conformers") + " N)");
  } else if (record.format == io::RecordFormat::structure && record.text.empty()) {
    throw InputError("a PQR structure cannot go into a library (write it as PDB or SDF)");
  } else {
    conformations.push_back(record);
  }
  const Stopwatch clock;
  std::vector<LibraryEntry> entries;
  std::optional<Molecule> first;  // generated conformers: one molecule, other coordinates
  for (std::size_t c = 0; c < conformations.size(); ++c) {
    // The conformers of one record share their atoms, charges and lipophilicity, which depend
    // on the bonds alone: the first is read whole, the others take its atoms with their own
    // coordinates (as reading their blocks gives them, checked in tests).
    std::optional<Molecule> molecule;
    if (first && options.conformers) {
      const std::optional<std::vector<Eigen::Vector3d>> positions =
          io::mdl_coordinates(conformations[c].text);
      if (positions && positions->size() == first->atoms.size()) {
        molecule = *first;
        for (std::size_t a = 0; a < positions->size(); ++a)
          molecule->atoms[a].position = (*positions)[a];
      }
    }
    if (!molecule) molecule = io::read_record_molecule(conformations[c], options.read);
    if (!first) first = *molecule;
    LibraryEntry entry;
    entry.info.name = record.name;
    entry.info.source = record.source.string();
    entry.info.record = static_cast<std::uint32_t>(record.record);
    entry.info.conformer = options.conformers ? static_cast<std::uint32_t>(c + 1) : 0;
    entry.info.heavy_atoms = detail::heavy_atom_count(*molecule);
    entry.molecule = std::move(conformations[c]);
    entry.sample = matching::sample_molecule(*molecule, options.spacing, options.surface);
    entry.atoms = matching::sample_atoms(harmonic::surface_atoms(*molecule));
    entry.kind = matching::SampleKind::atoms;
    entry.packed = matching::PackedSample(entry.sample, entry.atoms, options.sigma, entry.kind);
    entries.push_back(std::move(entry));
  }
  if (times != nullptr) times->entries += clock.elapsed_s();
  return entries;
}

std::string build_settings(const LibraryBuildOptions& options, bool sites) {
  std::ostringstream text;
  if (sites) {
    text << "sites (site_radius " << options.site.sphere_radius << ", chain_contact_radius "
         << options.site.chain_contact_radius << ", surface_margin " << options.site.surface_margin
         << ", lining_radius " << options.lining_radius << ")\n";
  } else if (options.conformers) {
    text << "conformers " << options.conformers->count << " (ETKDGv3 seed "
         << options.conformers->seed << ", MMFF94 " << options.conformers->mmff_iterations
         << " iterations)\n";
  } else {
    text << "conformers 0 (the records' coordinates)\n";
  }
  text << "spacing " << options.spacing << "\n";
  text << "sigma " << options.sigma << "\n";
  text << "sample " << (sites ? "surface" : "atoms (screening surface; .hsi inputs: surface)")
       << "\n";
  text << "probe_radius " << options.surface.ses.probe_radius << "\n";
  text << "vertex_density " << options.surface.ses.vertex_density << "\n";
  return text.str();
}

}  // namespace surfcomp::screening
