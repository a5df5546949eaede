#include "surfcomp/core/protein_lipophilicity.hpp"

#include <cctype>
#include <map>
#include <string>

namespace surfcomp {
namespace {

// Wildman-Crippen atom types used by the amino acids and their published logP contributions
// (J. Chem. Inf. Comput. Sci. 39, 868 (1999), Table 1; the same values RDKit ships).
double type_contribution(std::string_view type) {
  static const std::map<std::string_view, double> contributions{
      {"C1", 0.1441},   {"C2", 0.0000},  {"C3", -0.2035}, {"C4", -0.2051},  {"C5", -0.2783},
      {"C10", -0.0516}, {"C18", 0.1581}, {"C19", 0.2955}, {"C21", 0.1360},  {"C23", 0.5437},
      {"N1", -1.0190},  {"N2", -0.7096}, {"N7", -0.3187}, {"N10", -1.9500}, {"N11", -0.3239},
      {"N12", -1.1190}, {"O2", -0.2893}, {"O9", -0.1526}, {"O12", -1.3260}, {"S1", 0.6482},
      {"H1", 0.1230},   {"H2", -0.2677}, {"H3", 0.2142},
  };
  return contributions.at(type);
}

// A united atom: heavy-atom type plus `hydrogens` bonded hydrogens of type `hydrogen_type`.
double united(std::string_view heavy_type, int hydrogens = 0,
              std::string_view hydrogen_type = "H1") {
  return type_contribution(heavy_type) +
         (hydrogens > 0 ? hydrogens * type_contribution(hydrogen_type) : 0.0);
}

double mean(double a, double b) { return 0.5 * (a + b); }

using ResidueTable = std::map<std::string, std::map<std::string, double>>;

ResidueTable build_table() {
  // Types assigned by hand (and checked against RDKit's typing of a peptide in the tests).
  const double amide_n = united("N2", 1, "H3");
  const double alpha_c = united("C4", 1);
  const std::map<std::string, double> backbone{{"N", amide_n},
                                               {"CA", alpha_c},
                                               {"C", united("C5")},
                                               {"O", united("O9")},
                                               {"OXT", united("O12")}};
  const double aromatic_ch = united("C18", 1);
  const double carboxylate_o = mean(united("O9"), united("O12"));
  const double benzyl_cb = united("C10", 2);
  const std::map<std::string, double> phenyl{
      {"CB", benzyl_cb},    {"CG", united("C21")}, {"CD1", aromatic_ch}, {"CD2", aromatic_ch},
      {"CE1", aromatic_ch}, {"CE2", aromatic_ch},  {"CZ", aromatic_ch}};
  std::map<std::string, double> tyrosyl = phenyl;
  tyrosyl["CZ"] = united("C23");
  tyrosyl["OH"] = united("O2", 1, "H2");
  const std::map<std::string, std::map<std::string, double>> side_chains{
      {"ALA", {{"CB", united("C1", 3)}}},
      {"ARG",
       {{"CB", united("C1", 2)},
        {"CG", united("C1", 2)},
        {"CD", united("C3", 2)},
        {"NE", united("N2", 1, "H3")},
        {"CZ", united("C5")},
        {"NH1", mean(united("N10", 2, "H3"), united("N1", 2, "H3"))},
        {"NH2", mean(united("N10", 2, "H3"), united("N1", 2, "H3"))}}},
      {"ASN",
       {{"CB", united("C1", 2)},
        {"CG", united("C5")},
        {"OD1", united("O9")},
        {"ND2", united("N1", 2, "H3")}}},
      {"ASP",
       {{"CB", united("C1", 2)},
        {"CG", united("C5")},
        {"OD1", carboxylate_o},
        {"OD2", carboxylate_o}}},
      {"CYS", {{"CB", united("C3", 2)}, {"SG", united("S1", 1, "H2")}}},
      {"CYX", {{"CB", united("C3", 2)}, {"SG", united("S1")}}},
      {"GLN",
       {{"CB", united("C1", 2)},
        {"CG", united("C1", 2)},
        {"CD", united("C5")},
        {"OE1", united("O9")},
        {"NE2", united("N1", 2, "H3")}}},
      {"GLU",
       {{"CB", united("C1", 2)},
        {"CG", united("C1", 2)},
        {"CD", united("C5")},
        {"OE1", carboxylate_o},
        {"OE2", carboxylate_o}}},
      {"GLY", {{"CA", united("C3", 2)}}},
      {"HIE",
       {{"CB", benzyl_cb},
        {"CG", united("C21")},
        {"ND1", united("N11")},
        {"CD2", aromatic_ch},
        {"CE1", aromatic_ch},
        {"NE2", united("N11", 1, "H3")}}},
      {"HID",
       {{"CB", benzyl_cb},
        {"CG", united("C21")},
        {"ND1", united("N11", 1, "H3")},
        {"CD2", aromatic_ch},
        {"CE1", aromatic_ch},
        {"NE2", united("N11")}}},
      {"HIP",
       {{"CB", benzyl_cb},
        {"CG", united("C21")},
        {"ND1", mean(united("N12", 1, "H3"), united("N11", 1, "H3"))},
        {"CD2", aromatic_ch},
        {"CE1", aromatic_ch},
        {"NE2", mean(united("N12", 1, "H3"), united("N11", 1, "H3"))}}},
      {"ILE",
       {{"CB", united("C2", 1)},
        {"CG1", united("C1", 2)},
        {"CG2", united("C1", 3)},
        {"CD1", united("C1", 3)}}},
      {"LEU",
       {{"CB", united("C1", 2)},
        {"CG", united("C2", 1)},
        {"CD1", united("C1", 3)},
        {"CD2", united("C1", 3)}}},
      {"LYS",
       {{"CB", united("C1", 2)},
        {"CG", united("C1", 2)},
        {"CD", united("C1", 2)},
        {"CE", united("C3", 2)},
        {"NZ", united("N10", 3, "H3")}}},
      {"MET",
       {{"CB", united("C1", 2)},
        {"CG", united("C3", 2)},
        {"SD", united("S1")},
        {"CE", united("C3", 3)}}},
      {"PHE", phenyl},
      {"PRO",
       {{"N", united("N7")},
        {"CB", united("C1", 2)},
        {"CG", united("C1", 2)},
        {"CD", united("C3", 2)}}},
      {"SER", {{"CB", united("C3", 2)}, {"OG", united("O2", 1, "H2")}}},
      {"THR", {{"CB", united("C4", 1)}, {"OG1", united("O2", 1, "H2")}, {"CG2", united("C1", 3)}}},
      {"TRP",
       {{"CB", benzyl_cb},
        {"CG", united("C21")},
        {"CD1", aromatic_ch},
        {"CD2", united("C19")},
        {"NE1", united("N11", 1, "H3")},
        {"CE2", united("C19")},
        {"CE3", aromatic_ch},
        {"CZ2", aromatic_ch},
        {"CZ3", aromatic_ch},
        {"CH2", aromatic_ch}}},
      {"TYR", tyrosyl},
      {"VAL", {{"CB", united("C2", 1)}, {"CG1", united("C1", 3)}, {"CG2", united("C1", 3)}}},
  };
  ResidueTable table;
  for (const auto& [residue, atoms] : side_chains) {
    auto& entry = table[residue];
    entry = backbone;
    for (const auto& [name, value] : atoms) entry[name] = value;
  }
  table["HIS"] = table.at("HIE");
  return table;
}

std::string normalized(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (!std::isspace(static_cast<unsigned char>(c))) {
      out.push_back(static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
    }
  }
  return out;
}

bool is_hydrogen_name(const std::string& name) {
  std::size_t i = 0;
  while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i]))) ++i;
  return i < name.size() && name[i] == 'H';
}

}  // namespace

std::optional<double> protein_atom_lipophilicity(std::string_view residue,
                                                 std::string_view atom_name) {
  static const ResidueTable table = build_table();
  const auto found_residue = table.find(normalized(residue));
  if (found_residue == table.end()) return std::nullopt;
  const std::string name = normalized(atom_name);
  const auto found_atom = found_residue->second.find(name);
  if (found_atom != found_residue->second.end()) return found_atom->second;
  if (is_hydrogen_name(name)) return 0.0;
  return std::nullopt;
}

}  // namespace surfcomp
