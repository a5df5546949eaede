// SDF/MOL, MOL2 and PDB reading through RDKit; charges and Wildman-Crippen increments. Part of
// the RDKit module (rdkit_module.hpp); surfcomp::core reaches these through its entry points.
#include "molecule_reader_detail.hpp"
#include "molecule_text.hpp"
#include "rdkit_module.hpp"
#include "surfcomp/core/elements.hpp"
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/input_file.hpp"
#include "surfcomp/core/io/molecule_formats.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/write_molecule.hpp"
#include "surfcomp/core/molecule.hpp"
#include "surfcomp/core/option_names.hpp"
#include "surfcomp/core/protein_charges.hpp"

#include <GraphMol/Descriptors/Crippen.h>
#include <GraphMol/FileParsers/FileParsers.h>
#include <GraphMol/ForceFieldHelpers/MMFF/AtomTyper.h>
#include <GraphMol/GraphMol.h>
#include <GraphMol/MolOps.h>
#include <GraphMol/MonomerInfo.h>
#include <GraphMol/PartialCharges/GasteigerCharges.h>
#include <GraphMol/SmilesParse/SmilesParse.h>
#include <GraphMol/Substruct/SubstructMatch.h>
#include <RDGeneral/RDLog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace surfcomp::io::detail {
namespace {

std::string one_line(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      if (!out.empty() && out.back() != ' ') out.push_back(' ');
    } else {
      out.push_back(c);
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

// RDKit's message for a file it refused, in a chemist's words where it is one of the common
// ones (atom numbers from 1, as in the file); any other keeps RDKit's text after "RDKit: ".
std::string in_chemists_words(const std::string& message) {
  std::smatch m;
  const auto atoms_from_one = [](const std::string& indices) {
    std::istringstream in(indices);
    std::string out;
    for (int index = 0; in >> index;) out += (out.empty() ? "" : " ") + std::to_string(index + 1);
    return out;
  };
  if (std::regex_search(message, m, std::regex(R"(Counts line too short: .* on line ?(\d+))")))
    return "line " + m[1].str() + ": the counts line (atom and bond counts) is missing or short";
  if (std::regex_search(message, m, std::regex(R"(Element '([^']*)' not found)")))
    return "'" + m[1].str() + "' is not an element symbol";
  if (message.find("self-bond") != std::string::npos) return "a bond joins an atom to itself";
  if (message.find("AtomIdx()") != std::string::npos)
    return "a bond names an atom number beyond the molecule's atom count";
  if (std::regex_search(message, m,
                        std::regex(R"(valence for atom # (\d+) (\w+), (\d+), is greater)"))) {
    return "atom " + atoms_from_one(m[1].str()) + " (" + m[2].str() + ") has valence " +
           m[3].str() + ", more than " + m[2].str() + " allows (a missing charge?)";
  }
  if (std::regex_search(message, m, std::regex(R"(Unkekulized atoms:([\d ]+))"))) {
    return "the aromatic atoms " + atoms_from_one(m[1].str()) +
           " admit no alternating single and double bonds (a missing hydrogen on an aromatic "
           "N?)";
  }
  return "RDKit: " + message;
}

// Runs an RDKit call, turning any exception it throws into a FormatError naming `source`.
template <typename Call>
auto rdkit_call(const std::string& source, const std::string& what, Call&& call) {
  try {
    return call();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw FormatError(source, "cannot " + what + ": " + in_chemists_words(one_line(e.what())));
  } catch (...) {
    throw FormatError(source, "cannot " + what + " (RDKit failed without a reason)");
  }
}

std::unique_ptr<RDKit::RWMol> parse(const std::string& text, RdkitFormat format,
                                    const std::string& source) {
  return rdkit_call(source, "parse the file", [&]() {
    switch (format) {
      case RdkitFormat::mdl:
        return std::unique_ptr<RDKit::RWMol>(RDKit::MolBlockToMol(text, false, false));
      case RdkitFormat::mol2:
        return std::unique_ptr<RDKit::RWMol>(RDKit::Mol2BlockToMol(text, false, false));
      case RdkitFormat::pdb:
        break;
    }
    return std::unique_ptr<RDKit::RWMol>(
        RDKit::PDBBlockToMol(first_alternate_locations(text), false, false, 0, true));
  });
}

// RDKit's Mol2 reader gives an N.ar with three neighbours a +1 charge (pyridinium-like); in a
// five-membered ring that is a pyrrole-type NH and must be neutral, or kekulisation fails
// (tryptophan's indole in thermolysin ligands). Returns whether any atom was changed.
bool neutralize_pyrrole_nitrogens(RDKit::RWMol& mol) {
  RDKit::MolOps::fastFindRings(mol);
  bool changed = false;
  for (RDKit::Atom* atom : mol.atoms()) {
    if (atom->getAtomicNum() == 7 && atom->getIsAromatic() && atom->getFormalCharge() == 1 &&
        atom->getDegree() == 3 && mol.getRingInfo()->isAtomInRingOfSize(atom->getIdx(), 5)) {
      atom->setFormalCharge(0);
      changed = true;
    }
  }
  return changed;
}

void sanitize(std::unique_ptr<RDKit::RWMol>& mol, RdkitFormat format, const std::string& source) {
  const RDKit::RWMol original(*mol);
  try {
    RDKit::MolOps::sanitizeMol(*mol);
    return;
  } catch (const std::exception& e) {
    const std::string reason = one_line(e.what());
    if (format == RdkitFormat::mol2) {
      auto repaired = std::make_unique<RDKit::RWMol>(original);
      try {
        if (neutralize_pyrrole_nitrogens(*repaired)) {
          RDKit::MolOps::sanitizeMol(*repaired);
          mol = std::move(repaired);
          return;
        }
      } catch (const std::exception&) {
        // fall through to the original reason
      }
    }
    throw FormatError(source, "not a valid molecule: " + in_chemists_words(reason));
  }
}

Molecule convert_atoms(const RDKit::ROMol& mol, const std::string& source) {
  Molecule molecule;
  molecule.source = source;
  if (mol.getNumConformers() == 0) throw FormatError(source, "the molecule has no coordinates");
  const RDKit::Conformer& conformer = mol.getConformer();
  molecule.atoms.reserve(mol.getNumAtoms());
  for (const RDKit::Atom* rd_atom : mol.atoms()) {
    Atom atom;
    const RDGeom::Point3D& p = conformer.getAtomPos(rd_atom->getIdx());
    atom.position = Eigen::Vector3d(p.x, p.y, p.z);
    atom.element = rd_atom->getAtomicNum() > 0 ? rd_atom->getSymbol() : "";
    atom.formal_charge = rd_atom->getFormalCharge();
    if (const auto* info =
            dynamic_cast<const RDKit::AtomPDBResidueInfo*>(rd_atom->getMonomerInfo())) {
      atom.name = trimmed(info->getName());
      atom.residue_name = trimmed(info->getResidueName());
      atom.residue_number = info->getResidueNumber();
      atom.chain = trimmed(info->getChainId());
      atom.hetero = info->getIsHeteroAtom();
    } else if (const auto* monomer = rd_atom->getMonomerInfo()) {
      atom.name = trimmed(monomer->getName());
    }
    molecule.atoms.push_back(atom);
    if (atom.element.empty()) {
      throw InputError(source + ": " + describe_atom(molecule, molecule.atoms.size() - 1) +
                       " has an unknown element");
    }
  }
  return molecule;
}

// Keeps only the atoms whose indices are in `keep` (sorted), in both representations. The
// molecule is rebuilt from the kept atoms, the bonds between them, the conformers' kept
// positions and its own properties (the title): RDKit removes atoms one at a time in time
// proportional to the molecule each.
void keep_atoms(std::unique_ptr<RDKit::RWMol>& mol, Molecule& molecule,
                const std::vector<std::size_t>& keep) {
  auto kept = std::make_unique<RDKit::RWMol>();
  std::vector<int> index(mol->getNumAtoms(), -1);
  for (const std::size_t i : keep) {
    index[i] = static_cast<int>(
        kept->addAtom(new RDKit::Atom(*mol->getAtomWithIdx(static_cast<unsigned int>(i))),
                      /*updateLabel=*/false, /*takeOwnership=*/true));
  }
  for (const RDKit::Bond* bond : mol->bonds()) {
    const int a = index[bond->getBeginAtomIdx()], b = index[bond->getEndAtomIdx()];
    if (a < 0 || b < 0) continue;
    auto copy = std::make_unique<RDKit::Bond>(*bond);
    copy->setOwningMol(kept.get());
    copy->setBeginAtomIdx(static_cast<unsigned int>(a));
    copy->setEndAtomIdx(static_cast<unsigned int>(b));
    kept->addBond(copy.release(), /*takeOwnership=*/true);
  }
  for (auto conformer = mol->beginConformers(); conformer != mol->endConformers(); ++conformer) {
    auto* copy = new RDKit::Conformer(static_cast<unsigned int>(keep.size()));
    copy->setId((*conformer)->getId());
    copy->set3D((*conformer)->is3D());
    for (std::size_t k = 0; k < keep.size(); ++k)
      copy->setAtomPos(static_cast<unsigned int>(k),
                       (*conformer)->getAtomPos(static_cast<unsigned int>(keep[k])));
    kept->addConformer(copy, /*assignId=*/false);
  }
  kept->updateProps(*mol);
  mol = std::move(kept);
  std::vector<Atom> atoms;
  atoms.reserve(keep.size());
  for (const std::size_t i : keep) atoms.push_back(molecule.atoms[i]);
  molecule.atoms = std::move(atoms);
}

// PDB files do not encode metal coordination, and RDKit's proximity rule bonds an ion to the
// atoms around it (Ca and Zn to Asp/Glu/His in thermolysin). Those bonds are dropped: metals
// are treated as free ions.
void disconnect_metals(RDKit::RWMol& mol) {
  std::vector<std::pair<unsigned int, unsigned int>> metal_bonds;
  for (const RDKit::Bond* bond : mol.bonds()) {
    if (is_metal(bond->getBeginAtom()->getSymbol()) || is_metal(bond->getEndAtom()->getSymbol())) {
      metal_bonds.emplace_back(bond->getBeginAtomIdx(), bond->getEndAtomIdx());
    }
  }
  for (const auto& [begin, end] : metal_bonds) mol.removeBond(begin, end);
}

// Gasteiger charges per connected fragment (Gasteiger equalisation never crosses fragments),
// implicit hydrogens' charges added to their heavy atom; isolated ions see usual_ionic_charge.
std::vector<double> gasteiger_charges(const RDKit::ROMol& mol, const Molecule& molecule) {
  std::vector<std::vector<int>> mapping;
  const auto fragments = rdkit_call(molecule.source, "split the molecule", [&]() {
    return RDKit::MolOps::getMolFrags(mol, false, nullptr, &mapping, false);
  });
  std::vector<double> charges(mol.getNumAtoms(), 0.0);
  for (std::size_t f = 0; f < fragments.size(); ++f) {
    RDKit::ROMol& fragment = *fragments[f];
    try {
      RDKit::computeGasteigerCharges(fragment, 12, true);
    } catch (const std::exception& e) {
      const std::size_t first = static_cast<std::size_t>(mapping[f].front());
      const auto ionic = usual_ionic_charge(molecule.atoms[first].element);
      const int formal = mol.getAtomWithIdx(static_cast<unsigned int>(first))->getFormalCharge();
      if (fragment.getNumAtoms() == 1 && (formal != 0 || ionic)) {
        charges[first] = formal != 0 ? formal : *ionic;
        continue;
      }
      throw InputError(molecule.source + ": Gasteiger charges unavailable for the fragment of " +
                       describe_atom(molecule, first) + " (RDKit: " + one_line(e.what()) +
                       "); use MMFF94 charges (" + options::named("charges") +
                       " mmff) or a PQR file");
    }
    for (const RDKit::Atom* atom : fragment.atoms()) {
      const std::size_t index = static_cast<std::size_t>(mapping[f][atom->getIdx()]);
      double charge = atom->getProp<double>(RDKit::common_properties::_GasteigerCharge);
      if (atom->hasProp(RDKit::common_properties::_GasteigerHCharge)) {
        charge += atom->getProp<double>(RDKit::common_properties::_GasteigerHCharge);
      }
      if (!std::isfinite(charge)) {
        throw InputError(molecule.source + ": the Gasteiger charge of " +
                         describe_atom(molecule, index) + " is not a number");
      }
      charges[index] = charge;
    }
  }
  return charges;
}

// A copy of `mol` with all hydrogens explicit; atoms [0, mol.getNumAtoms()) keep their index.
std::unique_ptr<RDKit::RWMol> with_explicit_hydrogens(const RDKit::ROMol& mol) {
  auto copy = std::make_unique<RDKit::RWMol>(mol);
  RDKit::MolOps::addHs(*copy);
  return copy;
}

// Folds per-atom values of added hydrogens (indices >= n) onto their heavy neighbour.
std::vector<double> fold_added_hydrogens(const RDKit::ROMol& with_h, std::size_t n,
                                         const std::vector<double>& values) {
  std::vector<double> folded(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t i = n; i < with_h.getNumAtoms(); ++i) {
    const RDKit::Atom* hydrogen = with_h.getAtomWithIdx(static_cast<unsigned int>(i));
    for (const RDKit::Bond* bond : with_h.atomBonds(hydrogen)) {
      folded[bond->getOtherAtomIdx(hydrogen->getIdx())] += values[i];
    }
  }
  return folded;
}

std::vector<double> mmff_charges(const RDKit::ROMol& mol, const std::string& source) {
  const auto with_h = with_explicit_hydrogens(mol);
  RDKit::MMFF::MMFFMolProperties properties(*with_h);
  if (!properties.isValid()) {
    throw InputError(source +
                     ": MMFF94 atom typing failed (RDKit found an atom without an "
                     "MMFF94 type); use Gasteiger charges (" +
                     options::named("charges") + " gasteiger)");
  }
  std::vector<double> charges(with_h->getNumAtoms());
  for (unsigned int i = 0; i < with_h->getNumAtoms(); ++i) {
    charges[i] = properties.getMMFFPartialCharge(i);
  }
  return fold_added_hydrogens(*with_h, mol.getNumAtoms(), charges);
}

std::vector<double> crippen_contributions(const RDKit::ROMol& mol, const std::string& source) {
  return rdkit_call(source, "compute Wildman-Crippen contributions", [&]() {
    const auto with_h = with_explicit_hydrogens(mol);
    std::vector<double> logp(with_h->getNumAtoms()), mr(with_h->getNumAtoms());
    RDKit::Descriptors::getCrippenAtomContribs(*with_h, logp, mr, true);
    return fold_added_hydrogens(*with_h, mol.getNumAtoms(), logp);
  });
}

std::vector<double> tripos_charges(const RDKit::ROMol& mol, const std::string& source) {
  std::vector<double> charges;
  for (const RDKit::Atom* atom : mol.atoms()) {
    double charge = 0.0;
    bool present = false;
    try {
      present = atom->getPropIfPresent("_TriposPartialCharge", charge);
    } catch (const std::exception&) {  // RDKit keeps an unparsable charge field as text
      throw FormatError(source, "the partial charge of atom " + std::to_string(atom->getIdx() + 1) +
                                    " is not a number");
    }
    if (!present) {
      throw FormatError(source, "atom " + std::to_string(atom->getIdx() + 1) +
                                    " has no partial charge although the header declares some");
    }
    charges.push_back(charge);
  }
  return charges;
}

// Acid and base groups that a file may draw neutral but that are ionised at pH 7, as SMARTS
// whose first atom is the one that takes the charge: carboxylic, phosphonic or phosphoric, and
// sulfonic or sulfuric acids; 1H- and 2H-tetrazoles; aliphatic amines (not on an aromatic
// ring, a carbonyl, thiocarbonyl, imine, vinyl, sulfonyl or nitrile carbon, nor on N, O or S);
// amidines and guanidines outside aromatic rings, not on an aromatic ring's atom nor acylated
// or sulfonylated.
constexpr std::array<const char*, 7> ionisable_group_smarts = {
    "[OX2H1]-[CX3]=O",
    "[OX2H1]-[PX4]=O",
    "[OX2H1]-[SX4](=O)=O",
    "[#7H1]1:[#6]:[#7]:[#7]:[#7]:1",
    "[#7H1]1:[#7]:[#6]:[#7]:[#7]:1",
    "[NX3;!$(N-a);!$(N-[#6,#15,#16]=[#6,#7,#8,#16]);!$(N-[#7,#8,#16]);!$(N-C#N)]-[#6]",
    "[NX2;!a;!$(N-a);!$(N-[#7,#8]);!$(N-C=O);!$(N-S(=O)=O)]=[CX3;!a]-[NX3;!$(N-a);!$(N-C=O);"
    "!$(N-S(=O)=O)]",
};

// Molecule::ionisable_atoms of a sanitised molecule. The patterns are parsed per thread: a
// recursive SMARTS query is not shared between threads.
std::vector<std::size_t> ionisable_atoms(const RDKit::ROMol& mol) {
  thread_local const std::vector<std::unique_ptr<RDKit::RWMol>> patterns = [] {
    std::vector<std::unique_ptr<RDKit::RWMol>> parsed;
    parsed.reserve(ionisable_group_smarts.size());
    for (const char* smarts : ionisable_group_smarts)
      parsed.emplace_back(RDKit::SmartsToMol(smarts));
    return parsed;
  }();
  std::set<std::size_t> atoms;
  for (const std::unique_ptr<RDKit::RWMol>& pattern : patterns) {
    for (const RDKit::MatchVectType& match : RDKit::SubstructMatch(mol, *pattern)) {
      for (const auto& [query_atom, atom] : match) {
        if (query_atom == 0) atoms.insert(static_cast<std::size_t>(atom));
      }
    }
  }
  return {atoms.begin(), atoms.end()};
}

Molecule read_unguarded(const std::filesystem::path& path, const std::string& whole_text,
                        RdkitFormat format, const MoleculeReadOptions& options) {
  const std::string source = path.string();
  if (trimmed(whole_text).empty()) throw InputError(source + ": the file is empty (no atoms)");
  if (format != RdkitFormat::pdb && !options.ligand.empty()) {
    throw OptionError(source + ": " + options::named("ligand") + " " + options.ligand +
                      " selects a HETATM residue of a PDB or PQR file; an SDF, MOL or MOL2 "
                      "file is the ligand itself (give no " +
                      options::named("ligand") + ")");
  }
  if (format == RdkitFormat::pdb) {
    check_single_record(options.record, source);
    check_pdb_coordinates(whole_text, source);
  }
  if (format != RdkitFormat::pdb && options.min_plddt > 0.0) {
    throw OptionError(source + ": " + options::named("min_plddt") +
                      " reads the B-factor column of a PDB or mmCIF structure; an "
                      "SDF, MOL or MOL2 file has none");
  }
  const std::string text =
      format != RdkitFormat::pdb ? select_record(whole_text, format, options.record, source)
      : options.min_plddt > 0.0  ? drop_low_plddt_residues(whole_text, options.min_plddt, source)
                                 : whole_text;
  if (format == RdkitFormat::mol2) check_mol2_structure(text, source);
  auto mol = parse(text, format, source);
  if (!mol) throw FormatError(source, "cannot parse the file: it holds no molecule");
  if (mol->getNumAtoms() == 0) throw InputError(source + ": the file has no atoms");
  Molecule molecule = convert_atoms(*mol, source);
  check_read_atoms(molecule);

  bool whole_structure = false;
  if (format == RdkitFormat::pdb) {
    std::vector<std::size_t> keep;
    if (!options.ligand.empty()) {
      keep = select_ligand(molecule, parse_ligand_selector(options.ligand));
    } else {
      whole_structure = true;
      for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
        if (!is_dropped_residue(molecule.atoms[i].residue_name, options)) {
          keep.push_back(i);
        }
      }
      if (keep.empty()) throw InputError(source + ": the structure has no atoms besides water");
    }
    if (keep.size() != molecule.atoms.size()) {
      rdkit_call(source, "select atoms", [&]() { keep_atoms(mol, molecule, keep); });
    }
  }
  if (format == RdkitFormat::pdb) {
    rdkit_call(source, "disconnect metal ions", [&]() { disconnect_metals(*mol); });
  }
  // A protein from a PDB file has no bond orders, and RDKit's proximity bonds over explicit
  // hydrogens break valences: its charges and lipophilicities come from residue tables, so it
  // is not sanitised.
  const bool protein = whole_structure && has_standard_residue(molecule.atoms);
  if (protein && options.charges != ChargeModel::file) {
    throw OptionError(source +
                      ": Gasteiger and MMFF charges need bond orders, which a protein "
                      "PDB file lacks; use the residue charges (charges 'file') or a PQR file");
  }
  if (!protein) sanitize(mol, format, source);
  // A PDB file has no bond orders: its amides and anilines would read as amines.
  if (format != RdkitFormat::pdb) {
    molecule.ionisable_atoms =
        rdkit_call(source, "find ionisable groups", [&]() { return ionisable_atoms(*mol); });
  }

  std::string name;
  if (mol->getPropIfPresent(RDKit::common_properties::_Name, name) && !trimmed(name).empty()) {
    molecule.title = trimmed(name);
  } else {
    molecule.title = structure_stem(path);
  }

  const std::string charge_type = format == RdkitFormat::mol2 ? mol2_charge_type(text) : "";
  const bool file_charges =
      options.charges == ChargeModel::file && !charge_type.empty() && charge_type != "NO_CHARGES";
  std::vector<double> charges;
  if (protein) {
    assign_protein_formal_charges(molecule);
    for (const Atom& atom : molecule.atoms) charges.push_back(atom.charge);
  } else if (file_charges) {
    charges = tripos_charges(*mol, source);
    molecule.charge_source = ChargeSource::file;
  } else if (options.charges == ChargeModel::mmff) {
    charges =
        rdkit_call(source, "compute MMFF94 charges", [&]() { return mmff_charges(*mol, source); });
    molecule.charge_source = ChargeSource::mmff;
  } else {
    charges = gasteiger_charges(*mol, molecule);
    molecule.charge_source = ChargeSource::gasteiger;
  }
  for (std::size_t i = 0; i < molecule.atoms.size(); ++i) molecule.atoms[i].charge = charges[i];

  if (options.assign_lipophilicity) {
    if (protein) {
      assign_protein_lipophilicity(molecule);
    } else {
      const std::vector<double> contributions = crippen_contributions(*mol, source);
      for (std::size_t i = 0; i < molecule.atoms.size(); ++i) {
        molecule.atoms[i].lipophilicity = contributions[i];
      }
      molecule.lipophilicity_assigned = true;
    }
  }
  assign_bondi_radii(molecule);
  validate_molecule(molecule);
  return molecule;
}

}  // namespace

Molecule rdkit_read_molecule(const std::filesystem::path& path, const std::string& text,
                             RdkitFormat format, const MoleculeReadOptions& options) {
  const RDLog::LogStateSetter quiet;  // RDKit's warnings would go to stderr
  // Every RDKit call that can fail on bad input is wrapped where it is made; this catches what
  // RDKit throws from less expected places (property casts, invariant checks) on damaged files.
  return rdkit_call(path.string(), "read the file",
                    [&]() { return read_unguarded(path, text, format, options); });
}

std::vector<double> rdkit_crippen_of_pdb_block(const std::string& pdb_block,
                                               const std::string& source) {
  const RDLog::LogStateSetter quiet;
  auto mol = parse(pdb_block, RdkitFormat::pdb, source);
  if (!mol || mol->getNumAtoms() == 0) {
    throw FormatError(source, "RDKit could not read the ligand");
  }
  rdkit_call(source, "disconnect metal ions", [&]() { disconnect_metals(*mol); });
  sanitize(mol, RdkitFormat::pdb, source);
  return crippen_contributions(*mol, source);
}

}  // namespace surfcomp::io::detail

namespace surfcomp::io {

namespace {

std::string moved_block(const std::string& text, detail::RdkitFormat format,
                        const std::string& source, const Eigen::Matrix3d& rotation,
                        const Eigen::Vector3d& translation) {
  const RDLog::LogStateSetter quiet;
  if (format == detail::RdkitFormat::mol2) detail::check_mol2_structure(text, source);
  auto mol = detail::parse(text, format, source);
  if (!mol || mol->getNumConformers() == 0)
    throw FormatError(source, "RDKit could not read the molecule");
  RDKit::Conformer& conformer = mol->getConformer();
  for (unsigned i = 0; i < mol->getNumAtoms(); ++i) {
    const RDGeom::Point3D& p = conformer.getAtomPos(i);
    const Eigen::Vector3d moved = rotation * Eigen::Vector3d(p.x, p.y, p.z) + translation;
    conformer.setAtomPos(i, RDGeom::Point3D(moved.x(), moved.y(), moved.z()));
  }
  return detail::rdkit_call(source, "write the molecule",
                            [&]() { return RDKit::MolToMolBlock(*mol, true, -1, false); });
}

}  // namespace

std::string rdkit_moved_mol_block(const std::filesystem::path& input,
                                  const Eigen::Matrix3d& rotation,
                                  const Eigen::Vector3d& translation, std::size_t record) {
  const std::string source = input.string();
  const MoleculeFormat* found = find_molecule_format(input);
  if (found == nullptr ||
      (found->kind != MoleculeFileKind::mdl && found->kind != MoleculeFileKind::mol2)) {
    throw InputError(source +
                     ": a moved SDF copy needs an SDF, MOL or MOL2 input (write .pdb instead)");
  }
  const detail::RdkitFormat format =
      found->kind == MoleculeFileKind::mol2 ? detail::RdkitFormat::mol2 : detail::RdkitFormat::mdl;
  const std::string text = detail::select_record(read_input_file(input), format, record, source);
  return moved_block(text, format, source, rotation, translation) + "$$$$\n";
}

std::string rdkit_moved_record_block(const MoleculeRecord& record, const Eigen::Matrix3d& rotation,
                                     const Eigen::Vector3d& translation) {
  const std::string source = record.source.string();
  switch (record.format) {
    case RecordFormat::mdl:
      return moved_block(record.text, detail::RdkitFormat::mdl, source, rotation, translation);
    case RecordFormat::mol2:
      return moved_block(record.text, detail::RdkitFormat::mol2, source, rotation, translation);
    case RecordFormat::structure:
      if (!record.text.empty()) {
        return moved_block(record.text, detail::RdkitFormat::pdb, source, rotation, translation);
      }
      throw InputError(source + ": a PQR structure cannot be written as a mol block");
    case RecordFormat::descriptors:
      throw InputError(source + ": a .hsi file has no molecule to write as a mol block");
    case RecordFormat::mesh:
      throw InputError(source + ": a mesh has no molecule to write as a mol block");
    case RecordFormat::smiles:
      break;
  }
  throw InputError(source + ": record " + std::to_string(record.record) +
                   " is a SMILES string without coordinates");
}

}  // namespace surfcomp::io
