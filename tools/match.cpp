// surfcomp match: ranked rigid alignments of PROBE onto REF (METHOD sections 5-7), as a table on
// stdout and a JSON file other tools read; optionally PROBE moved by the top alignment.
#include "command.hpp"
#include "command_files.hpp"
#include "options.hpp"
#include "surface_input.hpp"

#include "surfcomp/core/io/atomic_file.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/mesh/io/ply.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace surfcomp::tools {
namespace {

constexpr const char* kUsage =
    "usage: surfcomp match REF PROBE [-o result.json] [--aligned-out FILE.sdf|.pdb|.ply]\n"
    "                      [options]\n\n"
    "Finds where PROBE's surface looks and feels like REF's and returns ranked rigid\n"
    "alignments that move PROBE into REF's frame: critical-point pairs filtered by ESP/LP\n"
    "(fuzzy), harmonic shape images, distances and overlap; maximal cliques; least-squares fits\n"
    "on the images' corresponding points; single-linkage merging; consensus ranking (METHOD\n"
    "sections 5-7); then the first --refine-top alignments are refined on the whole surfaces\n"
    "(Gaussian overlay of shape, ESP and LP) and ranked by that overlay score (table column\n"
    "'overlay', * = refined), together with --principal-axes-starts superpositions refined the\n"
    "same way (column 'from': axes). Where both inputs are molecules (or .hsi files built from\n"
    "molecules), a refined pose's score also weighs the overlap of same-element heteroatoms\n"
    "(--overlay-atom-weight), and the first --polish-top poses are refined again on that whole\n"
    "score.\n\n"
    "REF, PROBE  a molecule (.sdf .mol .mol2 .pdb .pqr), a mesh (.ply .vert .off .obj) or a\n"
    "            .hsi file from hsi-build (two .hsi files must have been built with the same\n"
    "            parameters)\n"
    "Binding sites: --site-ligand RES (both sides) or --ref-site-ligand/--probe-site-ligand\n"
    "build the protein's surface without water and without one copy of that HETATM residue (the\n"
    "lowest chain, then residue number) and keep the critical points within --site-radius of\n"
    "its atoms; --site-sphere x,y,z,r (repeatable; also --ref-/--probe-site-sphere) adds\n"
    "spheres. A site's surface is that of the atoms within --site-margin of its spheres (the\n"
    "whole structure's surface wherever patches of up to 8 A reach; ESP and LP from every\n"
    "atom). A site match overlays the pocket linings (within --site-overlay-radius of the\n"
    "site's critical points) on shape alone (--site-chem-weight 0) from the cliques and 24\n"
    "principal-axes starts; the top-1 overlay score is then the sites' similarity (shape\n"
    "Tanimoto of the linings).";

/// A notifier refusing a value <= 0 as a command-line error (like a value that is no integer).
auto positive(const char* name) {
  return [name](std::int64_t value) {
    if (value <= 0) {
      namespace po = boost::program_options;
      po::validation_error error(po::validation_error::invalid_option_value, name,
                                 std::to_string(value), po::command_line_style::allow_long);
      error.set_substitute("value", std::to_string(value));
      throw error;
    }
  };
}

/// What the match cut, one line each: the clique search's stop (MatchResult::cliques_complete).
std::vector<std::string> match_warnings(const matching::MatchResult& result,
                                        const matching::MatchOptions& options) {
  std::vector<std::string> warnings;
  if (!result.cliques_complete) {
    warnings.push_back(result.cliques >= options.max_cliques
                           ? "clique search stopped at " + std::to_string(result.cliques) +
                                 " cliques (--max-cliques); alignments may be missing"
                           : "clique search stopped after " + std::to_string(result.clique_work) +
                                 " units of work (--max-clique-work " +
                                 std::to_string(options.max_clique_work) +
                                 "); alignments may be missing");
  }
  return warnings;
}

struct Side {
  std::filesystem::path path;
  std::optional<mesh::Surface> surface;  // read or built, until describe_side takes it
  harmonic::SurfaceDescriptors descriptors;
  std::optional<Molecule> molecule;  // the molecule read, for --aligned-out and messages
  std::vector<matching::SiteSphere> site;
  std::size_t record = 0;  // the molecule of the file read (MoleculeReadOptions::record)
};

matching::SiteSphere parse_sphere(const std::string& text) {
  const std::optional<matching::SiteSphere> sphere = matching::parse_site_sphere(text);
  if (!sphere) throw OptionError("--site-sphere '" + text + "': expected x,y,z,r with r > 0 (A)");
  return *sphere;
}

/// Checks, before any work, that one side's input and site options fit together: a site ligand
/// needs the structure (a molecule file) and is not a water (the readers drop waters), and
/// --ligand cannot pick the structure's ligand at the same time (OptionError).
void check_side(const char* name, const std::filesystem::path& path, const SurfaceInput& input,
                const char* site_option, const std::string& site_ligand) {
  if (!site_ligand.empty()) {
    if (is_water_residue(site_ligand)) {
      throw OptionError(std::string(site_option) + " " + site_ligand +
                        ": waters (HOH, WAT, DOD) are dropped when a structure is read, so a "
                        "water cannot be a site ligand; give --site-sphere x,y,z,r around it");
    }
    if (harmonic::io::is_hsi_file(path)) {
      throw OptionError(std::string(name) + " " + path.string() +
                        ": --site-ligand needs the structure, not a .hsi file; use --site-sphere");
    }
    if (!io::is_molecule_file(path)) {
      throw OptionError(std::string(name) + " " + path.string() +
                        ": --site-ligand needs a molecule file (the structure); use --site-sphere");
    }
    if (!input.read.ligand.empty())
      throw OptionError("--ligand and --site-ligand cannot be combined");
  }
  if (!harmonic::io::is_hsi_file(path)) mesh::check_surface_input(path, input);
}

/// The formats --aligned-out can take for this PROBE: a molecule moves as PDB, an SDF, MOL or
/// MOL2 file also as SDF (its bonds kept), any side as its surface (PLY).
std::vector<std::string> aligned_formats(const std::filesystem::path& probe) {
  if (!io::is_molecule_file(probe)) return {".ply"};
  const std::string extension = io::lowercase_extension(probe);
  if (extension == ".sdf" || extension == ".mol" || extension == ".mol2") {
    return {".sdf", ".pdb", ".ply"};
  }
  return {".pdb", ".ply"};
}

/// Reads one side, or builds its surface (its options already passed check_side): a .hsi file
/// gives the description itself; otherwise the surface waits in Side::surface for describe_side.
/// A molecule with a site (`site_ligand`, `spheres` or both) gets the binding site's surface
/// (matching::binding_site without the ligand copy, matching::build_site_surface around it).
Side load_side(const std::filesystem::path& path, const SurfaceInput& input,
               const std::string& site_ligand, std::vector<matching::SiteSphere> spheres,
               const matching::BindingSiteOptions& site_options) {
  Side side;
  side.path = path;
  side.record = input.read.record;
  if (harmonic::io::is_hsi_file(path)) {
    side.descriptors = harmonic::io::read_hsi(path);
    side.site = std::move(spheres);
    return side;
  }
  mesh::LoadedSurface loaded;
  if (io::is_molecule_file(path) && (!site_ligand.empty() || !spheres.empty())) {
    const Molecule structure = io::read_molecule(path, input.read);
    matching::BindingSite site =
        site_ligand.empty()
            ? matching::binding_site(structure, spheres, site_options)
            : matching::binding_site(structure, LigandSelector{site_ligand, {}, {}}, site_options);
    if (!site_ligand.empty())
      site.spheres.insert(site.spheres.end(), spheres.begin(), spheres.end());
    loaded.surface = matching::build_site_surface(site, input.surface);
    loaded.molecule = std::move(site.structure);
    side.site = std::move(site.spheres);
  } else {
    loaded = mesh::load_surface(path, input);
    side.site = std::move(spheres);
  }
  side.molecule = std::move(loaded.molecule);
  matching::require_match_properties(loaded.surface);
  side.surface = std::move(loaded.surface);
  return side;
}

/// Describes a side that load_side left a surface in: with a site (the ligand's spheres and
/// --site-sphere), only its critical points get patches, maps and images
/// (matching::describe_site).
void describe_side(Side& side, const harmonic::DescriptorOptions& options) {
  if (!side.surface) return;  // read from a .hsi file
  mesh::Surface surface = std::move(*side.surface);
  side.surface.reset();
  if (side.site.empty()) {
    side.descriptors = side.molecule
                           ? harmonic::describe_surface(std::move(surface), *side.molecule, options)
                           : harmonic::describe_surface(std::move(surface), options);
  } else {
    side.descriptors =
        side.molecule
            ? matching::describe_site(std::move(surface), *side.molecule, side.site, options)
            : matching::describe_site(std::move(surface), side.site, options);
  }
}

bool same_options(const harmonic::DescriptorOptions& x, const harmonic::DescriptorOptions& y) {
  return x.critical_points.radius == y.critical_points.radius &&
         x.critical_points.property_disc_radius == y.critical_points.property_disc_radius &&
         x.critical_points.distance == y.critical_points.distance &&
         x.patch.radius == y.patch.radius && x.patch.margin == y.patch.margin &&
         x.patch.distance == y.patch.distance && x.disk_map.weights == y.disk_map.weights &&
         x.image.rings == y.image.rings && x.image.sectors == y.image.sectors &&
         x.image_property == y.image_property;
}

nlohmann::json to_json(const matching::MatchResult& result, const matching::MatchOptions& options,
                       const Side& ref, const Side& probe,
                       const std::vector<std::string>& warnings) {
  nlohmann::json alignments = nlohmann::json::array();
  for (const auto& a : result.alignments) {
    nlohmann::json transform = nlohmann::json::array();
    for (int r = 0; r < 4; ++r) {
      transform.push_back(
          {a.transform(r, 0), a.transform(r, 1), a.transform(r, 2), a.transform(r, 3)});
    }
    nlohmann::json pairs = nlohmann::json::array();
    for (const auto& [x, y] : a.cp_pairs) pairs.push_back({x, y});
    const char* source =
        a.source == matching::AlignmentSource::cliques ? "cliques" : "principal_axes";
    alignments.push_back(
        {{"rank", a.rank},
         {"source", source},
         {"transform", transform},
         {"rmsd", a.rmsd},
         {"n_points", a.n_points},
         {"r_chem", a.r_chem},
         {"consensus", a.consensus},
         {"refined", a.refined},
         {"overlay",
          {{"score", a.overlay.score},
           {"shape", a.overlay.shape},
           {"chem", a.overlay.chem},
           {"atoms", a.overlay.atoms}}},
         {"cp_pairs", pairs},
         {"parent", a.parent > 0 ? nlohmann::json(a.parent) : nlohmann::json(nullptr)},
         {"children", a.children}});
  }
  nlohmann::json trace = nlohmann::json::array();
  for (const auto& stage : result.trace) {
    trace.push_back({{"stage", stage.stage}, {"nodes", stage.nodes}, {"edges", stage.edges}});
  }
  nlohmann::json timing = nlohmann::json::object();
  for (const auto& [stage, ms] : result.timing_ms) timing[stage] = ms;
  const auto& g = options.graph;
  return {{"reference", ref.path.string()},
          {"probe", probe.path.string()},
          {"alignments", alignments},
          {"trace", trace},
          {"timing_ms", timing},
          {"cliques",
           {{"count", result.cliques},
            {"complete", result.cliques_complete},
            {"work", result.clique_work}}},
          {"warnings", warnings},
          {"parameters",
           {{"fuzzy_threshold", g.fuzzy_threshold},
            {"image_threshold", g.image_threshold},
            {"distance_tolerance", g.distance_tolerance},
            {"min_distance", g.min_distance},
            {"overlap_tolerance_degrees", g.overlap_tolerance_degrees},
            {"rmsd_cut", options.clustering.rmsd_cut},
            {"merge_cut", options.clustering.merge_cut},
            {"min_clique_size", options.min_clique_size},
            {"max_graph_nodes", g.max_nodes},
            {"max_clique_work", options.max_clique_work},
            {"max_cliques", options.max_cliques},
            {"refine_top", options.refine_top},
            {"overlay_sigma", options.overlay.sigma},
            {"overlay_spacing", options.overlay.spacing},
            {"overlay_chem_weight", options.overlay.chem_weight},
            {"overlay_atom_weight", options.overlay.atom_weight},
            {"polish_top", options.polish_top},
            {"overlay_tolerance", options.overlay.tolerance},
            {"principal_axes_starts", options.principal_axes_starts},
            {"site_overlay_radius", options.site.overlay_radius},
            {"site_chem_weight", options.site.chem_weight},
            {"site_principal_axes_starts", options.site.principal_axes_starts},
            {"critical_point_radius", ref.descriptors.options.critical_points.radius},
            {"patch_radius", ref.descriptors.options.patch.radius},
            {"image_rings", ref.descriptors.options.image.rings},
            {"image_sectors", ref.descriptors.options.image.sectors}}}};
}

void write_aligned(const Side& probe, const Eigen::Matrix4d& transform, const std::string& output) {
  const Eigen::Matrix3d rotation = transform.topLeftCorner<3, 3>();
  const Eigen::Vector3d translation = transform.topRightCorner<3, 1>();
  const std::string extension = io::lowercase_extension(output);
  if (extension == ".ply") {
    mesh::Surface moved = probe.descriptors.surface;
    mesh::transform_surface(moved, rotation, translation);
    mesh::io::write_ply(moved, output);
  } else if (extension == ".sdf") {
    const std::string block = io::moved_mol_block(probe.path, rotation, translation, probe.record);
    surfcomp::io::write_file_atomically(output, [&](std::ostream& out) { out << block; });
  } else {
    Molecule moved = *probe.molecule;
    transform_molecule(moved, rotation, translation);
    surfcomp::io::write_file_atomically(output,
                                        [&](std::ostream& out) { io::write_pdb(moved, out); });
  }
}

}  // namespace

int match(const std::vector<std::string>& args) {
  namespace po = boost::program_options;
  std::string output, aligned_out, ranking;
  std::string site_ligand, ref_site_ligand, probe_site_ligand;
  std::vector<std::string> site_spheres, ref_site_spheres, probe_site_spheres;
  matching::BindingSiteOptions site_options;
  int top = 10;
  SurfaceInput input;
  matching::MatchOptions options;
  harmonic::DescriptorOptions descriptor_options;
  po::options_description described("options");
  auto& g = options.graph;
  // Read as signed integers, so that a negative value is refused rather than wrapped.
  std::int64_t max_clique_work = options.max_clique_work;
  auto max_cliques = static_cast<std::int64_t>(options.max_cliques);
  auto max_graph_nodes = static_cast<std::int64_t>(g.max_nodes);
  // clang-format off
  described.add_options()
      ("help,h", "print this help")
      ("output,o", po::value(&output),
       "write the result as JSON (alignments, trace, timing_ms, parameters)")
      ("aligned-out", po::value(&aligned_out),
       "write PROBE moved by the top alignment: .sdf (SDF/MOL/MOL2 PROBE), .pdb (molecule PROBE) "
       "or .ply")
      ("top", defaulted(&top), "alignments shown in the table")
      ("trace", po::bool_switch(), "print the association graph's nodes and edges after each stage")
      ("site-ligand", po::value(&site_ligand),
       "binding site of both proteins: this ligand residue name")
      ("ref-site-ligand", po::value(&ref_site_ligand), "binding site of REF only")
      ("probe-site-ligand", po::value(&probe_site_ligand), "binding site of PROBE only")
      ("site-radius", defaulted(&site_options.sphere_radius),
       "radius of the spheres around the site ligand's atoms, A")
      ("site-sphere", po::value(&site_spheres)->composing(),
       "site sphere x,y,z,r on both sides (A)")
      ("site-margin", defaulted(&site_options.surface_margin),
       (std::string(kSiteMarginHelp) + "; by default at least --patch-radius + 8").c_str())
      ("ref-site-sphere", po::value(&ref_site_spheres)->composing(), "site sphere on REF only")
      ("probe-site-sphere", po::value(&probe_site_spheres)->composing(),
       "site sphere on PROBE only")
      ("fuzzy-threshold", defaulted(&g.fuzzy_threshold),
       "fuzzy ESP/LP similarity threshold F")
      ("image-threshold", defaulted(&g.image_threshold),
       "harmonic shape image correlation threshold R")
      ("distance-tolerance", defaulted(&g.distance_tolerance),
       "distance filter tolerance t, A")
      ("min-distance", defaulted(&g.min_distance),
       "distance filter minimum d_min, A")
      ("overlap-tolerance",
       defaulted(&g.overlap_tolerance_degrees),
       "overlap filter tolerance j_tol, degrees")
      ("max-graph-nodes", defaulted(&max_graph_nodes)
                              ->notifier(positive("max-graph-nodes")),
       "refuse a match whose association graph keeps more critical-point pairs than this after "
       "the image filter (a positive integer); its cost grows with the square of the count")
      ("max-clique-work", defaulted(&max_clique_work)
                              ->notifier(positive("max-clique-work")),
       "stop the clique search after this much work (a positive integer; a unit is one 64-node "
       "word of a set operation, a few ns) and go on with the cliques found, saying so")
      ("max-cliques", defaulted(&max_cliques)
                          ->notifier(positive("max-cliques")),
       "stop the clique search rather than report more cliques than this (a positive integer); "
       "each is fitted and merged, in time quadratic in their number")
      ("rmsd-cut",
       defaulted(&options.clustering.rmsd_cut),
       "drop cliques whose fit RMSD exceeds this, A")
      ("ranking", po::value(&ranking)->default_value("rank"),
       "consensus: rank (rank-by-rank) | number (rank-by-number) | vote (rank-by-vote)")
      ("refine-top", defaulted(&options.refine_top),
       "refine this many alignments on the whole surfaces and rank them by their overlay score "
       "(0: the seed's consensus ranking alone)")
      ("overlay-sigma", defaulted(&options.overlay.sigma),
       "Gaussian width of the whole-surface overlay, A")
      ("overlay-chem-weight",
       defaulted(&options.overlay.chem_weight),
       "weight of the ESP/LP Tanimoto against the shape Tanimoto in the overlay score")
      ("overlay-atom-weight",
       defaulted(&options.overlay.atom_weight),
       "weight of the same-element heteroatom Tanimoto in the overlay score, where both inputs "
       "are molecules (or .hsi files built from molecules); not for site matches")
      ("polish-top", defaulted(&options.polish_top),
       "with the atom term, refine the first N alignments again on the whole score, heteroatoms "
       "pulled too, and order them again (0: no polish)")
      ("overlay-tolerance",
       defaulted(&options.overlay.tolerance),
       "a refinement stops when a step moves no sampled probe point farther than this, A")
      ("principal-axes-starts",
       defaulted(&options.principal_axes_starts),
       "also refine this many principal-axes superpositions of the whole surfaces: 0, 4 or 24 "
       "(with --refine-top > 0; so do the --site-* overlay options)")
      ("site-overlay-radius",
       defaulted(&options.site.overlay_radius),
       "site matches: overlay the vertices within this distance of the site's critical points, A")
      ("site-chem-weight",
       defaulted(&options.site.chem_weight),
       "site matches: --overlay-chem-weight for the pocket overlay")
      ("site-principal-axes-starts",
       defaulted(&options.site.principal_axes_starts),
       "site matches: --principal-axes-starts for the pocket overlay (0, 4 or 24)")
      ("patch-radius",
       defaulted(&descriptor_options.patch.radius),
       "patch radius for molecule/mesh inputs, A (about 5 for ligands, larger for sites)")
      ("max-image-bytes",
       defaulted(&descriptor_options.max_image_bytes),
       "limit: memory of the shape images of a molecule/mesh input, bytes");
  // clang-format on
  add_surface_options(described, input);
  po::variables_map vm;
  if (!parse_command_line(args, described, 2, kUsage, vm)) return 0;
  const auto inputs =
      vm.count("input") ? vm["input"].as<std::vector<std::string>>() : std::vector<std::string>{};
  if (inputs.size() != 2) throw OptionError("expected REF and PROBE (see --help)");
  finish_surface_options(input);
  options.max_clique_work = max_clique_work;
  options.max_cliques = static_cast<std::size_t>(max_cliques);
  g.max_nodes = static_cast<std::size_t>(max_graph_nodes);
  require_in_range("top", top, 1, 1e9);
  require_in_range("site-radius", site_options.sphere_radius, 0.1, 100.0);
  require_in_range("site-margin", site_options.surface_margin, 0.0, 1000.0);
  require_in_range("fuzzy-threshold", g.fuzzy_threshold, 0.0, 1.0);
  require_in_range("image-threshold", g.image_threshold, -1.0, 1.0);
  require_in_range("distance-tolerance", g.distance_tolerance, 0.0, 100.0);
  require_in_range("min-distance", g.min_distance, 0.0, 100.0);
  require_in_range("overlap-tolerance", g.overlap_tolerance_degrees, 0.0, 180.0);
  require_positive("rmsd-cut", options.clustering.rmsd_cut, 100.0);
  require_in_range("patch-radius", descriptor_options.patch.radius, 0.1, 100.0);
  // The margin's default covers patches of 8 A; larger patches reach farther.
  if (vm["site-margin"].defaulted()) {
    site_options.surface_margin =
        std::max(site_options.surface_margin,
                 descriptor_options.patch.radius + matching::surface_margin_beyond_patch);
  }
  require_in_range("refine-top", options.refine_top, 0, 1e6);
  require_in_range("overlay-sigma", options.overlay.sigma, 0.1, 10.0);
  require_in_range("overlay-chem-weight", options.overlay.chem_weight, 0.0, 100.0);
  require_in_range("overlay-atom-weight", options.overlay.atom_weight, 0.0, 1000.0);
  require_in_range("overlay-tolerance", options.overlay.tolerance, 0.0, 10.0);
  require_in_range("polish-top", options.polish_top, 0, 1e6);
  require_in_range("site-overlay-radius", options.site.overlay_radius, 0.1, 100.0);
  require_in_range("site-chem-weight", options.site.chem_weight, 0.0, 100.0);
  for (const auto& [name, value] :
       {std::pair<const char*, int>{"principal-axes-starts", options.principal_axes_starts},
        std::pair<const char*, int>{"site-principal-axes-starts",
                                    options.site.principal_axes_starts}}) {
    if (!matching::is_axes_start_count(value)) {
      throw OptionError(std::string("--") + name + " must be 0, 4 or 24, got " +
                        std::to_string(value));
    }
  }
  require_one_of("ranking", ranking, {"rank", "number", "vote"});
  options.ranking.scheme = ranking == "number" ? matching::ConsensusScheme::rank_by_number
                           : ranking == "vote" ? matching::ConsensusScheme::rank_by_vote
                                               : matching::ConsensusScheme::rank_by_rank;
  std::vector<matching::SiteSphere> ref_spheres, probe_spheres;
  for (const auto& text : site_spheres) {
    ref_spheres.push_back(parse_sphere(text));
    probe_spheres.push_back(parse_sphere(text));
  }
  for (const auto& text : ref_site_spheres) ref_spheres.push_back(parse_sphere(text));
  for (const auto& text : probe_site_spheres) probe_spheres.push_back(parse_sphere(text));
  const char* ref_site_option = ref_site_ligand.empty() ? "--site-ligand" : "--ref-site-ligand";
  const char* probe_site_option =
      probe_site_ligand.empty() ? "--site-ligand" : "--probe-site-ligand";
  if (!site_ligand.empty()) {
    if (ref_site_ligand.empty()) ref_site_ligand = site_ligand;
    if (probe_site_ligand.empty()) probe_site_ligand = site_ligand;
  }
  if (!ref_site_ligand.empty() || !probe_site_ligand.empty() || !ref_spheres.empty() ||
      !probe_spheres.empty()) {
    options.mode = matching::MatchMode::binding_sites;
  }
  matching::validate(options);
  const std::filesystem::path ref_path = inputs[0], probe_path = inputs[1];
  check_side("REF", ref_path, input, ref_site_option, ref_site_ligand);
  check_side("PROBE", probe_path, input, probe_site_option, probe_site_ligand);
  const std::vector<std::string> aligned = aligned_formats(probe_path);
  check_command_files(
      {{{"REF", ref_path}, {"PROBE", probe_path}, {"--molecule", input.molecule_file}},
       {{"--output", output, {}, ""},
        {"--aligned-out", aligned_out, aligned,
         aligned.size() == 1   ? "PROBE is not a molecule"
         : aligned.size() == 2 ? "PROBE is not an SDF, MOL or MOL2 file"
                               : ""}}});

  Stopwatch clock;
  // A .hsi side fixes the descriptor parameters the other side is built with; the limit stays
  // the command line's.
  const std::int64_t max_image_bytes = descriptor_options.max_image_bytes;
  if (harmonic::io::is_hsi_file(ref_path) && !harmonic::io::is_hsi_file(probe_path)) {
    descriptor_options = harmonic::io::read_hsi(ref_path).options;
  } else if (harmonic::io::is_hsi_file(probe_path) && !harmonic::io::is_hsi_file(ref_path)) {
    descriptor_options = harmonic::io::read_hsi(probe_path).options;
  }
  descriptor_options.max_image_bytes = max_image_bytes;
  // Both inputs are read (and their surfaces built) before either is described, so that a
  // probe that cannot be matched is refused before the reference's descriptors are computed.
  Side ref = load_side(ref_path, input, ref_site_ligand, std::move(ref_spheres), site_options);
  Side probe =
      load_side(probe_path, input, probe_site_ligand, std::move(probe_spheres), site_options);
  describe_side(ref, descriptor_options);
  describe_side(probe, descriptor_options);
  if (!same_options(ref.descriptors.options, probe.descriptors.options)) {
    throw InputError(
        ref_path.string() + " and " + probe_path.string() +
        ": the .hsi files were built with different parameters (critical point radius, "
        "patch radius, spring weights or image grid); rebuild one with the other's");
  }
  std::vector<bool> ref_allowed, probe_allowed;
  for (Side* side : {&ref, &probe}) {
    if (side->site.empty()) continue;
    auto& allowed = side == &ref ? ref_allowed : probe_allowed;
    allowed = matching::critical_points_in_site(side->descriptors, side->site);
    if (std::find(allowed.begin(), allowed.end(), true) == allowed.end()) {
      throw InputError(side->path.string() + ": the binding site holds no critical point (" +
                       std::to_string(side->site.size()) + " spheres, " +
                       std::to_string(side->descriptors.critical_points.size()) +
                       " critical points)");
    }
  }
  if (ref.site.empty() && probe.site.empty() && options.overlay.atom_weight > 0.0 &&
      ref.descriptors.atoms.empty() != probe.descriptors.atoms.empty()) {
    const Side& without = ref.descriptors.atoms.empty() ? ref : probe;
    std::fprintf(
        stderr,
        "note: %s carries no atoms (a mesh, or a .hsi file of format version 1): poses are judged "
        "on the surfaces alone\n",
        without.path.string().c_str());
  }
  const double prepare_ms = clock.elapsed_ms();
  const matching::MatchResult result = matching::match_surfaces(
      ref.descriptors, probe.descriptors, options, ref_allowed.empty() ? nullptr : &ref_allowed,
      probe_allowed.empty() ? nullptr : &probe_allowed);
  const double total_ms = clock.elapsed_ms();
  const std::vector<std::string> warnings = match_warnings(result, options);
  for (const std::string& warning : warnings)
    std::fprintf(stderr, "surfcomp match: warning: %s\n", warning.c_str());

  if (vm["trace"].as<bool>()) {
    std::printf("%-16s %8s %10s %10s\n", "stage", "nodes", "edges", "ms");
    for (const auto& stage : result.trace) {
      std::printf("%-16s %8zu %10zu %10.2f\n", stage.stage.c_str(), stage.nodes, stage.edges,
                  stage.milliseconds);
    }
    std::printf("%zu maximal cliques\n\n", result.cliques);
  }
  std::printf("%s vs %s: %zu alignments, surfaces and images %.0f ms, match %.0f ms\n",
              ref_path.string().c_str(), probe_path.string().c_str(), result.alignments.size(),
              prepare_ms, total_ms - prepare_ms);
  if (!result.alignments.empty()) {
    std::printf("%5s %-7s %8s %8s %8s %9s %8s %6s %7s  %s\n", "rank", "from", "rmsd", "points",
                "r_chem", "consensus", "overlay", "pairs", "parent",
                "rotation (deg) / translation (A)");
  }
  for (const auto& a : result.alignments) {
    if (a.rank > top) break;
    const Eigen::Matrix3d r = a.transform.topLeftCorner<3, 3>();
    const double angle = std::acos(std::clamp((r.trace() - 1.0) / 2.0, -1.0, 1.0)) * 180.0 / M_PI;
    if (a.source == matching::AlignmentSource::cliques) {
      std::printf("%5d %-7s %8.3f %8zu %8.3f %9.3f %7.3f%s %6zu %7s  %.1f / (%.2f, %.2f, %.2f)\n",
                  a.rank, "cliques", a.rmsd, a.n_points, a.r_chem, a.consensus, a.overlay.score,
                  a.refined ? "*" : " ", a.cp_pairs.size(),
                  a.parent > 0 ? std::to_string(a.parent).c_str() : "-", angle, a.transform(0, 3),
                  a.transform(1, 3), a.transform(2, 3));
    } else {  // no CP correspondences behind it: no fit RMSD, points, R_chem, consensus or tree
      std::printf("%5d %-7s %8s %8s %8s %9s %7.3f%s %6s %7s  %.1f / (%.2f, %.2f, %.2f)\n", a.rank,
                  "axes", "-", "-", "-", "-", a.overlay.score, a.refined ? "*" : " ", "-", "-",
                  angle, a.transform(0, 3), a.transform(1, 3), a.transform(2, 3));
    }
  }
  // Outputs last, each atomic; a failure of the second removes the first.
  if (!aligned_out.empty()) {
    if (result.alignments.empty())
      throw InputError("no alignment found: nothing to write to " + aligned_out);
    write_aligned(probe, result.alignments.front().transform, aligned_out);
  }
  if (!output.empty()) {
    try {
      const nlohmann::json document = to_json(result, options, ref, probe, warnings);
      surfcomp::io::write_file_atomically(
          output, [&](std::ostream& out) { out << document.dump(2) << "\n"; });
    } catch (...) {
      if (!aligned_out.empty()) std::filesystem::remove(aligned_out);
      throw;
    }
  }
  return 0;
}

}  // namespace surfcomp::tools
