// surfcomp pockets: the pockets of a protein structure, found from its atoms alone, as JSON
// and, for viewing, as PDB alpha sphere centres.
#include "command.hpp"
#include "console.hpp"
#include "options.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/command_files.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/molsurf/pockets.hpp"
#include "surfcomp/report/pocket_files.hpp"

#include <filesystem>
#include <string>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp pockets STRUCTURE -o POCKETS.json [--pdb-out POCKETS.pdb] [options]\n\n"
    "Finds the pockets of a protein from its ATOM records alone (ligands, ions and water set\n"
    "aside), as fpocket does: the empty spheres of the heavy atoms' Delaunay triangulation\n"
    "(alpha spheres) of radius between --pocket-min-radius and --pocket-max-radius, kept when\n"
    "buried, clustered by their centres (2.4 A) and ranked by their summed buriedness. Each\n"
    "pocket has a rank, score, volume, centre, lining residues and its alpha spheres, which are\n"
    "a binding site wherever one is asked for (`match --site-pocket N`, `library build\n"
    "--pockets`, `screen --site-pocket N`).\n\n"
    "STRUCTURE  a PDB (.pdb .ent) or PDBx/mmCIF (.cif .mmcif .cif.gz) file; the first model";

}  // namespace

int pockets(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, pdb_out;
  po::options_description described("options");
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output)->required(), "the pockets as JSON")
      ("pdb-out", po::value(&pdb_out), "also write the alpha sphere centres as PDB (residue STP)");
  // clang-format on
  add_table_options(described, molsurf::pocket_search_option_table());
  po::variables_map vm;
  if (!parse_command_line(args, described, 1, kUsage, vm)) return 0;
  if (!vm.count("input")) throw OptionError("missing STRUCTURE (see --help)");
  const auto inputs = vm["input"].as<std::vector<std::string>>();
  if (inputs.size() != 1) throw OptionError("one STRUCTURE at a time (see --help)");
  const std::filesystem::path path = inputs.front();
  molsurf::PocketSearchOptions options;
  apply_table_options(molsurf::pocket_search_option_table(), vm, options);
  io::check_command_files({{{"STRUCTURE", path}},
                           {{"--output", output, {}, ""}, {"--pdb-out", pdb_out, {".pdb"}, ""}}});

  Stopwatch clock;
  const report::PocketSet set{path.string(), options.pockets, molsurf::find_pockets(path, options)};
  const molsurf::StructurePockets& found = set.found;
  if (found.models > 1) {
    console::note(path.string() + ": holds " + std::to_string(found.models) +
                  " models; the first is read");
  }
  const double elapsed = clock.elapsed_ms();

  // The JSON goes last; if it cannot be written, the PDB file written before it is removed.
  if (!pdb_out.empty()) {
    surfcomp::io::write_file_atomically(
        pdb_out, [&](std::ostream& out) { report::write_pockets_pdb(found.pockets, out); });
  }
  try {
    surfcomp::io::write_file_atomically(
        output, [&](std::ostream& out) { out << report::pockets_json(set); });
  } catch (...) {
    if (!pdb_out.empty()) std::filesystem::remove(pdb_out);
    throw;
  }
  if (found.pockets.empty()) {
    console::summary("%s: no pocket found (%zu protein atoms), %.0f ms -> %s\n",
                     path.string().c_str(), found.protein_atoms, elapsed, output.c_str());
  } else {
    const molsurf::Pocket& top = found.pockets.front();
    console::summary(
        "%s: %zu pockets (%zu protein atoms); pocket 1: score %.1f, %.0f A^3, %zu "
        "residues; %.0f ms -> %s\n",
        path.string().c_str(), found.pockets.size(), found.protein_atoms, top.score, top.volume,
        top.lining_residues.size(), elapsed, output.c_str());
  }
  return 0;
}

}  // namespace surfcomp::tools
