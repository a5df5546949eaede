// The domain of every matching option, checked in one place: each public entry point that takes
// an option (build_association_graph and its filters, maximal_cliques, cluster_alignments,
// pair_correspondences, rank_alignments, sample_surface, SurfaceOverlay) and
// validate(MatchOptions) call the same function, so a domain and its message are written once.
// Not installed.
#pragma once

#include "surfcomp/matching/association_graph.hpp"
#include "surfcomp/matching/atom_polish.hpp"
#include "surfcomp/matching/cliques.hpp"
#include "surfcomp/matching/clustering.hpp"
#include "surfcomp/matching/correspondences.hpp"
#include "surfcomp/matching/overlay.hpp"
#include "surfcomp/matching/ranking.hpp"

#include <string>

namespace surfcomp::matching::detail {

/// Who checks, for the messages: "<caller>: <prefix><name> = <value>, expected <domain>".
struct OptionCheck {
  std::string caller;  ///< "association graph", "match options", ...
  std::string prefix;  ///< the options' path in MatchOptions ("graph."), or ""

  /// Throws OptionError with the message above unless `ok`.
  void require(bool ok, const std::string& name, const std::string& value,
               const char* expected) const;
  void require(bool ok, const std::string& name, double value, const char* expected) const;
  void require(bool ok, const std::string& name, int value, const char* expected) const;
};

void check_distance_filter(double tolerance, double min_distance, const OptionCheck& check);
void check_overlap_tolerance(double tolerance_degrees, const OptionCheck& check);
void check_graph_options(const GraphOptions& options, const OptionCheck& check);
void check_min_clique_size(int min_size, const std::string& name, const OptionCheck& check);
void check_clique_work(std::int64_t max_work, const std::string& name, const OptionCheck& check);
void check_clique_count(std::size_t max_cliques, const std::string& name, const OptionCheck& check);
void check_clique_options(const CliqueOptions& options, const OptionCheck& check);
void check_clustering_options(const ClusteringOptions& options, const OptionCheck& check);
void check_correspondence_options(const CorrespondenceOptions& options, const OptionCheck& check);
void check_ranking_options(const RankingOptions& options, const OptionCheck& check);
void check_overlay_spacing(double spacing, const OptionCheck& check);
void check_overlay_options(const OverlayOptions& options, const OptionCheck& check);
void check_axes_start_count(int n, const std::string& name, const OptionCheck& check);
void check_atom_polish_options(const AtomPolishOptions& options, const OptionCheck& check);

}  // namespace surfcomp::matching::detail
