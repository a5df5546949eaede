// Binding-site comparison on the Kahraman dev set (issue 4, "Binding sites"): 36 sites of ATP,
// HEM and FMN (../shared/datasets/kahraman-dev). Each site is built once (molsurf::binding_site
// of the entry's ligand copy, its chains in contact): the surface of its structure without water
// and without the site's own ligand copy, described (patch, harmonic map, shape image) only at
// the critical points within kSiteRadius of that ligand's atoms (matching::describe_site). Every
// unordered pair of sites is then matched (REF = the earlier entry) and scored from its top-1
// alignment; the ROC AUC of each score separates same-ligand pairs from different-ligand pairs.
// Targets: AUC >= 0.8, a site pair <= 10 s. The similarity score the project documents is
// site: the top-1 alignment's overlay score of the two pocket linings, (shape + w chem) /
// (1 + w) with w = MatchOptions::site.chem_weight, with the lining residues' composition
// (matching::site_score, w = MatchOptions::site.lining_weight). Issue 31's figures: each
// score's AUC beside the size baseline's, on all pairs and on the size-matched ones.
//
// The match runs with each parameter set of variants(); the sites are built once.
//
//   ./build/r/bench/site_bench [entries.txt [PREFIX [VARIANTS [MARGIN [SES]]]]]
// entries.txt defaults to ../shared/datasets/kahraman-dev/entries.txt (the homogeneous set,
// ../shared/datasets/homogeneous/entries.txt, has the same layout and IsoMIF's per-site figures
// beside it, printed with the per-site AUCs); PREFIX, when given and not "-", makes
// PREFIX.<variant>.csv with one row per pair (sites, ligand types, same type, imaged CPs, site
// surface vertices, ms, every score printed, r_chem, the top-1 transform as t00..t23), which
// bench/site_choice.py reads; sites are built and pairs matched on every core; VARIANTS, a
// comma-separated list (or "-" for all), runs those only; MARGIN (A) is the site surface's margin
// (BindingSiteOptions::surface_margin; 0 = the surface of the whole structure); SES "edt" builds
// the site surfaces by the distance transform (--ses-method edt), anything else the exact SES.
#include "surfcomp/core/error.hpp"
#include "surfcomp/core/io/read_molecule.hpp"
#include "surfcomp/core/stopwatch.hpp"
#include "surfcomp/harmonic/surface_descriptors.hpp"
#include "surfcomp/matching/match.hpp"
#include "surfcomp/matching/site.hpp"
#include "surfcomp/molsurf/molecular_surface.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace {

namespace fs = std::filesystem;
using namespace surfcomp;

constexpr double kSiteRadius = 4.0;  // A, spheres around the ligand's atoms (the CLI's default)
constexpr double kPatchRadius =
    8.0;  // A, as in tests/matching/site_match_test.cpp (thermolysin sites)
constexpr double kContactRadius = 5.0;  // A, a chain with an atom this close to the ligand is kept

/// One line of entries.txt: `PDB ligand residue-number chain [altloc]`.
struct Entry {
  std::string pdb, ligand, chain;
  int residue_number = 0;
};

std::vector<Entry> read_entries(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw FileError(path.string(), "cannot open the entries list");
  std::vector<Entry> entries;
  std::size_t line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::istringstream fields(line);
    Entry e;
    if (!(fields >> e.pdb >> e.ligand >> e.residue_number >> e.chain)) {
      throw FormatError(path.string(), line_number,
                        "'" + line + "': expected PDB ligand residue-number chain");
    }
    entries.push_back(e);
  }
  return entries;
}

/// A built site: its description (the critical points outside the site skipped) and mask.
struct Site {
  Entry entry;
  std::string chains;  ///< the chains kept
  std::size_t atoms = 0, ligand_atoms = 0;
  harmonic::SurfaceDescriptors descriptors;
  std::vector<bool> in_site;             ///< one flag per critical point: inside the site
  std::size_t site_cps = 0;              ///< critical points inside the site
  std::size_t imaged = 0;                ///< site critical points with an image
  std::size_t site_vertices = 0;         ///< surface vertices inside the site's spheres
  matching::LiningComposition lining{};  ///< its lining residues' composition
  /// Its surface points' interaction composition (matching::interaction_composition).
  matching::InteractionComposition interactions{};
  std::vector<matching::InteractionPoint> points;  ///< its surface points' interactions
  double build_ms = 0;  ///< read, surface, critical points and site descriptors
};

/// Builds the site of `entry` from `pdb`: the binding site of the entry's ligand copy (residue
/// name, number and chain) on the structure reduced to the chains in contact with it. Whole
/// structures are not used: the surface's ESP and LP cost #vertices x #atoms, and chains that
/// do not touch the ligand are far from its site. Throws InputError when that copy is absent.
Site build_site(const Entry& entry, const fs::path& pdb, double margin,
                const harmonic::DescriptorOptions& options, molsurf::SesMethod method) {
  const Stopwatch start;
  Site site;
  site.entry = entry;
  molsurf::BindingSiteOptions site_options;
  site_options.sphere_radius = kSiteRadius;
  site_options.chain_contact_radius = kContactRadius;
  site_options.surface_margin = margin;
  const molsurf::BindingSite binding_site = molsurf::binding_site(
      io::read_molecule(pdb), LigandSelector{entry.ligand, entry.chain, entry.residue_number},
      site_options);
  std::set<std::string> chains;
  for (const Atom& atom : binding_site.ligand.atoms) chains.insert(atom.chain);
  for (const Atom& atom : binding_site.structure.atoms) chains.insert(atom.chain);
  for (const auto& chain : chains) site.chains += chain;
  site.atoms = binding_site.structure.atoms.size();
  site.ligand_atoms = binding_site.ligand.atoms.size();
  molsurf::MolecularSurfaceOptions surface_options;
  surface_options.ses.method = method;
  site.descriptors =
      matching::describe_site(molsurf::build_site_surface(binding_site, surface_options),
                              binding_site.structure, binding_site.spheres, options);
  site.in_site = matching::critical_points_in_site(site.descriptors, binding_site.spheres);
  site.site_cps =
      static_cast<std::size_t>(std::count(site.in_site.begin(), site.in_site.end(), true));
  site.imaged = harmonic::count_descriptors(site.descriptors).imaged;
  const Eigen::MatrixX3d positions = site.descriptors.surface.positions();
  for (Eigen::Index v = 0; v < positions.rows(); ++v) {
    const Eigen::Vector3d x = positions.row(v).transpose();
    site.site_vertices += std::any_of(binding_site.spheres.begin(), binding_site.spheres.end(),
                                      [&](const molsurf::SiteSphere& sphere) {
                                        return (x - sphere.center).norm() <= sphere.radius;
                                      })
                              ? 1
                              : 0;
  }
  site.lining = matching::lining_composition(binding_site.structure, binding_site.spheres)
                    .value_or(matching::LiningComposition{});  // none: similarity 0
  site.points = matching::interaction_points(site.descriptors.surface, binding_site.structure,
                                             binding_site.spheres);
  site.interactions =
      matching::interaction_composition(site.points).value_or(matching::InteractionComposition{});
  site.build_ms = start.elapsed_ms();
  return site;
}

/// The top-1 alignment of one site pair, and the pair's figures.
struct PairResult {
  std::size_t a = 0, b = 0;
  bool same = false;           ///< the same ligand type
  std::size_t alignments = 0;  ///< alignments found (cliques' and principal axes')
  /// Critical-point pairs of the top-1 alignment (0: none, or from the axes).
  std::size_t pairs = 0;
  std::size_t points = 0;                                   ///< its corresponding surface points
  Eigen::Matrix4d transform = Eigen::Matrix4d::Identity();  ///< top-1: b into a's frame
  double r_chem = 0;                                        ///< its ESP correlation at those points
  matching::OverlayScore overlay;        ///< its whole-site overlay scores (0 when not refined)
  matching::AlignedInteractions fields;  ///< the sites' interaction points under it
  double match_ms = 0;
};

/// A similarity score of a pair, larger = more similar.
struct Score {
  const char* name;
  const char* definition;
  std::function<double(const PairResult&, const Site&, const Site&)> value;
};

/// A set of match parameters tried on every pair. Looser still (F 0.1, R 0.2, t 3 A, j_tol 60
/// degrees) did not finish the 435 pairs in 7 minutes: the association graphs grow too dense.
struct Variant {
  const char* name;
  matching::MatchOptions options;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  const auto make = [&](const char* name, double fuzzy, double image, double distance,
                        double overlap) {
    Variant v{name, {}};
    v.options.mode = matching::MatchMode::binding_sites;
    v.options.graph.fuzzy_threshold = fuzzy;
    v.options.graph.image_threshold = image;
    v.options.graph.distance_tolerance = distance;
    v.options.graph.overlap_tolerance_degrees = overlap;
    out.push_back(v);
  };
  const matching::GraphOptions defaults;
  // The library's defaults for sites: the pocket linings (vertices within 2 A of the site CPs)
  // overlaid on shape alone from the cliques' and 24 principal-axes starts.
  make("default", defaults.fuzzy_threshold, defaults.image_threshold, defaults.distance_tolerance,
       defaults.overlap_tolerance_degrees);
  const auto vary = [&](const char* name,
                        const std::function<void(matching::MatchOptions&)>& change) {
    make(name, defaults.fuzzy_threshold, defaults.image_threshold, defaults.distance_tolerance,
         defaults.overlap_tolerance_degrees);
    change(out.back().options);
  };
  // What each choice adds: the cliques' poses alone; 4 axes starts instead of 24; a wider
  // lining; the chemistry in the score; the looser image threshold of the previous default.
  vary("no-axes", [](matching::MatchOptions& o) { o.site.principal_axes_starts = 0; });
  vary("axes4", [](matching::MatchOptions& o) { o.site.principal_axes_starts = 4; });
  vary("lining4", [](matching::MatchOptions& o) { o.site.overlay_radius = 4.0; });
  vary("lining8", [](matching::MatchOptions& o) { o.site.overlay_radius = 8.0; });
  vary("chem6", [](matching::MatchOptions& o) { o.site.chem_weight = 6.0; });
  vary("chem0.25", [](matching::MatchOptions& o) { o.site.chem_weight = 0.25; });
  vary("chem0.5", [](matching::MatchOptions& o) { o.site.chem_weight = 0.5; });
  vary("image0.3", [](matching::MatchOptions& o) { o.graph.image_threshold = 0.3; });
  vary("image0", [](matching::MatchOptions& o) { o.graph.image_threshold = 0.0; });
  return out;
}

/// ROC AUC of `scores` for positives against negatives: the probability that a random
/// positive scores above a random negative, ties counting one half (Mann-Whitney U / (P N)).
double roc_auc(const std::vector<double>& scores, const std::vector<bool>& positive) {
  double wins = 0;
  double p = 0, n = 0;
  for (std::size_t i = 0; i < scores.size(); ++i) {
    if (!positive[i]) continue;
    ++p;
    for (std::size_t j = 0; j < scores.size(); ++j) {
      if (positive[j]) continue;
      wins += scores[i] > scores[j] ? 1.0 : scores[i] == scores[j] ? 0.5 : 0.0;
    }
  }
  for (bool x : positive) n += x ? 0 : 1;
  return wins / (p * n);
}

/// 95 % interval of the ROC AUC of `score` over site resamples: `draws` times, the sites are
/// drawn with replacement (std::mt19937, `seed`) and the AUC taken over the pairs of distinct
/// drawn sites (a site drawn twice brings its pairs twice). It says how much the AUC owes to
/// which 36 sites happen to be in the set.
std::pair<double, double> site_bootstrap_auc(const std::vector<PairResult>& results,
                                             std::size_t n_sites,
                                             const std::function<double(const PairResult&)>& score,
                                             unsigned seed, int draws) {
  std::vector<std::vector<const PairResult*>> pair_of(
      n_sites, std::vector<const PairResult*>(n_sites, nullptr));
  for (const auto& r : results) pair_of[r.a][r.b] = pair_of[r.b][r.a] = &r;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, n_sites - 1);
  std::vector<double> aucs;
  for (int d = 0; d < draws; ++d) {
    std::vector<std::size_t> drawn(n_sites);
    for (auto& site : drawn) site = pick(rng);
    std::vector<double> values;
    std::vector<bool> positive;
    for (std::size_t i = 0; i < drawn.size(); ++i) {
      for (std::size_t j = i + 1; j < drawn.size(); ++j) {
        const PairResult* r = pair_of[drawn[i]][drawn[j]];
        if (drawn[i] == drawn[j] || r == nullptr) continue;
        values.push_back(score(*r));
        positive.push_back(r->same);
      }
    }
    const auto n_positive = std::count(positive.begin(), positive.end(), true);
    if (n_positive == 0 || n_positive == static_cast<std::ptrdiff_t>(positive.size())) continue;
    aucs.push_back(roc_auc(values, positive));
  }
  std::sort(aucs.begin(), aucs.end());
  const auto at = [&](double q) {
    return aucs[static_cast<std::size_t>(q * static_cast<double>(aucs.size() - 1))];
  };
  return aucs.empty() ? std::pair<double, double>{0.0, 0.0}
                      : std::pair<double, double>{at(0.025), at(0.975)};
}

}  // namespace

/// |imaged critical points of x - those of y|: the size baseline's distance.
double size_gap(const Site& x, const Site& y) {
  return std::abs(static_cast<double>(x.imaged) - static_cast<double>(y.imaged));
}

/// Size alone separates the ligand types of this set well; over the pairs whose critical-point
/// counts differ by at most kSizeMatched, size says nothing, and what a score separates there is
/// its own.
constexpr double kSizeMatched = 2.0;

void print_size_matched(const std::vector<PairResult>& results, const std::vector<Site>& sites,
                        const std::vector<Score>& scores) {
  std::vector<const PairResult*> matched;
  for (const auto& r : results) {
    if (size_gap(sites[r.a], sites[r.b]) <= kSizeMatched) matched.push_back(&r);
  }
  std::vector<bool> positive;
  for (const PairResult* r : matched) positive.push_back(r->same);
  const auto same = std::count(positive.begin(), positive.end(), true);
  std::printf("size-matched pairs (|imaged_a - imaged_b| <= %.0f): %zu (%td same, %td different)\n",
              kSizeMatched, matched.size(), same,
              static_cast<std::ptrdiff_t>(matched.size()) - same);
  for (const Score& score : scores) {
    std::vector<double> values;
    for (const PairResult* r : matched) {
      values.push_back(score.value(*r, sites[r->a], sites[r->b]));
    }
    std::printf("  size-matched AUC %-14s %.3f\n", score.name, roc_auc(values, positive));
  }
}

/// Pocket search, leave one out: each site queried against the other sites, ranked by `score`
/// (ties by entry order); how often the first, or one of the first three, binds the same ligand
/// type.
void print_pocket_search(const std::vector<PairResult>& results, const std::vector<Site>& sites,
                         const Score& score) {
  std::vector<std::vector<std::pair<double, std::size_t>>> ranked(sites.size());
  for (const auto& r : results) {
    const double value = score.value(r, sites[r.a], sites[r.b]);
    ranked[r.a].emplace_back(value, r.b);
    ranked[r.b].emplace_back(value, r.a);
  }
  std::size_t top1 = 0, top3 = 0;
  for (std::size_t query = 0; query < sites.size(); ++query) {
    auto& hits = ranked[query];
    std::sort(hits.begin(), hits.end(), [](const auto& x, const auto& y) {
      return x.first != y.first ? x.first > y.first : x.second < y.second;
    });
    const auto same = [&](std::size_t k) {
      return k < hits.size() && sites[hits[k].second].entry.ligand == sites[query].entry.ligand;
    };
    top1 += same(0) ? 1 : 0;
    top3 += (same(0) || same(1) || same(2)) ? 1 : 0;
  }
  std::printf("pocket search, leave one out by %s: top-1 same ligand type %zu/%zu, top-3 %zu/%zu\n",
              score.name, top1, sites.size(), top3, sites.size());
}

/// Per-site AUC the way IsoMIF's evaluation computes it: each site in turn is the query, the
/// other sites are ranked by `score`, and the AUC separates those of the query's ligand type from
/// the rest. Prints the mean over all sites and per ligand type, beside IsoMIF's published
/// per-site figures when `isomif_csv` exists (rows IsoMIF_p, a column per ligand type).
void print_per_site_auc(const std::vector<PairResult>& results, const std::vector<Site>& sites,
                        const Score& score, const fs::path& isomif_csv) {
  std::vector<std::vector<double>> values(sites.size());
  std::vector<std::vector<bool>> same(sites.size());
  for (const auto& r : results) {
    const double value = score.value(r, sites[r.a], sites[r.b]);
    for (const auto& [query, other] : {std::pair{r.a, r.b}, std::pair{r.b, r.a}}) {
      values[query].push_back(value);
      same[query].push_back(sites[other].entry.ligand == sites[query].entry.ligand);
    }
  }
  std::map<std::string, std::vector<double>> by_type;
  std::vector<double> all;
  for (std::size_t query = 0; query < sites.size(); ++query) {
    const auto positives = std::count(same[query].begin(), same[query].end(), true);
    if (positives == 0 || positives == static_cast<std::ptrdiff_t>(same[query].size())) continue;
    const double auc = roc_auc(values[query], same[query]);
    by_type[sites[query].entry.ligand].push_back(auc);
    all.push_back(auc);
  }
  std::map<std::string, std::vector<double>> isomif;
  if (std::ifstream in(isomif_csv); in) {
    std::string header;
    std::getline(in, header);
    std::vector<std::string> columns;
    std::stringstream names(header);
    for (std::string name; std::getline(names, name, ',');) columns.push_back(name);
    for (std::string line; std::getline(in, line);) {
      std::stringstream cells(line);
      std::string cell;
      std::getline(cells, cell, ',');
      if (cell != "IsoMIF_p") continue;
      for (std::size_t c = 1; c < columns.size() && std::getline(cells, cell, ','); ++c) {
        isomif[columns[c]].push_back(std::stod(cell));
      }
    }
  }
  const auto mean = [](const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
  };
  std::vector<double> isomif_all;
  for (const auto& [type, aucs] : isomif)
    isomif_all.insert(isomif_all.end(), aucs.begin(), aucs.end());
  std::printf(
      "per-site AUC by %s (each site the query, same type against the rest): mean %.3f over %zu "
      "sites",
      score.name, mean(all), all.size());
  if (!isomif_all.empty())
    std::printf("; IsoMIF_p published mean %.3f over %zu", mean(isomif_all), isomif_all.size());
  std::printf("\n");
  for (const auto& [type, aucs] : by_type) {
    std::printf("  %-4s %2zu sites  %.3f", type.c_str(), aucs.size(), mean(aucs));
    if (const auto it = isomif.find(type); it != isomif.end())
      std::printf("   IsoMIF_p %.3f", mean(it->second));
    std::printf("\n");
  }
}

int main(int argc, char** argv) {
  const fs::path entries_path =
      argc > 1 ? fs::path(argv[1]) : test::shared_datasets_root() / "kahraman-dev/entries.txt";
  if (!fs::exists(entries_path)) {
    std::printf("skipped: %s is absent\n", entries_path.c_str());
    return 0;
  }
  try {
    const std::vector<Entry> entries = read_entries(entries_path);
    harmonic::DescriptorOptions options;
    options.patch.radius = kPatchRadius;
    const double margin =
        argc > 4 ? std::stod(argv[4]) : molsurf::BindingSiteOptions{}.surface_margin;
    const molsurf::SesMethod method = argc > 5 && std::string(argv[5]) == "edt"
                                          ? molsurf::SesMethod::distance_transform
                                          : molsurf::SesMethod::exact;
    std::printf(
        "site radius %.1f A, patch radius %.1f A, chains within %.1f A of the ligand, surface "
        "margin %.1f A, SES %s\n\n",
        kSiteRadius, kPatchRadius, kContactRadius, margin,
        method == molsurf::SesMethod::exact ? "exact" : "edt (distance transform)");
    std::printf("%-5s %-4s %6s %-2s %-6s %7s %6s %9s %6s %7s %9s\n", "pdb", "lig", "resnum", "ch",
                "kept", "atoms", "ligat", "vertices", "cps", "imaged", "build_ms");
    // Sites are built, and pairs matched, in parallel (every core TBB is given); each time in the
    // tables is one site's or one pair's own wall time.
    std::vector<Site> built(entries.size());
    std::vector<std::string> build_error(entries.size());
    tbb::parallel_for(std::size_t{0}, entries.size(), [&](std::size_t i) {
      const Entry& e = entries[i];
      // A site whose surface a stage rejects is reported and left out of the pairs.
      try {
        built[i] = build_site(e, entries_path.parent_path() / "pdb" / (e.pdb + ".pdb"), margin,
                              options, method);
      } catch (const Error& error) {
        build_error[i] = error.what();
      }
    });
    std::vector<Site> sites;
    std::vector<std::string> skipped;
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const Entry& e = entries[i];
      if (!build_error[i].empty()) {
        std::printf("%-5s %-4s skipped: %s\n", e.pdb.c_str(), e.ligand.c_str(),
                    build_error[i].c_str());
        skipped.push_back(e.pdb);
        continue;
      }
      sites.push_back(std::move(built[i]));
      const Site& s = sites.back();
      std::printf("%-5s %-4s %6d %-2s %-6s %7zu %6zu %9zu %6zu %7zu %9.0f\n", e.pdb.c_str(),
                  e.ligand.c_str(), e.residue_number, e.chain.c_str(), s.chains.c_str(), s.atoms,
                  s.ligand_atoms, s.descriptors.surface.n_vertices(), s.site_cps, s.imaged,
                  s.build_ms);
    }
    std::printf("%d threads\n", tbb::this_task_arena::max_concurrency());
    std::fflush(stdout);

    for (const Variant& variant : variants()) {
      if (argc > 3 && std::string(argv[3]) != "-" &&
          ("," + std::string(argv[3]) + ",").find("," + std::string(variant.name) + ",") ==
              std::string::npos)
        continue;
      const matching::MatchOptions& match_options = variant.options;
      const auto& g = match_options.graph;
      std::printf(
          "\n== %s: fuzzy F %.2f, image R %.2f, distance t %.1f A, overlap j_tol %.0f deg\n",
          variant.name, g.fuzzy_threshold, g.image_threshold, g.distance_tolerance,
          g.overlap_tolerance_degrees);
      std::vector<PairResult> results;
      for (std::size_t a = 0; a < sites.size(); ++a) {
        for (std::size_t b = a + 1; b < sites.size(); ++b) {
          PairResult r;
          r.a = a;
          r.b = b;
          r.same = sites[a].entry.ligand == sites[b].entry.ligand;
          results.push_back(r);
        }
      }
      tbb::parallel_for(std::size_t{0}, results.size(), [&](std::size_t i) {
        PairResult& r = results[i];
        const Stopwatch start;
        const auto match =
            matching::match_surfaces(sites[r.a].descriptors, sites[r.b].descriptors, match_options,
                                     &sites[r.a].in_site, &sites[r.b].in_site);
        r.match_ms = start.elapsed_ms();
        r.alignments = match.alignments.size();
        if (!match.alignments.empty()) {
          const auto& top = match.alignments.front();
          r.pairs = top.cp_pairs.size();
          r.points = top.n_points;
          r.r_chem = top.r_chem;
          r.overlay = top.overlay;
          r.transform = top.transform;
        }
        r.fields =
            matching::aligned_interactions(sites[r.a].points, sites[r.b].points, r.transform);
      });

      // Correspondences per matched critical-point pair at full image coverage: the image grid's
      // point count over the correspondence subsampling is the same for every pair, so n_points
      // over the smaller site's imaged critical points measures the fraction of that site imaged
      // onto the other.
      const std::vector<Score> scores = {
          {"pairs", "critical-point pairs of the top-1 alignment",
           [](const PairResult& r, const Site&, const Site&) {
             return static_cast<double>(r.pairs);
           }},
          {"coverage", "top-1 n_points / min(imaged site critical points of the two sites)",
           [](const PairResult& r, const Site& x, const Site& y) {
             const double smaller = static_cast<double>(std::min(x.imaged, y.imaged));
             return smaller > 0 ? static_cast<double>(r.points) / smaller : 0.0;
           }},
          {"pairs_jaccard", "top-1 pairs / (imaged_a + imaged_b - pairs)",
           [](const PairResult& r, const Site& x, const Site& y) {
             const double union_size =
                 static_cast<double>(x.imaged + y.imaged) - static_cast<double>(r.pairs);
             return union_size > 0 ? static_cast<double>(r.pairs) / union_size : 0.0;
           }},
          {"overlay",
           "top-1 overlay score of the pocket linings (shape + w chem) / (1 + w), w = "
           "site.chem_weight (the documented site similarity)",
           [](const PairResult& r, const Site&, const Site&) { return r.overlay.score; }},
          {"overlay_shape", "top-1 shape Tanimoto of the pocket linings",
           [](const PairResult& r, const Site&, const Site&) { return r.overlay.shape; }},
          {"overlay_chem", "top-1 ESP/LP colour Tanimoto of the site regions",
           [](const PairResult& r, const Site&, const Site&) { return r.overlay.chem; }},
          {"coverage_chem", "coverage * (1 + r_chem) / 2",
           [](const PairResult& r, const Site& x, const Site& y) {
             const double smaller = static_cast<double>(std::min(x.imaged, y.imaged));
             return smaller > 0 ? static_cast<double>(r.points) / smaller * (1.0 + r.r_chem) / 2.0
                                : 0.0;
           }},
          {"size", "baseline: -|imaged_a - imaged_b|, the sites' critical-point counts",
           [](const PairResult&, const Site& x, const Site& y) { return -size_gap(x, y); }},
          {"lining", "lining_similarity of the lining residues' compositions",
           [](const PairResult&, const Site& x, const Site& y) {
             return matching::lining_similarity(x.lining, y.lining);
           }},
          {"interactions", "interaction_similarity of the site surface points' interaction classes",
           [](const PairResult&, const Site& x, const Site& y) {
             return matching::interaction_similarity(x.interactions, y.interactions);
           }},
          {"fields", "aligned_interactions similarity: agreeing interaction points of both",
           [](const PairResult& r, const Site&, const Site&) { return r.fields.similarity; }},
          {"fields_partial",
           "aligned_interactions coverage: agreeing points of the smaller site over its points",
           [](const PairResult& r, const Site&, const Site&) { return r.fields.coverage; }},
          {"site",
           "site_score: (overlay + w lining) / (1 + w), w = site.lining_weight (the documented "
           "site similarity)",
           [w = match_options.site.lining_weight](const PairResult& r, const Site& x,
                                                  const Site& y) {
             return matching::site_score(r.overlay.score,
                                         matching::lining_similarity(x.lining, y.lining), w);
           }},
      };
      if (argc > 2 && std::string(argv[2]) != "-") {
        std::ofstream csv(std::string(argv[2]) + "." + variant.name + ".csv");
        if (!csv) throw FileError(argv[2], "cannot write the pairs table");
        csv << "a,b,ligand_a,ligand_b,same,imaged_a,imaged_b,site_vertices_a,site_vertices_b,"
               "points,"
               "match_ms";
        for (const Score& score : scores) csv << ',' << score.name;
        csv << ",r_chem,t00,t01,t02,t03,t10,t11,t12,t13,t20,t21,t22,t23\n";
        csv.precision(9);
        for (const auto& r : results) {
          const Site& x = sites[r.a];
          const Site& y = sites[r.b];
          csv << x.entry.pdb << ',' << y.entry.pdb << ',' << x.entry.ligand << ',' << y.entry.ligand
              << ',' << r.same << ',' << x.imaged << ',' << y.imaged << ',' << x.site_vertices
              << ',' << y.site_vertices << ',' << r.points << ',' << r.match_ms;
          for (const Score& score : scores) csv << ',' << score.value(r, x, y);
          csv << ',' << r.r_chem;
          for (int row = 0; row < 3; ++row) {
            for (int col = 0; col < 4; ++col) csv << ',' << r.transform(row, col);
          }
          csv << '\n';
        }
      }
      std::vector<bool> positive;
      std::vector<double> match_ms, pair_ms, build_ms;
      for (const auto& s : sites) build_ms.push_back(s.build_ms);
      for (const auto& r : results) {
        positive.push_back(r.same);
        match_ms.push_back(r.match_ms);
        pair_ms.push_back(sites[r.a].build_ms + sites[r.b].build_ms + r.match_ms);
      }
      const auto positives =
          static_cast<std::size_t>(std::count(positive.begin(), positive.end(), true));
      const auto aligned = std::count_if(results.begin(), results.end(),
                                         [](const PairResult& r) { return r.alignments > 0; });
      const auto from_cliques = std::count_if(results.begin(), results.end(),
                                              [](const PairResult& r) { return r.pairs > 0; });
      std::printf("%zu sites built, %zu skipped", sites.size(), skipped.size());
      for (const auto& name : skipped) std::printf(" %s", name.c_str());
      std::printf(
          "\n%zu sites, %zu pairs (%zu same ligand type, %zu different), %td with an alignment, "
          "%td with a top-1 from the cliques\n",
          sites.size(), results.size(), positives, results.size() - positives, aligned,
          from_cliques);
      for (const Score& score : scores) {
        std::vector<double> values;
        for (const auto& r : results) values.push_back(score.value(r, sites[r.a], sites[r.b]));
        std::printf("AUC %-14s %.3f   (%s)\n", score.name, roc_auc(values, positive),
                    score.definition);
      }
      print_size_matched(results, sites, scores);
      for (const Score& score : scores) {
        const std::string name = score.name;
        if (name != "overlay" && name != "site" && name != "size") continue;
        print_pocket_search(results, sites, score);
        print_per_site_auc(results, sites, score,
                           entries_path.parent_path() / "isomif_per_site_auc.csv");
        const auto [low, high] = site_bootstrap_auc(
            results, sites.size(),
            [&](const PairResult& r) { return score.value(r, sites[r.a], sites[r.b]); }, 20261122u,
            300);
        std::printf("AUC %s, 95 %% interval over 300 site resamples (seed 20261122): %.3f - %.3f\n",
                    score.name, low, high);
      }
      std::printf("site build (read, surface, site descriptors): median %.0f ms, max %.0f ms\n",
                  test::median(build_ms), *std::max_element(build_ms.begin(), build_ms.end()));
      std::printf("match per pair (descriptors built): median %.1f ms, max %.1f ms\n",
                  test::median(match_ms), *std::max_element(match_ms.begin(), match_ms.end()));
      std::printf("site pair from PDB files (both builds + match): median %.0f ms, max %.0f ms\n",
                  test::median(pair_ms), *std::max_element(pair_ms.begin(), pair_ms.end()));
      std::fflush(stdout);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "site_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
