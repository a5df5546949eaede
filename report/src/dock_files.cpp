#include "surfcomp/report/dock_files.hpp"

#include "dock_pose_terms.hpp"
#include "surfcomp/core/io/molecule_records.hpp"
#include "surfcomp/core/io/write_molecule.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>
#include <utility>

namespace surfcomp::report {
namespace {

nlohmann::ordered_json matrix_json(const Eigen::Matrix4d& m) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (int r = 0; r < 4; ++r) rows.push_back({m(r, 0), m(r, 1), m(r, 2), m(r, 3)});
  return rows;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", x);
  return text;
}

}  // namespace

std::string dock_json(const docking::DockResult& docked, const docking::DockOptions& options) {
  nlohmann::ordered_json doc;
  doc["ligand"] = docked.ligand.name;
  doc["receptor"] = docked.receptor.name;
  nlohmann::ordered_json spheres = nlohmann::ordered_json::array();
  for (const molsurf::SiteSphere& s : docked.receptor.site)
    spheres.push_back({s.center.x(), s.center.y(), s.center.z(), s.radius});
  doc["site"] = {{"spheres", spheres},
                 {"free_volume", docked.site_volume},
                 {"ligand_volume", docked.ligand_volume}};
  nlohmann::ordered_json poses = nlohmann::ordered_json::array();
  for (const docking::DockPose& p : docked.poses) {
    nlohmann::ordered_json cp = nlohmann::ordered_json::array();
    for (const auto& [receptor, ligand] : p.cp_pairs) cp.push_back({receptor, ligand});
    nlohmann::ordered_json pose = {{"rank", p.rank}};
    pose.update(detail::dock_pose_terms<nlohmann::ordered_json>(p));
    pose["transform"] = matrix_json(p.transform);
    pose["start"] = p.start;
    pose["conformer"] = p.conformer;
    pose["cp_pairs"] = cp;
    poses.push_back(std::move(pose));
  }
  doc["poses"] = poses;
  doc["conformers"] = docked.conformers;  // the blocks a pose's conformer k (1-based) names
  doc["starts"] = docked.starts;
  nlohmann::ordered_json trace = nlohmann::ordered_json::array();
  for (const matching::TraceStage& stage : docked.trace)
    trace.push_back({{"stage", stage.stage}, {"nodes", stage.nodes}, {"edges", stage.edges}});
  doc["trace"] = trace;
  doc["notes"] = docked.notes;
  doc["parameters"] = detail::dock_parameters<nlohmann::ordered_json>(options);
  nlohmann::ordered_json timing;
  for (const auto& [step, ms] : docked.timing_ms) timing[step] = ms;
  doc["timing_ms"] = timing;
  return doc.dump(2) + "\n";
}

std::string dock_poses_sdf(const docking::DockResult& docked, const std::filesystem::path& ligand,
                           std::size_t record) {
  std::ostringstream out;
  for (const docking::DockPose& p : docked.poses) {
    const Eigen::Matrix3d rotation = p.transform.topLeftCorner<3, 3>();
    const Eigen::Vector3d translation = p.transform.topRightCorner<3, 1>();
    std::string block;
    if (p.conformer == 0) {
      block = io::moved_mol_block(ligand, rotation, translation, record);
    } else {  // a generated conformer: its own block, moved
      io::MoleculeRecord conformer;
      conformer.source = ligand;
      conformer.text = docked.conformers.at(static_cast<std::size_t>(p.conformer - 1));
      block = io::moved_record_block(conformer, rotation, translation);
    }
    const std::size_t end = block.rfind("$$$$");
    if (end != std::string::npos) block.erase(end);
    if (block.empty() || block.back() != '\n') block += '\n';
    out << block;
    if (p.conformer > 0) out << ">  <surfcomp_conformer>\n" << p.conformer << "\n\n";
    out << ">  <surfcomp_rank>\n"
        << p.rank << "\n\n"
        << ">  <surfcomp_score>\n"
        << number(p.score.score) << "\n\n"
        << ">  <surfcomp_contact>\n"
        << number(p.score.contact) << "\n\n"
        << ">  <surfcomp_clash>\n"
        << number(p.score.clash) << "\n\n$$$$\n";
  }
  return out.str();
}

}  // namespace surfcomp::report
