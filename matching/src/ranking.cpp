#include "surfcomp/matching/ranking.hpp"

#include "option_checks.hpp"
#include "surfcomp/core/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <string>

namespace surfcomp::matching {

namespace {

/// Fractional ranks (1 = best) of `values` where larger is better: equal values share the mean
/// of the positions they span.
std::vector<double> fractional_ranks(const std::vector<double>& values) {
  const std::size_t n = values.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return values[x] > values[y]; });
  std::vector<double> ranks(n);
  for (std::size_t start = 0; start < n;) {
    std::size_t end = start + 1;
    while (end < n && values[order[end]] == values[order[start]]) ++end;
    const double shared = 0.5 * static_cast<double>(start + 1 + end);  // mean of start+1 .. end
    for (std::size_t k = start; k < end; ++k) ranks[order[k]] = shared;
    start = end;
  }
  return ranks;
}

}  // namespace

std::vector<RankedAlignment> rank_alignments(const std::vector<Cluster>& clusters,
                                             const RankingOptions& options) {
  const std::array<double, 3> weights = {options.weight_rmsd, options.weight_points,
                                         options.weight_chem};
  detail::check_ranking_options(options, {"rank_alignments", ""});
  const double weight_sum = weights[0] + weights[1] + weights[2];

  // The scores, each oriented so that larger is better.
  const std::size_t n = clusters.size();
  std::array<std::vector<double>, 3> scores;
  for (auto& s : scores) s.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Cluster& c = clusters[i];
    if (!std::isfinite(c.fit.rmsd) || !std::isfinite(c.r_chem)) {
      throw InputError("ranking: cluster " + std::to_string(i) + " has RMSD " +
                       std::to_string(c.fit.rmsd) + " and R_chem " + std::to_string(c.r_chem) +
                       "; expected finite scores");
    }
    scores[0][i] = -c.fit.rmsd;
    scores[1][i] = static_cast<double>(c.fit.n_points);
    scores[2][i] = c.r_chem;
  }

  std::vector<double> consensus(n, 0.0);
  bool lower_is_better = false;
  switch (options.scheme) {
    case ConsensusScheme::rank_by_rank: {
      lower_is_better = true;
      for (std::size_t j = 0; j < 3; ++j) {
        const std::vector<double> ranks = fractional_ranks(scores[j]);
        for (std::size_t i = 0; i < n; ++i) consensus[i] += weights[j] * ranks[i];
      }
      break;
    }
    case ConsensusScheme::rank_by_number: {
      for (std::size_t j = 0; j < 3 && n > 0; ++j) {
        const auto [lo, hi] = std::minmax_element(scores[j].begin(), scores[j].end());
        const double range = *hi - *lo;
        for (std::size_t i = 0; i < n; ++i) {
          const double normalised = range > 0.0 ? (scores[j][i] - *lo) / range : 1.0;
          consensus[i] += weights[j] * normalised;
        }
      }
      break;
    }
    case ConsensusScheme::rank_by_vote: {
      const auto k = std::max<std::size_t>(
          1,
          static_cast<std::size_t>(std::ceil(options.vote_top_fraction * static_cast<double>(n))));
      for (std::size_t j = 0; j < 3 && n > 0; ++j) {
        std::vector<double> best = scores[j];
        std::nth_element(best.begin(), best.begin() + static_cast<std::ptrdiff_t>(k - 1),
                         best.end(), std::greater<>());
        const double border = best[k - 1];
        for (std::size_t i = 0; i < n; ++i) {
          if (scores[j][i] >= border) consensus[i] += weights[j];
        }
      }
      break;
    }
  }

  if (options.scheme != ConsensusScheme::rank_by_vote) {
    // Divided once at the end, so that equal weighted sums stay equal (ties by index).
    for (double& c : consensus) c /= weight_sum;
  }

  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) {
    const double cx = consensus[static_cast<std::size_t>(x)],
                 cy = consensus[static_cast<std::size_t>(y)];
    return lower_is_better ? cx < cy : cx > cy;
  });
  std::vector<RankedAlignment> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    out[k] = {order[k], consensus[static_cast<std::size_t>(order[k])], static_cast<int>(k) + 1};
  }
  return out;
}

}  // namespace surfcomp::matching
