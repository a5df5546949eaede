// Pocket libraries: the sites of a site list or the pockets detected in structures, each entry
// a site's surface with its neighbourhood of the structure.
#include "library_build_items.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"

#include <algorithm>
#include <exception>
#include <numeric>
#include <sstream>
#include <string>
#include <tbb/parallel_for.h>
#include <utility>
#include <vector>

namespace surfcomp::screening {

std::vector<SiteRequest> read_site_list(const std::filesystem::path& list) {
  const std::string text = io::read_input_file(list);
  std::vector<SiteRequest> sites;
  std::istringstream lines(text);
  std::string line;
  for (std::size_t number = 1; std::getline(lines, line); ++number) {
    std::istringstream fields(line);
    std::vector<std::string> words;
    for (std::string word; fields >> word;) words.push_back(word);
    if (words.empty() || words.front().front() == '#') continue;
    const std::string where = list.string() + ":" + std::to_string(number) + ": ";
    if (words.size() < 2) {
      throw InputError(where +
                       "expected 'STRUCTURE LIGAND [CHAIN]', 'STRUCTURE x,y,z,r [x,y,z,r ...]' or "
                       "'STRUCTURE pocket N'");
    }
    SiteRequest site;
    site.line = number;
    site.structure = words[0];
    if (site.structure.is_relative()) site.structure = list.parent_path() / site.structure;
    const std::string stem = io::structure_stem(words[0]);
    if (residue_key(words[1]) == "POCKET") {  // no residue name is six letters long
      char* end = nullptr;
      const long rank = words.size() == 3 ? std::strtol(words[2].c_str(), &end, 10) : 0;
      if (words.size() != 3 || end == words[2].c_str() || *end != '\0' || rank < 1 ||
          rank > 1000000) {
        throw InputError(where + "expected 'STRUCTURE pocket N' with N a pocket rank >= 1");
      }
      site.pocket_rank = static_cast<int>(rank);
      site.pocket = true;
      site.name = stem + ":pocket" + std::to_string(rank);
    } else if (words[1].find(',') != std::string::npos) {
      for (std::size_t w = 1; w < words.size(); ++w) {
        const std::optional<molsurf::SiteSphere> sphere = molsurf::parse_site_sphere(words[w]);
        if (!sphere) {
          throw InputError(where + "'" + words[w] + "' is not a sphere x,y,z,r with r > 0 (A)");
        }
        site.spheres.push_back(*sphere);
      }
      site.name = stem + ":spheres" + std::to_string(number);
    } else {
      if (words.size() > 3) {
        throw InputError(where + "expected 'STRUCTURE LIGAND [CHAIN]', got " +
                         std::to_string(words.size()) + " fields");
      }
      try {
        site.ligand = parse_ligand_selector(words[1]);
      } catch (const OptionError& error) {
        throw InputError(where + error.what());
      }
      site.name = stem + ":" + words[1];
      if (words.size() == 3) {
        site.ligand->chain = words[2];
        site.name += ":" + words[2];
      }
    }
    sites.push_back(std::move(site));
  }
  if (sites.empty()) throw FileError(list.string(), "lists no site");
  return sites;
}

std::vector<std::filesystem::path> structure_files(
    const std::vector<std::filesystem::path>& inputs) {
  std::vector<std::filesystem::path> files;
  for (const std::filesystem::path& input : inputs) {
    if (std::filesystem::is_directory(input)) {
      std::vector<std::filesystem::path> inside;
      for (const auto& item : std::filesystem::directory_iterator(input)) {
        if (item.is_regular_file() && io::is_structure_file(item.path()))
          inside.push_back(item.path());
      }
      std::sort(inside.begin(), inside.end());
      files.insert(files.end(), inside.begin(), inside.end());
    } else if (io::is_structure_file(input)) {
      files.push_back(input);
    } else {
      throw InputError(input.string() + ": not a structure file (" +
                       io::molecule_extensions(io::MoleculeUse::structure) + ") nor a directory");
    }
  }
  if (files.empty()) {
    std::string names;
    for (const std::filesystem::path& input : inputs)
      names += (names.empty() ? "" : ", ") + input.string();
    throw FileError(names,
                    inputs.size() == 1 ? "holds no structure file" : "hold no structure file");
  }
  return files;
}

namespace {

/// The entry of site `request` on `structure`, read from request.structure (for a pocket, its
/// pocket_structure).
LibraryEntry site_entry(const Molecule& structure, const SiteRequest& request,
                        const LibraryBuildOptions& options) {
  molsurf::BindingSite site = request.ligand
                                  ? molsurf::binding_site(structure, *request.ligand, options.site)
                                  : molsurf::binding_site(structure, request.spheres, options.site);
  const harmonic::DescriptorOptions describing;
  site.surface_margin = molsurf::site_surface_margin(site.surface_margin, describing.patch.radius);
  // The entry keeps the site's neighbourhood, not the structure (a margin of 0 keeps every atom),
  // and is built from that text read back, as the screen will read it.
  LibraryEntry entry;
  entry.molecule.source = request.structure;
  entry.molecule.record = request.line;
  entry.molecule.name = request.name;
  entry.molecule.format = io::RecordFormat::structure;
  std::ostringstream pdb;
  const double reach = std::max(site.surface_margin + molsurf::neighbourhood_beyond_margin,
                                molsurf::site_atom_reach(site, options.surface.ses));
  io::write_pdb(site.surface_margin == 0.0
                    ? site.structure
                    : molsurf::site_neighbourhood(site.structure, site.spheres, reach),
                pdb);
  entry.molecule.text = pdb.str();
  entry.info.heavy_atoms = detail::heavy_atom_count(site.structure);
  site.structure = io::read_record_molecule(entry.molecule, site_entry_read_options(options.read));
  const harmonic::SurfaceDescriptors described = matching::describe_site(
      molsurf::build_site_surface(site, options.surface), site.structure, site.spheres, describing);
  const std::vector<bool> in_site = matching::critical_points_in_site(described, site.spheres);
  const std::vector<bool> lining =
      matching::pocket_lining(described, &in_site, options.lining_radius);
  entry.info.name = request.name;
  entry.info.source = request.structure.string();
  entry.info.record = static_cast<std::uint32_t>(request.line);
  entry.info.site_spheres = static_cast<std::uint32_t>(site.spheres.size());
  entry.sample = matching::sample_surface(described.surface, options.spacing, &lining);
  if (entry.sample.size() == 0)
    throw InputError(request.name + ": the site's pocket lining has no vertex");
  entry.kind = matching::SampleKind::surface;
  entry.packed = matching::PackedSample(entry.sample, entry.atoms, options.sigma, entry.kind);
  entry.site = std::move(site.spheres);
  return entry;
}

/// The settings lines a pocket library adds to build_settings: the structures' pLDDT cut and,
/// when pockets are detected, how (a resumed build must detect them the same way).
std::string site_settings(const LibraryBuildOptions& options, bool detects_pockets) {
  std::ostringstream text;
  text << "min_plddt " << options.read.min_plddt << "\n";
  if (detects_pockets) {
    const molsurf::PocketOptions& p = options.pockets;
    text << "pockets (min_sphere_radius " << p.min_sphere_radius << ", max_sphere_radius "
         << p.max_sphere_radius << ", min_buriedness " << p.min_buriedness << ", buried_distance "
         << p.buried_distance << ", cluster_distance " << p.cluster_distance << ", min_spheres "
         << p.min_spheres << ", max_volume " << p.max_volume << ")\n";
  }
  return text.str();
}

}  // namespace

detail::BuildItems detail::site_items(const std::vector<SiteRequest>& sites,
                                      const LibraryBuildOptions& options) {
  detail::BuildItems items;
  items.count = sites.size();
  items.build = [&sites, &options](std::size_t i, BuildTimes& times, std::vector<SkippedRecord>&) {
    const Stopwatch clock;
    std::vector<LibraryEntry> entries{build_site_entry(sites[i], options)};
    times.entries += clock.elapsed_s();
    return entries;
  };
  items.origin = [&sites](std::size_t i) {
    return detail::ItemOrigin{sites[i].structure.string(), sites[i].line, sites[i].name};
  };
  items.identity = [&sites](std::size_t i, io::BinaryWriter& bytes) {
    const SiteRequest& site = sites[i];
    detail::file_identity(site.structure, bytes);
    bytes.u64(site.line);
    bytes.string(site.name);
    bytes.string(site.ligand ? site.ligand->residue_name + ":" + site.ligand->chain.value_or("")
                             : "");
    for (const molsurf::SiteSphere& sphere : site.spheres) {
      bytes.f64(sphere.center.x());
      bytes.f64(sphere.center.y());
      bytes.f64(sphere.center.z());
      bytes.f64(sphere.radius);
    }
  };
  const bool detects_pockets = std::any_of(
      sites.begin(), sites.end(), [](const SiteRequest& site) { return site.pocket_rank > 0; });
  items.settings = build_settings(options, true) + site_settings(options, detects_pockets);
  items.noun = "site";
  return items;
}

detail::BuildItems detail::pocket_items(const std::vector<std::filesystem::path>& structures,
                                        const LibraryBuildOptions& options) {
  detail::BuildItems items;
  items.count = structures.size();
  items.build = [&structures, &options](std::size_t i, BuildTimes& times,
                                        std::vector<SkippedRecord>& skipped) {
    const Stopwatch clock;
    const std::filesystem::path& file = structures[i];
    const Molecule structure = molsurf::pocket_structure(io::read_molecule(file, options.read));
    std::vector<molsurf::Pocket> pockets = molsurf::detect_pockets(structure, options.pockets);
    if (pockets.empty()) throw InputError("no pocket found");
    const double detection_seconds = clock.elapsed_s();
    const std::string stem = io::structure_stem(file);
    std::vector<SiteRequest> requests(pockets.size());
    std::vector<std::optional<LibraryEntry>> built(pockets.size());
    std::vector<std::string> errors(pockets.size());
    std::vector<double> seconds(pockets.size(), 0.0);
    tbb::parallel_for(std::size_t{0}, pockets.size(), [&](std::size_t k) {
      const Stopwatch pocket_clock;
      SiteRequest& request = requests[k];
      request.line = static_cast<std::size_t>(pockets[k].rank);
      request.structure = file;
      request.spheres = std::move(pockets[k].spheres);
      request.name = stem + ":pocket" + std::to_string(pockets[k].rank);
      request.pocket = true;
      try {
        built[k] = site_entry(structure, request, options);
      } catch (const std::bad_alloc&) {
        errors[k] = "out of memory";
      } catch (const std::exception& e) {
        errors[k] = detail::one_line(e.what());
      }
      seconds[k] = pocket_clock.elapsed_s();
    });
    std::vector<LibraryEntry> entries;
    for (std::size_t k = 0; k < built.size(); ++k) {
      if (built[k]) {
        entries.push_back(std::move(*built[k]));
      } else {
        skipped.push_back({file.string(), requests[k].line, requests[k].name, errors[k]});
      }
    }
    if (entries.empty()) throw InputError("no pocket's entry could be built (" + errors[0] + ")");
    // The detection's time, then each pocket's: core time, as the other builds count it.
    times.entries += detection_seconds + std::accumulate(seconds.begin(), seconds.end(), 0.0);
    return entries;
  };
  items.origin = [&structures](std::size_t i) {
    return detail::ItemOrigin{structures[i].string(), 0, io::structure_stem(structures[i])};
  };
  items.identity = [&structures](std::size_t i, io::BinaryWriter& bytes) {
    detail::file_identity(structures[i], bytes);
  };
  items.settings = build_settings(options, true) + site_settings(options, true);
  items.noun = "structure";
  return items;
}

void detail::check_site_options(const LibraryBuildOptions& options) {
  if (options.conformers)
    throw OptionError(options::named("conformers") + " does not apply to sites or pockets");
}

LibraryEntry build_site_entry(const SiteRequest& request, const LibraryBuildOptions& options) {
  Molecule structure = io::read_molecule(request.structure, options.read);
  if (request.pocket_rank > 0) {
    SiteRequest found = request;
    found.spheres =
        molsurf::pocket_site(structure, request.pocket_rank, options.pockets, options.site).spheres;
    return site_entry(molsurf::pocket_structure(structure), found, options);
  }
  if (request.pocket) structure = molsurf::pocket_structure(structure);
  return site_entry(structure, request, options);
}

LibraryBuildResult build_site_library(const std::vector<SiteRequest>& sites,
                                      const std::filesystem::path& output,
                                      const LibraryBuildOptions& options) {
  return ShardedLibraryBuild(sites, output, options).run();
}

LibraryBuildResult build_pocket_library(const PocketStructures& structures,
                                        const std::filesystem::path& output,
                                        const LibraryBuildOptions& options) {
  return ShardedLibraryBuild(structures, output, options).run();
}

}  // namespace surfcomp::screening
