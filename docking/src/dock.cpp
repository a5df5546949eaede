#include "surfcomp/docking/dock.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/docking/complement.hpp"
#include "surfcomp/mesh/topology.hpp"

#include "require_option.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>
#include <utility>

namespace surfcomp::docking {
namespace {

/// The match that finds the starting poses: the user's graph and clique settings, ranked by
/// the consensus alone (the similarity overlay, atom polish, coverage and ICP would judge a
/// pose by likeness, which a dock does not seek).
matching::MatchOptions start_options(const matching::MatchOptions& asked) {
  matching::MatchOptions m = asked;
  m.mode = matching::MatchMode::whole_surfaces;
  m.refine_top = 0;
  m.polish_top = 0;
  m.atom_polish.sigma = 0.0;
  m.coverage_distance = 0.0;
  m.icp_top = 0;
  return m;
}

std::size_t protein_atoms(const Molecule& molecule) {
  return static_cast<std::size_t>(std::count_if(molecule.atoms.begin(), molecule.atoms.end(),
                                                [](const Atom& a) { return !a.hetero; }));
}

Eigen::Matrix3Xd heavy_atoms(const harmonic::SurfaceDescriptors& d) {
  Eigen::Matrix3Xd points(3, static_cast<Eigen::Index>(d.atoms.size()));
  for (std::size_t i = 0; i < d.atoms.size(); ++i)
    points.col(static_cast<Eigen::Index>(i)) = d.atoms[i].position;
  return points;
}

/// The sample of a described ligand's surface at `spacing` that `field`'s score reads, its metal
/// atoms' points lifted (lift_metal_points).
LigandSample scored_sample(const harmonic::SurfaceDescriptors& ligand, double spacing,
                           const ReceptorField& field) {
  LigandSample sample = sample_ligand(ligand.surface, spacing);
  lift_metal_points(sample, ligand.atoms, field.options().metal_allowance);
  return sample;
}

DockPose scored_pose(const ReceptorField& field, const matching::RigidTransform& pose,
                     const ComplementarityScore& score) {
  DockPose out;
  out.transform = pose.matrix();
  out.score = score;
  out.intersects = intersects(score, field.options());
  return out;
}

void rank(std::vector<DockPose>& poses) {
  std::stable_sort(poses.begin(), poses.end(), [](const DockPose& x, const DockPose& y) {
    if (x.intersects != y.intersects) return !x.intersects;
    return x.score.score > y.score.score;
  });
}

/// One docked conformation of the ligand: what the score reads of it, and its heavy atoms to
/// tell poses apart.
struct Conformation {
  LigandSample sample;  ///< the score's (ComplementarityOptions::sample_spacing)
  LigandSample coarse;  ///< the search's (SearchOptions::sample_spacing)
  Eigen::Matrix3Xd atoms;
};

/// The index into `ligands` of pose's conformation (DockPose::conformer counts from 1 when the
/// ligand's own coordinates are not docked).
std::size_t slot(const DockPose& pose) {
  return pose.conformer == 0 ? 0 : static_cast<std::size_t>(pose.conformer - 1);
}

/// The first options.poses distinct candidates by (intersects, score), after the best
/// 4 options.poses of them are refined to convergence (the search stops its optimisations
/// early). Two poses are one when their heavy atoms, each conformation's moved by its pose,
/// lie within distinct_rmsd (the conformers of one record share their atom order).
std::vector<DockPose> best_distinct(const ReceptorField& field,
                                    const std::vector<Conformation>& ligands,
                                    std::vector<DockPose> candidates, const DockOptions& options) {
  rank(candidates);
  const std::size_t polished =
      std::min(candidates.size(), 4 * static_cast<std::size_t>(options.poses));
  for (std::size_t k = 0; k < polished; ++k) {
    DockPose& pose = candidates[k];
    const LigandSample& sample = ligands[slot(pose)].sample;
    const matching::RigidTransform moved =
        refine_pose(field, sample, matching::RigidTransform::from_matrix(pose.transform));
    DockPose refined = scored_pose(field, moved, field.score(sample, moved));
    refined.start = pose.start;
    refined.conformer = pose.conformer;
    refined.cp_pairs = std::move(pose.cp_pairs);
    pose = std::move(refined);
  }
  rank(candidates);
  std::vector<DockPose> out;
  std::vector<Eigen::Matrix3Xd> kept;  // out's heavy atoms, placed
  for (DockPose& pose : candidates) {
    if (static_cast<int>(out.size()) >= options.poses) break;
    const Eigen::Matrix3Xd placed =
        matching::RigidTransform::from_matrix(pose.transform).apply(ligands[slot(pose)].atoms);
    const bool repeats = std::any_of(kept.begin(), kept.end(), [&](const Eigen::Matrix3Xd& p) {
      return p.cols() > 0 &&
             std::sqrt((p - placed).colwise().squaredNorm().mean()) < options.distinct_rmsd;
    });
    if (repeats) continue;
    pose.rank = static_cast<int>(out.size()) + 1;
    out.push_back(std::move(pose));
    kept.push_back(placed);
  }
  return out;
}

/// The ligand sides a dock places: `ligand` itself, or its record's conformers (their MDL
/// blocks in `blocks`), each with the ligand's name.
std::vector<matching::MatchInput> ligand_conformations(const matching::MatchInput& ligand,
                                                       const DockOptions& options,
                                                       std::vector<std::string>& blocks) {
  if (options.conformers == 0) return {ligand};
  const io::MoleculeReadOptions& read = options.inputs.input.read;
  const Molecule own = io::read_molecule(ligand.path, read);  // the record, checked as read
  const std::vector<io::MoleculeRecord> records = io::read_molecule_records(ligand.path);
  const io::MoleculeRecord& record = records.at(read.record == 0 ? 0 : read.record - 1);
  ConformerOptions asked;
  asked.count = options.conformers;
  asked.seed = options.conformer_seed;
  asked.hydrogens = std::any_of(own.atoms.begin(), own.atoms.end(),
                                [](const Atom& a) { return a.element == "H"; });
  blocks = generate_conformers(record, asked);
  std::vector<matching::MatchInput> out;
  for (const std::string& block : blocks) {
    io::MoleculeRecord conformer = record;
    conformer.format = io::RecordFormat::mdl;
    conformer.text = block;
    matching::MatchInput side;
    side.molecule = io::read_record_molecule(conformer, read);
    side.molecule->source = ligand.path.string();
    out.push_back(std::move(side));
  }
  return out;
}

/// Throws InputError unless `receptor` is a structure whose atoms can be read (a dock builds
/// the receptor's grid from them), and as check_match_input for it with its dock site.
void check_dock_receptor(const matching::MatchInput& receptor, const DockOptions& options) {
  if (receptor.path.empty() && !receptor.molecule) {
    throw InputError(receptor.name() +
                     ": a receptor is a protein structure, not a surface or a description");
  }
  matching::check_match_input(with_dock_site(receptor, options), options.inputs, "RECEPTOR");
  if (!receptor.path.empty() && !io::is_structure_file(receptor.path))
    throw InputError(receptor.path.string() + ": a receptor is a structure file");
}

}  // namespace

const options::Table<DockOptions>& dock_option_table() {
  using options::Kind;
  using D = DockOptions;
  static const options::Table<D> table = [] {
    options::Table<D> t;
    options::append(
        t, molsurf::surface_input_option_table(), [](auto& d) -> auto& { return d.inputs.input; });
    options::append(
        t, harmonic::descriptor_option_table(),
        [](auto& d) -> auto& { return d.inputs.descriptors; },
        {"critical-point-radius", "disc-radius", "image-rings", "image-sectors", "weights"});
    options::append(
        t,
        options::pick(matching::match_option_table(),
                      {"fuzzy-threshold", "image-threshold", "distance-tolerance", "min-distance",
                       "overlap-tolerance", "max-graph-nodes", "max-clique-work", "max-cliques",
                       "rmsd-cut", "ranking"}),
        [](auto& d) -> auto& { return d.inputs.match; });
    options::append(
        t, molsurf::binding_site_option_table(), [](auto& d) -> auto& { return d.inputs.site; });
    options::append(
        t, molsurf::pocket_option_table(), [](auto& d) -> auto& { return d.inputs.pockets; });
    using C = ComplementarityOptions;
    const auto score = [](options::Spec spec, double C::*member) {
      return options::field<D>(
          std::move(spec), [member](auto& d) -> auto& { return d.complementarity.*member; });
    };
    t.push_back(score({"contact-gap", Kind::real,
                       "gap from the ligand's surface to the receptor's atoms at which contact "
                       "counts fully",
                       "A", -2.0, 2.0},
                      &C::contact_gap));
    t.push_back(score({"contact-width", Kind::real, "width of the contact term about the gap", "A",
                       0.0, 5.0, true},
                      &C::contact_width));
    t.push_back(score({"clash-tolerance", Kind::real,
                       "depth inside the receptor's atoms a ligand surface point may reach "
                       "before it clashes",
                       "A", 0.0, 3.0},
                      &C::clash_tolerance));
    t.push_back(score({"metal-allowance", Kind::real,
                       "how much smaller than their van der Waals radius metal atoms count "
                       "(coordination bonds are short)",
                       "A", 0.0, 3.0},
                      &C::metal_allowance));
    t.push_back(score({"clash-weight", Kind::real, "weight of the clash term", "1/A^2", 0.0, 1e3},
                      &C::clash_weight));
    t.push_back(score({"esp-weight", Kind::real,
                       "weight of the ESP term (opposite ESP across the contact)", "", 0.0, 100.0},
                      &C::esp_weight));
    t.push_back(score({"lp-weight", Kind::real,
                       "weight of the LP term (like LP across the contact)", "", 0.0, 100.0},
                      &C::lp_weight));
    t.push_back(score(
        {"site-weight", Kind::real,
         "weight of the restraint that keeps the ligand's centre in the site", "1/A^2", 0.0, 1e3},
        &C::site_weight));
    t.push_back(score({"grid-spacing", Kind::real, "spacing of the receptor's grid", "A", 0.1, 2.0},
                      &C::spacing));
    t.push_back(
        score({"grid-margin", Kind::real, "the grid's reach beyond the site", "A", 0.0, 50.0},
              &C::margin));
    t.push_back(score({"sample-spacing", Kind::real,
                       "spacing of the ligand surface points the score reads", "A", 0.2, 5.0},
                      &C::sample_spacing));
    t.push_back(options::field<D>(
        {"poses", Kind::integer, "poses reported", "", 1, 1000},
        [](auto& d) -> auto& { return d.poses; }));
    t.push_back(options::field<D>(
        {"refine-top", Kind::integer, "clique poses refined on the complementarity score", "", 1,
         10000},
        [](auto& d) -> auto& { return d.refine_top; }));
    t.push_back(options::field<D>(
        {"search-chains", Kind::integer,
         "Monte Carlo chains over the site, each from a random pose in it", "", 0, 100000},
        [](auto& d) -> auto& { return d.search.chains; }));
    t.push_back(options::field<D>(
        {"search-steps", Kind::integer,
         "moves per Monte Carlo chain, each followed by a local "
         "optimisation",
         "", 0, 100000},
        [](auto& d) -> auto& { return d.search.steps; }));
    t.push_back(options::field<D>(
        {"search-sample-spacing", Kind::real,
         "spacing of the ligand surface points the search scores (the best poses are then "
         "optimised on {sample_spacing}'s)",
         "A", 0.2, 5.0},
        [](auto& d) -> auto& { return d.search.sample_spacing; }));
    t.push_back(options::field<D>(
        {"search-min-gain", Kind::real,
         "the chains' local optimisations stop when a step gains less than this", "score", 1e-12,
         1.0},
        [](auto& d) -> auto& { return d.search.min_gain; }));
    t.push_back(options::field<D>(
        {"search-temperature", Kind::real, "the Monte Carlo chains' temperature", "score", 1e-6,
         100.0},
        [](auto& d) -> auto& { return d.search.temperature; }));
    t.push_back(options::field<D>(
        {"conformers", Kind::integer,
         "dock this many ETKDG + MMFF conformers of the ligand instead of its own coordinates "
         "(0: its own)",
         "", 0, 1000},
        [](auto& d) -> auto& { return d.conformers; }));
    t.push_back(options::field<D>(
        {"conformer-seed", Kind::integer, "ETKDG's random seed (with {conformers})", "", 0,
         2147483647.0},
        [](auto& d) -> auto& { return d.conformer_seed; }));
    t.push_back(options::field<D>(
        {"distinct-rmsd", Kind::real, "poses whose ligand atoms lie closer than this are one pose",
         "A", 0.0, 100.0},
        [](auto& d) -> auto& { return d.distinct_rmsd; }));
    t.push_back(options::field<D>(
        {"local-only", Kind::flag,
         "optimise the ligand's own pose on the score and report it alone (no match, no "
         "search)"},
        [](auto& d) -> auto& { return d.local_only; }));
    t.push_back(options::field<D>(
        {"score-only", Kind::flag, "score the ligand's own pose as it is and report it alone"},
        [](auto& d) -> auto& { return d.score_only; }));
    t.push_back(options::field<D>(
        {"max-ligand-to-site", Kind::real,
         "refuse a ligand of more than this many times the site's free volume", "", 0.0, 1e6, true},
        [](auto& d) -> auto& { return d.max_ligand_to_site; }));
    t.push_back(options::field<D>(
        molsurf::site_ligand_spec(), [](auto& d) -> auto& { return d.site_ligand; }));
    t.push_back(molsurf::sphere_option<D>(
        molsurf::site_sphere_spec(), [](auto& d) -> auto& { return d.site_spheres; }));
    t.push_back(options::field<D>(
        molsurf::site_pocket_spec(), [](auto& d) -> auto& { return d.site_pocket; }));
    t.push_back(options::threads_option<D>([](auto& d) -> auto& { return d.inputs.threads; }));
    return t;
  }();
  return table;
}

void validate(const DockOptions& options) {
  docking::validate(options.complementarity);
  docking::validate(options.search);
  const auto require = detail::require_option;
  require(options.poses >= 1, "poses", options.poses, ">= 1");
  require(options.refine_top >= 1, "refine_top", options.refine_top, ">= 1");
  require(std::isfinite(options.distinct_rmsd) && options.distinct_rmsd >= 0.0, "distinct_rmsd",
          options.distinct_rmsd, "finite and >= 0");
  require(std::isfinite(options.max_ligand_to_site) && options.max_ligand_to_site > 0.0,
          "max_ligand_to_site", options.max_ligand_to_site, "finite and > 0");
  require(options.conformers >= 0 && options.conformers <= 1000, "conformers", options.conformers,
          "in [0, 1000]");
  require(options.conformer_seed >= 0, "conformer_seed", options.conformer_seed, ">= 0");
  if (options.local_only && options.score_only) {
    throw OptionError(options::named("local_only") + " and " + options::named("score_only") +
                      " are two answers to one question: give one");
  }
  if ((options.local_only || options.score_only) && options.conformers > 0) {
    throw OptionError(options::named(options.local_only ? "local_only" : "score_only") +
                      " keeps the ligand's own pose, and " + options::named("conformers") +
                      " docks new conformers in its place: give one");
  }
}

matching::MatchInput with_dock_site(matching::MatchInput receptor, const DockOptions& options) {
  if (!options.site_ligand.empty()) receptor.site_ligand = options.site_ligand;
  receptor.site_spheres.insert(receptor.site_spheres.end(), options.site_spheres.begin(),
                               options.site_spheres.end());
  if (options.site_pocket != 0) receptor.site_pocket = options.site_pocket;
  if (receptor.site_ligand.empty() && receptor.site_spheres.empty() && receptor.site_pocket == 0)
    receptor.site_pocket = 1;  // the best detected pocket
  return receptor;
}

void check_dock_ligand(const matching::MatchInput& ligand, const DockOptions& options) {
  // A dock reads atoms: the ligand's to tell poses apart.
  if (ligand.path.empty() && !ligand.molecule) {
    throw InputError(
        ligand.name() +
        ": a ligand is a molecule (a file or its atoms), not a surface or a description");
  }
  matching::check_match_input(ligand, options.inputs, "LIGAND");
  if (!ligand.path.empty() && !io::is_molecule_file(ligand.path))
    throw InputError(ligand.path.string() + ": a ligand is a molecule file");
  if (!ligand.site_ligand.empty() || !ligand.site_spheres.empty() || ligand.site_pocket != 0)
    throw OptionError(ligand.name() + ": a site is the receptor's, not the ligand's");
  if (options.conformers > 0) {
    const io::MoleculeFormat* format = io::find_molecule_format(ligand.path);
    if (format == nullptr ||
        (format->kind != io::MoleculeFileKind::mdl && format->kind != io::MoleculeFileKind::mol2)) {
      throw OptionError(options::named("conformers") +
                        ": conformers are made from the bonds of "
                        "an SDF or MOL2 ligand file's record, and " +
                        ligand.name() + " is not one");
    }
  }
}

void check_dock_inputs(const matching::MatchInput& ligand, const matching::MatchInput& receptor,
                       const DockOptions& options) {
  validate(options);
  check_dock_ligand(ligand, options);
  check_dock_receptor(receptor, options);
}

DockSite prepare_dock_site(const matching::MatchInput& receptor, const DockOptions& options) {
  validate(options);
  check_dock_receptor(receptor, options);
  const matching::MatchInput receptor_input = with_dock_site(receptor, options);
  DockSite site;
  Stopwatch clock;
  site.receptor = matching::prepare_input(receptor_input, options.inputs);
  if (!site.receptor.molecule || protein_atoms(*site.receptor.molecule) == 0) {
    throw InputError(site.receptor.name +
                     ": the receptor has no protein atoms (ATOM records); a receptor is a protein "
                     "structure");
  }
  site.timing_ms.emplace_back("receptor surface and description", clock.elapsed_ms());
  clock.restart();
  site.field = std::make_shared<const ReceptorField>(*site.receptor.molecule, site.receptor.site,
                                                     options.complementarity);
  site.free_volume = site.field->free_volume(site.receptor.site);
  if (!site.field->site_opens(site.receptor.site)) {
    throw InputError(site.receptor.name +
                     ": the site is buried: no path of free space leads from it out of the "
                     "grid, so no ligand can enter it");
  }
  site.timing_ms.emplace_back("receptor field", clock.elapsed_ms());
  return site;
}

DockResult dock(const matching::MatchInput& ligand, const matching::MatchInput& receptor,
                const DockOptions& options) {
  check_dock_inputs(ligand, receptor, options);
  const DockSite site = prepare_dock_site(receptor, options);
  DockResult result = dock(ligand, site, options);
  result.timing_ms.insert(result.timing_ms.begin(), site.timing_ms.begin(), site.timing_ms.end());
  return result;
}

DockResult dock(const matching::MatchInput& ligand_input, const DockSite& site,
                const DockOptions& options) {
  validate(options);
  check_dock_ligand(ligand_input, options);
  if (!site.field) throw InputError(site.receptor.name + ": the dock site was not prepared");
  DockResult result;
  result.receptor = site.receptor;
  result.site_volume = site.free_volume;
  const ReceptorField& field = *site.field;
  Stopwatch clock;
  const std::vector<matching::MatchInput> sides =
      ligand_conformations(ligand_input, options, result.conformers);
  result.ligand = matching::prepare_input(sides.front(), options.inputs);
  result.ligand_volume = mesh::measure_surface(result.ligand.descriptors.surface).volume;
  if (result.ligand_volume > options.max_ligand_to_site * result.site_volume) {
    throw InputError(result.ligand.name + ": the ligand (" +
                     std::to_string(std::lround(result.ligand_volume)) + " A^3) is more than " +
                     options::named("max_ligand_to_site") + " " +
                     std::to_string(options.max_ligand_to_site) + " times the free volume of " +
                     result.receptor.name + "'s site (" +
                     std::to_string(std::lround(result.site_volume)) + " A^3)");
  }
  double surfaces_ms = clock.elapsed_ms();
  if (options.local_only || options.score_only) {
    clock.restart();
    const LigandSample sample =
        scored_sample(result.ligand.descriptors, options.complementarity.sample_spacing, field);
    matching::RigidTransform pose;
    if (options.local_only) pose = refine_pose(field, sample, pose);
    result.poses.push_back(scored_pose(field, pose, field.score(sample, pose)));
    result.poses.back().rank = 1;
    result.timing_ms = {{"ligand surfaces and descriptions", surfaces_ms},
                        {options.local_only ? "refinement" : "score", clock.elapsed_ms()}};
    return result;
  }

  std::vector<Conformation> ligands;
  std::vector<DockPose> candidates;
  double match_ms = 0.0, search_ms = 0.0;
  for (std::size_t k = 0; k < sides.size(); ++k) {
    clock.restart();
    matching::PreparedInput other;
    if (k > 0) other = matching::prepare_input(sides[k], options.inputs);
    const matching::PreparedInput& ligand = k == 0 ? result.ligand : other;
    ligands.push_back(
        {scored_sample(ligand.descriptors, options.complementarity.sample_spacing, field),
         scored_sample(ligand.descriptors, options.search.sample_spacing, field),
         heavy_atoms(ligand.descriptors)});
    surfaces_ms += clock.elapsed_ms();

    clock.restart();
    const matching::MatchResult starts = matching::match_surfaces(
        result.receptor.descriptors, complement(ligand.descriptors),
        start_options(options.inputs.match), &result.receptor.site_points, nullptr);
    if (k == 0) result.trace = starts.trace;
    if (!starts.cliques_complete && result.notes.empty()) {
      result.notes.push_back("the clique search stopped at its budget (" +
                             options::named("max_clique_work") + ", " +
                             options::named("max_cliques") + "): poses may be missing");
    }
    match_ms += clock.elapsed_ms();

    clock.restart();
    const int conformer = options.conformers > 0 ? static_cast<int>(k) + 1 : 0;
    // Optimised on the coarse sample, scored on the score's own.
    const LigandSample& sample = ligands.back().sample;
    const LigandSample& coarse = ligands.back().coarse;
    int refined = 0;
    for (const matching::Alignment& a : starts.alignments) {
      if (a.repeat_of != 0) continue;
      ++result.starts;
      if (refined >= options.refine_top) continue;
      ++refined;
      const matching::RigidTransform moved =
          refine_pose(field, coarse, matching::RigidTransform::from_matrix(a.transform),
                      options.search.min_gain);
      DockPose pose = scored_pose(field, moved, field.score(sample, moved));
      pose.start = a.rank;
      pose.cp_pairs = a.cp_pairs;
      pose.conformer = conformer;
      candidates.push_back(std::move(pose));
    }
    SearchOptions search = options.search;
    search.seed += k;  // each conformer's chains start elsewhere
    for (const SearchedPose& found : search_site(field, coarse, result.receptor.site, search)) {
      candidates.push_back(scored_pose(field, found.pose, field.score(sample, found.pose)));
      candidates.back().conformer = conformer;
    }
    search_ms += clock.elapsed_ms();
    if (options.conformers > 0)
      result.conformer_inputs.push_back(k == 0 ? result.ligand : std::move(other));
  }
  clock.restart();
  result.poses = best_distinct(field, ligands, std::move(candidates), options);
  search_ms += clock.elapsed_ms();
  if (result.starts == 0 && !result.poses.empty())
    result.notes.push_back(
        "no clique of the complementary association graph: the poses are the search's alone");
  if (result.poses.empty())
    result.notes.push_back("no pose: no clique, and no search (" + options::named("search_chains") +
                           " 0)");
  const io::MoleculeFormat* format = io::find_molecule_format(ligand_input.path);
  if (options.conformers > 0 && format != nullptr && format->kind == io::MoleculeFileKind::mol2 &&
      options.inputs.input.read.charges == io::ChargeModel::file) {
    result.notes.push_back(
        "the conformers carry no charges of the MOL2 file: theirs are computed (Gasteiger)");
  }
  result.timing_ms = {{"ligand surfaces and descriptions", surfaces_ms},
                      {"complementary match", match_ms},
                      {"refinement", search_ms}};
  return result;
}

}  // namespace surfcomp::docking
