#include "surfcomp/matching/match_inputs.hpp"

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/file_extension.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/io/hsi_file.hpp"
#include "surfcomp/mesh/io/read_mesh.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

namespace surfcomp::matching {
namespace {

void log(const MatchInputOptions& options, const std::string& text) {
  if (options.log) options.log(text);
}

std::string milliseconds(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f ms", ms);
  return text;
}

bool is_stored_description(const MatchInput& input) {
  return input.descriptors || (!input.path.empty() && harmonic::io::is_hsi_file(input.path));
}

/// A side read or built, not yet described.
struct LoadedInput {
  std::string name;
  std::optional<harmonic::SurfaceDescriptors> descriptors;  // a stored description
  std::optional<mesh::Surface> surface;
  std::optional<Molecule> molecule;
  std::vector<molsurf::SiteSphere> site;
  /// The surface still needs its curvature, computed once its length unit is known (a mesh
  /// read without a molecule, or a surface in memory without curvature).
  bool needs_curvature = false;
  /// MatchInput::curvature_unit: the unit the surface's curvature was fitted at (0: none).
  double curvature_unit = 0.0;
  std::optional<mesh::RepairReport> repair;  ///< what --repair changed in a mesh file
  std::vector<std::string> notes;            ///< molsurf::LoadedSurface::notes
};

/// The surface of a molecule with a site: the site's structure (binding_site) surfaced around
/// the site (build_site_surface).
void load_site(LoadedInput& side, const Molecule& structure, const MatchInput& input,
               const MatchInputOptions& options) {
  molsurf::BindingSite site =
      input.site_pocket > 0
          ? molsurf::pocket_site(structure, input.site_pocket, options.pockets, options.site)
      : input.site_ligand.empty()
          ? molsurf::binding_site(structure, input.site_spheres, options.site)
          : molsurf::binding_site(structure, parse_ligand_selector(input.site_ligand),
                                  options.site);
  if (!input.site_ligand.empty()) {  // spheres add to the ligand's
    site.spheres.insert(site.spheres.end(), input.site_spheres.begin(), input.site_spheres.end());
  }
  side.surface = molsurf::build_site_surface(site, options.input.surface);
  side.molecule = std::move(site.structure);
  side.site = std::move(site.spheres);
}

LoadedInput load_unlogged(const MatchInput& input, const MatchInputOptions& options);

/// `input` with the molecule of its molecule file read into MatchInput::molecule (its path
/// kept, for messages); any other input as it is.
MatchInput with_molecule_read(const MatchInput& input, const MatchInputOptions& options) {
  MatchInput out = input;
  if (!input.molecule && !input.surface && !input.descriptors && !input.path.empty() &&
      !harmonic::io::is_hsi_file(input.path) && io::is_molecule_file(input.path)) {
    out.molecule = io::read_molecule(input.path, options.input.read);
  }
  return out;
}

/// The side read or built, logged as `role`.
LoadedInput load(const MatchInput& input, const MatchInputOptions& options, const char* role) {
  const Stopwatch clock;
  LoadedInput side = load_unlogged(input, options);
  std::string text = std::string(role) + " " + side.name + ": ";
  if (side.descriptors) {
    text += "stored description, " + std::to_string(side.descriptors->surface.n_vertices()) +
            " vertices, " + std::to_string(side.descriptors->critical_points.size()) +
            " critical points";
  } else {
    if (side.molecule) text += std::to_string(side.molecule->atoms.size()) + " atoms, ";
    text += "surface of " + std::to_string(side.surface->n_vertices()) + " vertices";
    if (!side.site.empty())
      text += " around a site of " + std::to_string(side.site.size()) + " spheres";
  }
  log(options, text + " (" + milliseconds(clock.elapsed_ms()) + ")");
  return side;
}

LoadedInput load_unlogged(const MatchInput& input, const MatchInputOptions& options) {
  LoadedInput side;
  side.name = input.name();
  side.site = input.site_spheres;
  if (input.descriptors) {
    side.descriptors = *input.descriptors;
    return side;
  }
  if (!input.path.empty() && harmonic::io::is_hsi_file(input.path)) {
    side.descriptors = harmonic::io::read_hsi(input.path);
    return side;
  }
  const bool has_site =
      !input.site_ligand.empty() || !input.site_spheres.empty() || input.site_pocket > 0;
  std::optional<Molecule> molecule;  // a molecule whose surface is built here
  if (input.molecule && !input.surface) {
    molecule = *input.molecule;
  } else if (!input.path.empty() && io::is_molecule_file(input.path)) {
    molecule = io::read_molecule(input.path, options.input.read);
  }
  if (molecule && has_site) {
    load_site(side, *molecule, input, options);
  } else if (molecule) {
    side.surface = molsurf::build_molecular_surface(*molecule, options.input.surface);
    side.molecule = std::move(molecule);
  } else if (input.surface) {
    molsurf::check_vertex_limit(*input.surface, options.input);
    side.surface = *input.surface;
    side.molecule = input.molecule;
    for (const char* name : {mesh::property::cc1, mesh::property::cc2, mesh::property::shape_index,
                             mesh::property::curvedness}) {
      if (!side.surface->has_property(name)) side.needs_curvature = true;
    }
    if (!side.needs_curvature) side.curvature_unit = input.curvature_unit;
  } else if (options.input.molecule_file.empty()) {
    molsurf::check_surface_input(input.path, options.input);
    molsurf::LoadedSurface loaded = molsurf::read_mesh_input(input.path, options.input);
    side.surface = std::move(loaded.surface);
    side.repair = loaded.repair;
    side.notes = std::move(loaded.notes);
    side.needs_curvature = true;
  } else {
    molsurf::LoadedSurface loaded = molsurf::load_surface(input.path, options.input);
    side.surface = std::move(loaded.surface);
    side.molecule = std::move(loaded.molecule);
    side.repair = loaded.repair;
    side.notes = std::move(loaded.notes);
  }
  return side;
}

/// The loaded side's surface: a stored description's or the one read or built.
const mesh::Surface& surface_of(const LoadedInput& side) {
  return side.descriptors ? side.descriptors->surface : *side.surface;
}

bool carries_chemistry(const LoadedInput& side) {
  const mesh::Surface& surface = surface_of(side);
  return surface.has_property(mesh::property::esp) && surface.has_property(mesh::property::lp);
}

/// True for a side whose coordinates are in A: a molecule, a stored description, a surface with
/// ESP and LP, an MSMS mesh.
bool is_molecular(const LoadedInput& side, const MatchInput& input) {
  if (side.descriptors) return side.descriptors->length_unit == 1.0;
  if (side.molecule) return true;
  return mesh::is_molecular_mesh(*side.surface, io::lowercase_extension(input.path));
}

/// `value` with every digit, so that a user may copy it from a message.
std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

/// True for two length units equal but for the rounding of a file or a message (1e-9).
bool same_unit(double a, double b) { return std::abs(a - b) <= 1e-9 * std::max(a, b); }

/// The length unit of a pair (SurfaceInputOptions::scale and unit) and how it was chosen.
mesh::LengthUnit length_unit(const LoadedInput& ref, const MatchInput& reference,
                             const LoadedInput& prb, const MatchInput& probe,
                             const MatchInputOptions& options) {
  const molsurf::SurfaceInputOptions& input = options.input;
  if (input.unit > 0.0) {
    for (const auto& [side, given] : {std::pair{&ref, &reference}, std::pair{&prb, &probe}}) {
      if (is_molecular(*side, *given)) {
        throw OptionError(options::named("unit") + " applies to general meshes; " + side->name +
                          " is in A (a molecule, a mesh with ESP and LP, or a stored "
                          "description)");
      }
    }
  }
  const bool ref_in_angstrom = is_molecular(ref, reference);
  const bool probe_in_angstrom = is_molecular(prb, probe);
  for (const auto& [stored_side, other_in_angstrom] :
       {std::pair{&ref, probe_in_angstrom}, std::pair{&prb, ref_in_angstrom}}) {
    if (other_in_angstrom && stored_side->descriptors &&
        stored_side->descriptors->length_unit != 1.0) {
      throw InputError(stored_side->name + ": a general mesh's description in a unit of " +
                       number_text(stored_side->descriptors->length_unit) +
                       " cannot be matched with an input in A; rebuild it with " +
                       options::named("scale") + " none");
    }
  }
  if (ref_in_angstrom || probe_in_angstrom) return {};
  // A general mesh's stored description brings the unit it was described in.
  std::optional<double> stored;
  for (const LoadedInput* side : {&ref, &prb}) {
    if (!side->descriptors) continue;
    const double unit = side->descriptors->length_unit;
    if (stored && !same_unit(*stored, unit)) {
      throw InputError(ref.name + " and " + prb.name +
                       ": the .hsi files were described in different length units (" +
                       number_text(*stored) + " and " + number_text(unit) +
                       "); rebuild one with the other's " + options::named("unit"));
    }
    stored = unit;
  }
  if (stored) {
    if (input.unit > 0.0 && !same_unit(input.unit, *stored)) {
      throw OptionError(options::named("unit") + " " + number_text(input.unit) +
                        ": the stored description is in a unit of " + number_text(*stored) +
                        "; give that unit or leave " + options::named("unit") + " out");
    }
    return {*stored, "stored"};
  }
  return mesh::general_mesh_unit({&*ref.surface, &*prb.surface}, input.scale, input.unit,
                                 ref.name + " and " + prb.name);
}

/// The curvature of a side that still needs it (LoadedInput::needs_curvature), in the length
/// unit its surface now has: over the molecular surface's neighbourhood, or for a general mesh
/// as molsurf::assign_general_mesh_curvature fits it.
void complete(LoadedInput& side, const MatchInputOptions& options, bool general_mesh) {
  if (!side.needs_curvature) return;
  if (general_mesh) {
    molsurf::assign_general_mesh_curvature(*side.surface, 1.0, options.input.surface.curvature);
  } else {
    molsurf::assign_surface_properties(*side.surface, nullptr, options.input.surface);
  }
  side.needs_curvature = false;
}

/// The side's surface and site spheres scaled by `factor` (a change of length unit); its
/// curvature is computed again at the new unit (but see settle_curvature).
void scale_side(LoadedInput& side, double factor) {
  if (side.descriptors) {
    harmonic::scale_descriptors(*side.descriptors, factor);
    return;
  }
  mesh::scale_surface(*side.surface, factor);
  side.needs_curvature = true;
  for (molsurf::SiteSphere& sphere : side.site) {
    sphere.center *= factor;
    sphere.radius *= factor;
  }
}

/// A side described in `unit` whose curvature was fitted at a unit (LoadedInput::curvature_unit)
/// keeps it when that is `unit` and has it fitted again otherwise.
void settle_curvature(LoadedInput& side, double unit) {
  if (side.curvature_unit > 0.0) side.needs_curvature = !same_unit(side.curvature_unit, unit);
}

/// A prepared side and the match result given back in the inputs' coordinates.
void unscale(PreparedInput& side, double unit) {
  harmonic::scale_descriptors(side.descriptors, unit);
  for (molsurf::SiteSphere& sphere : side.site) {
    sphere.center *= unit;
    sphere.radius *= unit;
  }
}

void unscale(MatchResult& result, double unit) {
  for (Alignment& a : result.alignments) {
    a.transform.topRightCorner<3, 1>() *= unit;
    a.rmsd *= unit;
  }
}

PreparedInput describe_unlogged(LoadedInput side, const harmonic::DescriptorOptions& options);

/// The side described, logged as `role`.
PreparedInput describe(LoadedInput side, const harmonic::DescriptorOptions& descriptors,
                       const MatchInputOptions& options, const char* role) {
  const Stopwatch clock;
  const bool stored = side.descriptors.has_value();
  PreparedInput prepared = describe_unlogged(std::move(side), descriptors);
  if (!stored) {
    const harmonic::DescriptorCounts counts = harmonic::count_descriptors(prepared.descriptors);
    log(options, std::string(role) + " " + prepared.name + ": " + std::to_string(counts.peaks) +
                     " peaks, " + std::to_string(counts.valleys) + " valleys, " +
                     std::to_string(counts.imaged) + " imaged (" +
                     milliseconds(clock.elapsed_ms()) + ")");
  }
  return prepared;
}

PreparedInput describe_unlogged(LoadedInput side, const harmonic::DescriptorOptions& options) {
  PreparedInput prepared;
  prepared.name = std::move(side.name);
  prepared.notes = std::move(side.notes);
  prepared.site = std::move(side.site);
  prepared.molecule = std::move(side.molecule);
  if (side.descriptors) {
    prepared.descriptors = std::move(*side.descriptors);
  } else {
    mesh::Surface surface = std::move(*side.surface);
    const Molecule* molecule = prepared.molecule ? &*prepared.molecule : nullptr;
    if (prepared.site.empty()) {
      prepared.descriptors =
          molecule ? harmonic::describe_surface(std::move(surface), *molecule, options)
                   : harmonic::describe_surface(std::move(surface), options);
    } else {
      prepared.descriptors =
          molecule ? describe_site(std::move(surface), *molecule, prepared.site, options)
                   : describe_site(std::move(surface), prepared.site, options);
    }
  }
  if (!prepared.site.empty()) {
    prepared.site_points = critical_points_in_site(prepared.descriptors, prepared.site);
    if (std::find(prepared.site_points.begin(), prepared.site_points.end(), true) ==
        prepared.site_points.end()) {
      throw InputError(prepared.name + ": the binding site holds no critical point (" +
                       std::to_string(prepared.site.size()) + " spheres, " +
                       std::to_string(prepared.descriptors.critical_points.size()) +
                       " critical points)");
    }
  }
  return prepared;
}

bool same_parameters(const harmonic::DescriptorOptions& x, const harmonic::DescriptorOptions& y) {
  return x.critical_points.radius == y.critical_points.radius &&
         x.critical_points.property_disc_radius == y.critical_points.property_disc_radius &&
         x.critical_points.distance == y.critical_points.distance &&
         x.patch.radius == y.patch.radius && x.patch.margin == y.patch.margin &&
         x.patch.distance == y.patch.distance && x.disk_map.weights == y.disk_map.weights &&
         x.image.rings == y.image.rings && x.image.sectors == y.image.sectors &&
         x.image_property == y.image_property;
}

bool has_site(const MatchInput& input) {
  return !input.site_ligand.empty() || !input.site_spheres.empty() || input.site_pocket > 0;
}

/// What the clique search's stop means for the match: reaching the clique budget
/// (--max-cliques) is the budget at work, told as a note; running out of work
/// (--max-clique-work) cut a search that had no end in sight, a warning.
void tell_clique_stop(const MatchResult& result, const MatchOptions& options, InputMatch& out) {
  if (result.cliques_complete) return;
  if (result.cliques >= options.max_cliques) {
    out.notes.push_back("the clique budget took the first " + std::to_string(result.cliques) +
                        " cliques the search found (" + options::named("max_cliques") + ")");
  } else {
    out.warnings.push_back("clique search stopped after " + std::to_string(result.clique_work) +
                           " units of work (" + options::named("max_clique_work") + " " +
                           std::to_string(options.max_clique_work) +
                           "); alignments may be missing");
  }
}

}  // namespace

std::string MatchInput::name() const {
  if (!path.empty()) return path.string();
  if (descriptors) return descriptors->surface.source();
  if (surface) return surface->source();
  if (molecule) return molecule->source;
  return "<no input>";
}

void check_match_input(const MatchInput& input, const MatchInputOptions& options, const char* role,
                       const std::string& site_ligand_option) {
  const std::string site_option =
      site_ligand_option.empty() ? options::named("site_ligand") : site_ligand_option;
  const int given = static_cast<int>(!input.path.empty()) +
                    static_cast<int>(input.descriptors.has_value()) +
                    static_cast<int>(input.surface.has_value()) +
                    static_cast<int>(input.molecule.has_value() && !input.surface.has_value());
  if (given != 1) {
    throw InputError(std::string(role) +
                     ": expected one input (a file, a molecule, a surface or a description), "
                     "got " +
                     std::to_string(given));
  }
  const std::string name = std::string(role) + " " + input.name();
  if (!input.site_ligand.empty()) {
    LigandSelector selector;
    try {
      selector = parse_ligand_selector(input.site_ligand);
    } catch (const OptionError& error) {
      throw OptionError(site_option + " " + error.what());
    }
    if (is_water_residue(selector.residue_name)) {
      throw OptionError(site_option + " " + input.site_ligand +
                        ": waters (HOH, WAT, DOD) are dropped when a structure is read, so a "
                        "water cannot be a site ligand; give " +
                        options::named("site_sphere") + " x,y,z,r around it");
    }
    if (is_stored_description(input)) {
      throw OptionError(name + ": " + site_option + " needs the structure, not a .hsi file; use " +
                        options::named("site_sphere"));
    }
    if (input.surface) {
      throw OptionError(name + ": " + site_option + " needs the structure, not a surface; use " +
                        options::named("site_sphere"));
    }
    if (!input.path.empty() && !io::is_molecule_file(input.path)) {
      throw OptionError(name + ": " + site_option + " needs a molecule file (the structure); use " +
                        options::named("site_sphere"));
    }
    if (!options.input.read.ligand.empty())
      throw OptionError(options::named("ligand") + " and " + options::named("site_ligand") +
                        " cannot be combined");
  }
  if (input.site_pocket != 0) {
    if (input.site_pocket < 0) {
      throw OptionError(name + ": " + options::named("site_pocket") + " " +
                        std::to_string(input.site_pocket) + ": pockets are ranked from 1");
    }
    if (!input.site_ligand.empty() || !input.site_spheres.empty()) {
      throw OptionError(name + ": " + options::named("site_pocket") +
                        " is a whole site; it takes no " + options::named("site_ligand") + " or " +
                        options::named("site_sphere") + " beside it");
    }
    const bool structure_file = !input.path.empty() && !harmonic::io::is_hsi_file(input.path) &&
                                io::is_molecule_file(input.path);
    if (!structure_file && !(input.molecule && !input.surface)) {
      throw OptionError(name + ": " + options::named("site_pocket") +
                        " needs a structure (a PDB or mmCIF file) to find "
                        "pockets in");
    }
  }
  if (!input.path.empty() && !harmonic::io::is_hsi_file(input.path))
    molsurf::check_surface_input(input.path, options.input);
}

PreparedInput prepare_input(const MatchInput& input, const MatchInputOptions& options) {
  check_match_input(input, options, "input");
  MatchInputOptions built = options;
  built.site.surface_margin =
      molsurf::site_surface_margin(options.site.surface_margin, options.descriptors.patch.radius);
  LoadedInput side = load(input, built, "input");
  if (side.descriptors) {  // as it was stored, in its own unit
    const double stored = side.descriptors->length_unit;
    PreparedInput prepared = describe(std::move(side), options.descriptors, options, "input");
    prepared.unit = stored == 1.0 ? mesh::LengthUnit{} : mesh::LengthUnit{stored, "stored"};
    return prepared;
  }
  const bool general_mesh = !is_molecular(side, input);
  if (!general_mesh && options.input.unit > 0.0) {
    throw OptionError(options::named("unit") + " applies to general meshes; " + side.name +
                      " is in A (a molecule, a mesh with ESP and LP, or a stored description)");
  }
  const mesh::LengthUnit unit = general_mesh
                                    ? mesh::general_mesh_unit({&*side.surface}, options.input.scale,
                                                              options.input.unit, side.name)
                                    : mesh::LengthUnit{};
  if (unit.value != 1.0) scale_side(side, 1.0 / unit.value);
  settle_curvature(side, unit.value);
  complete(side, options, general_mesh);
  PreparedInput prepared = describe(std::move(side), options.descriptors, options, "input");
  if (unit.value != 1.0) unscale(prepared, unit.value);
  prepared.unit = unit;
  return prepared;
}

InputMatch match_inputs(const MatchInput& reference, const MatchInput& probe,
                        const MatchInputOptions& options) {
  MatchOptions match = options.match;
  if (has_site(reference) || has_site(probe)) match.mode = MatchMode::binding_sites;
  validate(match);
  check_match_input(reference, options, "REF");
  check_match_input(probe, options, "PROBE");
  if (options.input.unit > 0.0) {  // before any work: what the names tell
    for (const MatchInput* side : {&reference, &probe}) {
      const bool molecule = side->molecule.has_value() || !side->site_ligand.empty() ||
                            side->site_pocket > 0 ||
                            (!side->path.empty() && io::is_molecule_file(side->path)) ||
                            (!side->path.empty() && !options.input.molecule_file.empty());
      if (molecule) {
        throw OptionError(options::named("unit") + " applies to general meshes; " + side->name() +
                          " is in A (a molecule, or a mesh with " + options::named("molecule") +
                          ")");
      }
    }
  }

  InputMatch out;
  const Stopwatch clock;
  // Stored descriptions first: one fixes the parameters the other side is described with (the
  // image memory limit and the progress stay the caller's), and so the patch radius a site
  // surface on the other side must reach. Molecule files are read next, both before any
  // surface is built, so that a bad file on either side is refused before the heavy work.
  const bool ref_stored = is_stored_description(reference);
  const bool probe_stored = is_stored_description(probe);
  std::optional<LoadedInput> ref, prb;
  if (ref_stored) ref = load(reference, options, "REF");
  if (probe_stored) prb = load(probe, options, "PROBE");
  const MatchInput ref_read = with_molecule_read(reference, options);
  const MatchInput probe_read = with_molecule_read(probe, options);
  harmonic::DescriptorOptions descriptors = options.descriptors;
  if (ref_stored && !probe_stored) descriptors = ref->descriptors->options;
  if (probe_stored && !ref_stored) descriptors = prb->descriptors->options;
  descriptors.max_image_bytes = options.descriptors.max_image_bytes;
  descriptors.progress = options.descriptors.progress;
  MatchInputOptions built = options;
  built.site.surface_margin =
      molsurf::site_surface_margin(options.site.surface_margin, descriptors.patch.radius);
  if (!ref) ref = load(ref_read, built, "REF");
  if (!prb) prb = load(probe_read, built, "PROBE");
  for (const LoadedInput* side : {&*ref, &*prb})
    out.notes.insert(out.notes.end(), side->notes.begin(), side->notes.end());
  const bool asked_shape_only = match.shape_only;
  for (const LoadedInput* side : {&*ref, &*prb}) {
    if (!asked_shape_only && !carries_chemistry(*side)) {
      match.shape_only = true;
      out.notes.push_back(side->name + " carries no ESP and LP: matched by shape alone");
    }
  }
  out.shape_only = match.shape_only;
  const mesh::LengthUnit unit = length_unit(*ref, reference, *prb, probe, options);
  out.unit = unit.value;
  out.unit_from = unit.from;
  // Decided before the change of unit, which takes a stored description's unit to 1.
  const bool general_meshes = !is_molecular(*ref, reference) && !is_molecular(*prb, probe);
  if (out.unit != 1.0) {
    scale_side(*ref, 1.0 / out.unit);
    scale_side(*prb, 1.0 / out.unit);
    log(options, "length unit " + std::to_string(out.unit) + " (" + out.unit_from + ")");
  }
  settle_curvature(*ref, out.unit);
  settle_curvature(*prb, out.unit);
  complete(*ref, options, general_meshes);
  complete(*prb, options, general_meshes);
  out.reference = describe(std::move(*ref), descriptors, options, "REF");
  out.probe = describe(std::move(*prb), descriptors, options, "PROBE");
  if (!same_parameters(out.reference.descriptors.options, out.probe.descriptors.options)) {
    throw InputError(out.reference.name + " and " + out.probe.name +
                     ": the .hsi files were built with different parameters (critical point "
                     "radius, patch radius, spring weights or image grid); rebuild one with the "
                     "other's");
  }
  if (out.reference.site.empty() && out.probe.site.empty() && !match.shape_only &&
      match.overlay.atom_weight > 0.0 &&
      out.reference.descriptors.atoms.empty() != out.probe.descriptors.atoms.empty()) {
    const PreparedInput& without =
        out.reference.descriptors.atoms.empty() ? out.reference : out.probe;
    out.notes.push_back(without.name +
                        " carries no atoms (a mesh, or a .hsi file of format version 1): poses "
                        "are judged on the surfaces alone");
  }
  if (!match.shape_only && out.reference.molecule && out.probe.molecule &&
      !out.reference.site.empty() && !out.probe.site.empty()) {
    const auto ref_lining = lining_composition(*out.reference.molecule, out.reference.site);
    const auto probe_lining = lining_composition(*out.probe.molecule, out.probe.site);
    // A site that no amino acid lines has no composition: its score stays the overlay's.
    if (ref_lining && probe_lining) out.lining = lining_similarity(*ref_lining, *probe_lining);
  }
  out.prepare_ms = clock.elapsed_ms();
  out.result =
      match_surfaces(out.reference.descriptors, out.probe.descriptors, match,
                     out.reference.site_points.empty() ? nullptr : &out.reference.site_points,
                     out.probe.site_points.empty() ? nullptr : &out.probe.site_points);
  out.reference.unit = unit;
  out.probe.unit = unit;
  if (out.unit != 1.0) {
    unscale(out.reference, out.unit);
    unscale(out.probe, out.unit);
    unscale(out.result, out.unit);
  }
  if (out.lining && !out.result.alignments.empty()) {
    out.site_score = site_score(out.result.alignments.front().overlay.score, *out.lining,
                                match.site.lining_weight);
  }
  if (out.lining) {
    // The sites' interaction points: their compositions, and their agreement under the top
    // alignment (its coverage scores a ligand's site inside a larger pocket).
    const auto ref_points = interaction_points(out.reference.descriptors.surface,
                                               *out.reference.molecule, out.reference.site);
    const auto probe_points =
        interaction_points(out.probe.descriptors.surface, *out.probe.molecule, out.probe.site);
    // The null is that of the default site score: other site settings have none.
    const SiteMatchOptions defaults;
    const bool default_site = match.site.lining_weight == defaults.lining_weight &&
                              match.site.chem_weight == defaults.chem_weight &&
                              match.site.overlay_radius == defaults.overlay_radius &&
                              match.site.principal_axes_starts == defaults.principal_axes_starts;
    if (out.site_score && !ref_points.empty() && !probe_points.empty() && default_site)
      out.site_z = site_z_score(*out.site_score, ref_points.size(), probe_points.size());
    const auto ref_interactions = interaction_composition(ref_points);
    const auto probe_interactions = interaction_composition(probe_points);
    if (ref_interactions && probe_interactions) {
      out.interactions = interaction_similarity(*ref_interactions, *probe_interactions);
      if (!out.result.alignments.empty()) {
        out.fields =
            aligned_interactions(ref_points, probe_points, out.result.alignments.front().transform);
      }
    }
  }
  out.match_ms = clock.elapsed_ms() - out.prepare_ms;
  tell_clique_stop(out.result, match, out);
  log(options, "match: " + std::to_string(out.result.alignments.size()) + " alignments from " +
                   std::to_string(out.result.cliques) + " cliques (" + milliseconds(out.match_ms) +
                   ")");
  return out;
}

}  // namespace surfcomp::matching
