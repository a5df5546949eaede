#include "surfcomp/report/pocket_files.hpp"

#include "match_document.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace surfcomp::report {

std::string pockets_json(const PocketSet& set) {
  nlohmann::json list = nlohmann::json::array();
  for (const molsurf::Pocket& pocket : set.found.pockets) {
    nlohmann::json spheres = nlohmann::json::array();
    for (const molsurf::SiteSphere& s : pocket.spheres) {
      spheres.push_back({s.center.x(), s.center.y(), s.center.z(), s.radius});
    }
    nlohmann::json atoms = nlohmann::json::array();
    for (std::size_t atom : pocket.lining_atoms) atoms.push_back(atom + 1);
    list.push_back({{"rank", pocket.rank},
                    {"score", pocket.score},
                    {"volume", pocket.volume},
                    {"buriedness", pocket.buriedness},
                    {"cavity", pocket.cavity},
                    {"center", {pocket.center.x(), pocket.center.y(), pocket.center.z()}},
                    {"lining_residues", pocket.lining_residues},
                    {"lining_atoms", atoms},
                    {"spheres", spheres}});
  }
  const molsurf::PocketOptions& o = set.options;
  const nlohmann::json document = {
      {"input", set.input},
      {"models", set.found.models},
      {"protein_atoms", set.found.protein_atoms},
      {"parameters",
       {{"method", "alpha spheres (CGAL 3D Delaunay), buriedness, single linkage"},
        {"min_sphere_radius", o.min_sphere_radius},
        {"max_sphere_radius", o.max_sphere_radius},
        {"min_buriedness", o.min_buriedness},
        {"buried_distance", o.buried_distance},
        {"cluster_distance", o.cluster_distance},
        {"min_spheres", o.min_spheres},
        {"max_volume", o.max_volume}}},
      {"pockets", list}};
  return detail::json_text(document, 2) + "\n";
}

void write_pockets_pdb(const std::vector<molsurf::Pocket>& pockets, std::ostream& out) {
  std::size_t serial = 0;
  for (const molsurf::Pocket& pocket : pockets) {
    for (const molsurf::SiteSphere& s : pocket.spheres) {
      ++serial;
      char line[96];
      std::snprintf(
          line, sizeof line, "HETATM%5zu APOL STP P%4d    %8.3f%8.3f%8.3f  1.00%6.2f           C\n",
          serial % 100000, pocket.rank % 10000, s.center.x(), s.center.y(), s.center.z(), s.radius);
      out << line;
    }
  }
  out << "END\n";
}

}  // namespace surfcomp::report
