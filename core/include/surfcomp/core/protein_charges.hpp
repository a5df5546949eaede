// Partial charges for protein atoms read from PDB files, which carry neither charges nor bond
// orders: the formal charges of the ionisable groups at pH 7, shared over their resonance
// atoms. For force-field charges, give a PQR file (e.g. from Debian's pdb2pqr --ff=AMBER).
#pragma once

#include "surfcomp/core/molecule.hpp"

#include <optional>
#include <string_view>

namespace surfcomp {

/// Formal charge (e) of atom `atom_name` of standard residue `residue` at pH 7, shared over the
/// atoms among which resonance spreads it: ASP OD1/OD2 and GLU OE1/OE2 -1/2 each, LYS NZ +1,
/// ARG NE/NH1/NH2 +1/3 each, HIP ND1/NE2 +1/2 each, OXT (C-terminal carboxylate, shared with
/// the residue's O) -1/2; every other atom of a standard residue 0 (HIS = HIE is neutral).
/// Returns nullopt for a residue that is not standard.
std::optional<double> protein_atom_formal_charge(std::string_view residue,
                                                 std::string_view atom_name);

/// The usual ionic charge of a free metal or halide ion (Na+, Ca2+, Zn2+, Cl-, ...), nullopt for
/// other elements.
std::optional<int> usual_ionic_charge(std::string_view element);

/// Sets the charge of every atom of a protein structure: protein_atom_formal_charge for standard
/// residues, +1 on the N of the first standard residue of each chain (the N-terminal amine),
/// -1/2 on the O of a residue that has an OXT, usual_ionic_charge for ions, 0 for every other
/// atom (hetero residues, water). Sets charge_source = ChargeSource::residue_table.
void assign_protein_formal_charges(Molecule& molecule);

}  // namespace surfcomp
