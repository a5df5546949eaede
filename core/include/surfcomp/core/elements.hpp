// Element data: Bondi van der Waals radii.
#pragma once

#include <optional>
#include <string_view>

namespace surfcomp {

/// Van der Waals radius in A for `element` (case-insensitive symbol): Bondi's value where he
/// gave one (H = 1.20), Mantina et al.'s consistent completion for the other main-group
/// elements, and 2.00 A for transition metals neither lists (Fe, Mn, Co, ...).
/// Returns nullopt for a symbol that is not an element.
/// Refs: A. Bondi, J. Phys. Chem. 68, 441 (1964); M. Mantina et al., J. Phys. Chem. A 113,
/// 5806 (2009).
std::optional<double> bondi_radius(std::string_view element);

/// Whether `element` (a symbol, any case) is a metal: any element but the non-metals and the
/// metalloids boron, silicon, arsenic and tellurium (H, He, B, C, N, O, F, Ne, Si, P, S, Cl,
/// Ar, As, Se, Br, Kr, Te, I, Xe, At, Rn). False for an empty symbol and a dummy atom ("*").
bool is_metal(std::string_view element);

/// Normalises an element symbol: trims blanks, first letter upper, rest lower ("CL" -> "Cl").
std::string normalize_element(std::string_view symbol);

}  // namespace surfcomp
