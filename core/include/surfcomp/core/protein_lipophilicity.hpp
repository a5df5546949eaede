// Lipophilicity increments for the atoms of standard amino-acid residues.
#pragma once

#include <optional>
#include <string_view>

namespace surfcomp {

/// Wildman-Crippen logP increment of atom `atom_name` (PDB name, blanks ignored) in residue
/// `residue` (ALA ... VAL, HIS/HIE/HID/HIP, CYX; "OXT" in any of them), as a united atom: the
/// heavy atom's type contribution plus those of its bonded hydrogens, each atom typed by hand
/// from S. A. Wildman, G. M. Crippen, J. Chem. Inf. Comput. Sci. 39, 868 (1999), Table 1.
/// Hydrogens (names starting with H, or a digit then H) return 0: their share is on the heavy
/// atom, so a residue's sum does not depend on whether the file lists hydrogens.
/// Protonation states are those at pH 7: ASP/GLU carboxylates, LYS NZ+, ARG guanidinium;
/// HIS = HIE (H on NE2), HIP doubly protonated. Atoms equivalent by resonance (ASP OD1/OD2,
/// GLU OE1/OE2, ARG NH1/NH2, HIP ND1/NE2) get the mean of their two Lewis-structure values.
/// Backbone atoms use the in-chain peptide values (terminal N as an amide NH); OXT is a
/// carboxylate O-. Returns nullopt for an unknown residue or atom name.
std::optional<double> protein_atom_lipophilicity(std::string_view residue,
                                                 std::string_view atom_name);

}  // namespace surfcomp
