#include "surfcomp/core/elements.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <string>
#include <utility>

namespace surfcomp {
namespace {

struct ElementRadius {
  const char* symbol;
  double radius;
};

// Bondi 1964 (first block), Mantina 2009 main-group completion (second), 2.00 A for the
// transition metals and lanthanides neither paper gives (third).
constexpr std::array kRadii{
    ElementRadius{"H", 1.20},  ElementRadius{"He", 1.40}, ElementRadius{"C", 1.70},
    ElementRadius{"N", 1.55},  ElementRadius{"O", 1.52},  ElementRadius{"F", 1.47},
    ElementRadius{"Ne", 1.54}, ElementRadius{"Si", 2.10}, ElementRadius{"P", 1.80},
    ElementRadius{"S", 1.80},  ElementRadius{"Cl", 1.75}, ElementRadius{"Ar", 1.88},
    ElementRadius{"As", 1.85}, ElementRadius{"Se", 1.90}, ElementRadius{"Br", 1.85},
    ElementRadius{"Kr", 2.02}, ElementRadius{"Te", 2.06}, ElementRadius{"I", 1.98},
    ElementRadius{"Xe", 2.16}, ElementRadius{"Li", 1.82}, ElementRadius{"Na", 2.27},
    ElementRadius{"Mg", 1.73}, ElementRadius{"K", 2.75},  ElementRadius{"Ni", 1.63},
    ElementRadius{"Cu", 1.40}, ElementRadius{"Zn", 1.39}, ElementRadius{"Ga", 1.87},
    ElementRadius{"Pd", 1.63}, ElementRadius{"Ag", 1.72}, ElementRadius{"Cd", 1.58},
    ElementRadius{"In", 1.93}, ElementRadius{"Sn", 2.17}, ElementRadius{"Pt", 1.72},
    ElementRadius{"Au", 1.66}, ElementRadius{"Hg", 1.55}, ElementRadius{"Tl", 1.96},
    ElementRadius{"Pb", 2.02}, ElementRadius{"U", 1.86},  ElementRadius{"B", 1.92},
    ElementRadius{"Be", 1.53}, ElementRadius{"Al", 1.84}, ElementRadius{"Ca", 2.31},
    ElementRadius{"Ge", 2.11}, ElementRadius{"Rb", 3.03}, ElementRadius{"Sr", 2.49},
    ElementRadius{"Sb", 2.06}, ElementRadius{"Cs", 3.43}, ElementRadius{"Ba", 2.68},
    ElementRadius{"Bi", 2.07}, ElementRadius{"Po", 1.97}, ElementRadius{"At", 2.02},
    ElementRadius{"Rn", 2.20}, ElementRadius{"Fr", 3.48}, ElementRadius{"Ra", 2.83},
    ElementRadius{"Sc", 2.00}, ElementRadius{"Ti", 2.00}, ElementRadius{"V", 2.00},
    ElementRadius{"Cr", 2.00}, ElementRadius{"Mn", 2.00}, ElementRadius{"Fe", 2.00},
    ElementRadius{"Co", 2.00}, ElementRadius{"Mo", 2.00}, ElementRadius{"W", 2.00},
    ElementRadius{"Ru", 2.00}, ElementRadius{"Rh", 2.00}, ElementRadius{"Os", 2.00},
    ElementRadius{"Ir", 2.00}, ElementRadius{"Gd", 2.00}, ElementRadius{"Yb", 2.00},
};

}  // namespace

bool is_metal(std::string_view element) {
  static constexpr std::array<std::string_view, 22> others{
      "H",  "He", "B",  "C",  "N",  "O",  "F",  "Ne", "Si", "P",  "S",
      "Cl", "Ar", "As", "Se", "Br", "Kr", "Te", "I",  "Xe", "At", "Rn"};
  const std::string symbol = normalize_element(element);
  return !symbol.empty() && symbol != "*" &&
         std::find(others.begin(), others.end(), symbol) == others.end();
}

std::string normalize_element(std::string_view symbol) {
  std::string out;
  for (char c : symbol) {
    if (std::isspace(static_cast<unsigned char>(c))) continue;
    out.push_back(static_cast<char>(out.empty() ? std::toupper(static_cast<unsigned char>(c))
                                                : std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

std::optional<double> bondi_radius(std::string_view element) {
  const std::string symbol = normalize_element(element);
  for (const auto& entry : kRadii) {
    if (symbol == entry.symbol) return entry.radius;
  }
  return std::nullopt;
}

}  // namespace surfcomp
