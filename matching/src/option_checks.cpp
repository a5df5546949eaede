#include "option_checks.hpp"

#include "surfcomp/core/error.hpp"

#include <cmath>

namespace surfcomp::matching::detail {
namespace {

bool finite_at_least(double value, double low) { return std::isfinite(value) && value >= low; }
bool finite_positive(double value) { return std::isfinite(value) && value > 0.0; }

}  // namespace

void OptionCheck::require(bool ok, const std::string& name, const std::string& value,
                          const char* expected) const {
  if (!ok) {
    throw OptionError(caller + ": " + prefix + name + " = " + value + ", expected " + expected);
  }
}

void OptionCheck::require(bool ok, const std::string& name, double value,
                          const char* expected) const {
  require(ok, name, std::to_string(value), expected);
}

void OptionCheck::require(bool ok, const std::string& name, int value, const char* expected) const {
  require(ok, name, std::to_string(value), expected);
}

void check_distance_filter(double tolerance, double min_distance, const OptionCheck& check) {
  check.require(finite_at_least(tolerance, 0.0), "distance_tolerance", tolerance,
                "a finite value >= 0 A");
  check.require(finite_at_least(min_distance, 0.0), "min_distance", min_distance,
                "a finite value >= 0 A");
}

void check_overlap_tolerance(double tolerance_degrees, const OptionCheck& check) {
  check.require(finite_at_least(tolerance_degrees, 0.0) && tolerance_degrees <= 180.0,
                "overlap_tolerance_degrees", tolerance_degrees, "a value in [0, 180] degrees");
}

void check_graph_options(const GraphOptions& options, const OptionCheck& check) {
  check.require(options.fuzzy_threshold >= 0.0 && options.fuzzy_threshold <= 1.0, "fuzzy_threshold",
                options.fuzzy_threshold, "a value in [0, 1]");
  check.require(std::isfinite(options.image_threshold), "image_threshold", options.image_threshold,
                "a finite value");
  check_distance_filter(options.distance_tolerance, options.min_distance, check);
  check_overlap_tolerance(options.overlap_tolerance_degrees, check);
  check.require(options.max_nodes > 0, "max_nodes", std::to_string(options.max_nodes), "> 0");
}

void check_min_clique_size(int min_size, const std::string& name, const OptionCheck& check) {
  check.require(min_size >= 1, name, min_size, ">= 1");
}

void check_clique_work(std::int64_t max_work, const std::string& name, const OptionCheck& check) {
  check.require(max_work > 0, name, std::to_string(max_work), "> 0");
}

void check_clique_count(std::size_t max_cliques, const std::string& name,
                        const OptionCheck& check) {
  check.require(max_cliques > 0, name, std::to_string(max_cliques), "> 0");
}

void check_clique_options(const CliqueOptions& options, const OptionCheck& check) {
  check_min_clique_size(options.min_size, "min_size", check);
  check_clique_work(options.max_work, "max_work", check);
  check_clique_count(options.max_cliques, "max_cliques", check);
}

void check_clustering_options(const ClusteringOptions& options, const OptionCheck& check) {
  check.require(options.rmsd_cut > 0.0, "rmsd_cut", options.rmsd_cut, "> 0 A");
  check.require(options.merge_cut > 0.0, "merge_cut", options.merge_cut, "> 0 A");
}

void check_correspondence_options(const CorrespondenceOptions& options, const OptionCheck& check) {
  check.require(options.ring_step >= 1, "ring_step", options.ring_step, ">= 1");
  check.require(options.sector_step >= 1, "sector_step", options.sector_step, ">= 1");
}

void check_ranking_options(const RankingOptions& options, const OptionCheck& check) {
  check.require(finite_at_least(options.weight_rmsd, 0.0), "weight_rmsd", options.weight_rmsd,
                "a finite value >= 0");
  check.require(finite_at_least(options.weight_points, 0.0), "weight_points", options.weight_points,
                "a finite value >= 0");
  check.require(finite_at_least(options.weight_chem, 0.0), "weight_chem", options.weight_chem,
                "a finite value >= 0");
  check.require(options.weight_rmsd + options.weight_points + options.weight_chem > 0.0,
                "weight_rmsd + weight_points + weight_chem", 0.0, "at least one weight > 0");
  check.require(options.vote_top_fraction > 0.0 && options.vote_top_fraction <= 1.0,
                "vote_top_fraction", options.vote_top_fraction, "a value in (0, 1]");
}

void check_overlay_spacing(double spacing, const OptionCheck& check) {
  check.require(finite_positive(spacing), "spacing", spacing, "a finite value > 0 A");
}

void check_overlay_options(const OverlayOptions& options, const OptionCheck& check) {
  check.require(finite_positive(options.sigma), "sigma", options.sigma, "a finite value > 0 A");
  check_overlay_spacing(options.spacing, check);
  check.require(finite_at_least(options.chem_weight, 0.0), "chem_weight", options.chem_weight,
                "a finite value >= 0");
  check.require(finite_at_least(options.atom_weight, 0.0), "atom_weight", options.atom_weight,
                "a finite value >= 0");
  check.require(options.iterations >= 0, "iterations", options.iterations, ">= 0");
  check.require(options.tolerance >= 0.0, "tolerance", options.tolerance, "a value >= 0 A");
}

void check_axes_start_count(int n, const std::string& name, const OptionCheck& check) {
  check.require(is_axes_start_count(n), name, n, "0, 4 or 24");
}

void check_atom_polish_options(const AtomPolishOptions& options, const OptionCheck& check) {
  check.require(options.sigma == 0.0 || finite_at_least(options.sigma, min_atom_polish_sigma),
                "sigma", options.sigma, "0 (off) or a finite value >= 0.05 A");
  check.require(finite_at_least(options.weight, 0.0), "weight", options.weight,
                "a finite value >= 0");
  check.require(options.iterations >= 0, "iterations", options.iterations, ">= 0");
  check.require(options.tolerance >= 0.0, "tolerance", options.tolerance, "a value >= 0 A");
}

}  // namespace surfcomp::matching::detail
