// A dock's results as files (`surfcomp dock`): the poses as SDF records in the receptor's
// frame, a JSON document in the layout of a match's result, and the HTML report showing the
// ligand in the pocket (docs/usage.md#dock).
#pragma once

#include "surfcomp/docking/dock.hpp"
#include "surfcomp/report/html_report.hpp"

#include <cstddef>
#include <filesystem>
#include <string>

namespace surfcomp::report {

/// The result document of `docked` as JSON text indented by two spaces, ending with a newline:
/// the inputs, the poses (rank, transform, score and its terms, the clique alignment each was
/// refined from and its critical-point pairs, the conformer), the graph trace, the volumes, the
/// notes and the timings.
std::string dock_json(const docking::DockResult& docked, const docking::DockOptions& options);

/// Each pose of `docked` as an SDF record of the ligand file `ligand` (record `record` as
/// MoleculeReadOptions::record gives it) moved into the receptor's frame, with its rank and
/// score as SD data items (surfcomp_rank, surfcomp_score, surfcomp_contact, surfcomp_clash),
/// best first; a pose of a generated conformer (DockPose::conformer) is that conformer's record,
/// with surfcomp_conformer before them. Throws as io::moved_mol_block (the ligand must be an SDF,
/// MOL or MOL2 file).
std::string dock_poses_sdf(const docking::DockResult& docked, const std::filesystem::path& ligand,
                           std::size_t record = 0);

/// The HTML report of `docked` (the page of html_report, one self-contained file): the
/// receptor's site surface with its lining and its molecule, each pose's ligand (its own
/// conformer) placed in it as surface and sticks, the critical-point pairs of a clique pose,
/// a table of the poses with the score's terms (a click shows one), the graph trace, the
/// timings and the parameters. report.top limits the poses listed. Throws as html_report.
std::string dock_html_report(const docking::DockResult& docked, const docking::DockOptions& options,
                             const HtmlReportOptions& report = {});

/// dock_html_report written to `path` atomically (io::write_file_atomically).
void write_dock_html_report(const std::filesystem::path& path, const docking::DockResult& docked,
                            const docking::DockOptions& options,
                            const HtmlReportOptions& report = {});

}  // namespace surfcomp::report
