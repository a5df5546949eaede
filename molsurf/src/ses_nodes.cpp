#include "ses_nodes.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace surfcomp::molsurf::detail {
namespace {

/// A union-find over the gaps between inside runs.
class Gaps {
 public:
  explicit Gaps(std::size_t count) : parent_(count), border_(count, 0) {
    for (std::size_t g = 0; g < count; ++g) parent_[g] = static_cast<int>(g);
  }
  void mark_border(int g) { border_[static_cast<std::size_t>(g)] = 1; }
  int find(int g) {
    while (parent_[static_cast<std::size_t>(g)] != g) {
      parent_[static_cast<std::size_t>(g)] =
          parent_[static_cast<std::size_t>(parent_[static_cast<std::size_t>(g)])];
      g = parent_[static_cast<std::size_t>(g)];
    }
    return g;
  }
  void join(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    parent_[static_cast<std::size_t>(b)] = a;
    border_[static_cast<std::size_t>(a)] |= border_[static_cast<std::size_t>(b)];
  }
  bool reaches_border(int g) { return border_[static_cast<std::size_t>(find(g))] != 0; }

 private:
  std::vector<int> parent_;
  std::vector<std::uint8_t> border_;
};

}  // namespace

NodeStates node_states(const NodeGrid& grid, const Eigen::Ref<const Eigen::MatrixX3d>& centers,
                       const Eigen::VectorXd& grown) {
  NodeStates out;
  const std::size_t rows = static_cast<std::size_t>(grid.ny) * static_cast<std::size_t>(grid.nz);
  const auto nx = static_cast<std::size_t>(grid.nx);
  out.state.assign(grid.size(), kSolvent);
  out.atom.assign(grid.size(), -1);
  struct Chord {
    std::size_t row;
    int first, last;
    bool operator<(const Chord& o) const {
      return row != o.row ? row < o.row : first != o.first ? first < o.first : last < o.last;
    }
  };
  std::vector<Chord> chords;
  for (Eigen::Index a = 0; a < centers.rows(); ++a) {
    grid.for_each_row_in_ball(centers.row(a).transpose(), grown(a),
                              [&](std::size_t at, int i0, int count, double, double) {
                                std::fill_n(out.state.begin() + static_cast<std::ptrdiff_t>(at),
                                            count, kInside);
                                std::fill_n(out.atom.begin() + static_cast<std::ptrdiff_t>(at),
                                            count, static_cast<std::int32_t>(a));
                                chords.push_back({at / nx, i0, i0 + count - 1});
                              });
  }
  std::sort(chords.begin(), chords.end());
  RowRuns& inside = out.inside;
  inside.offsets.assign(rows + 1, 0);
  for (const Chord& c : chords) {
    if (!inside.runs.empty() && inside.offsets[c.row + 1] > 0 &&
        c.first <= inside.runs.back().second + 1) {
      inside.runs.back().second = std::max(inside.runs.back().second, c.last);
      continue;
    }
    inside.runs.emplace_back(c.first, c.last);
    inside.offsets[c.row + 1] = inside.runs.size();
  }
  for (std::size_t r = 0; r < rows; ++r)
    inside.offsets[r + 1] = std::max(inside.offsets[r + 1], inside.offsets[r]);
  // The gaps between inside runs of each row, joined with the overlapping gaps of the rows
  // before it in y and in z; a gap at a row's end or in a border row is the solvent's.
  RowRuns gaps;
  gaps.offsets.assign(rows + 1, 0);
  for (std::size_t r = 0; r < rows; ++r) {
    int next = 0;
    const auto [begin, end] = inside.row(r);
    for (const auto* run = begin; run != end; ++run) {
      if (run->first > next) gaps.runs.emplace_back(next, run->first - 1);
      next = run->second + 1;
    }
    if (next < grid.nx) gaps.runs.emplace_back(next, grid.nx - 1);
    gaps.offsets[r + 1] = gaps.runs.size();
  }
  Gaps sets(gaps.runs.size());
  for (int k = 0; k < grid.nz; ++k) {
    for (int j = 0; j < grid.ny; ++j) {
      const std::size_t r = static_cast<std::size_t>(k) * static_cast<std::size_t>(grid.ny) +
                            static_cast<std::size_t>(j);
      const bool border_row = j == 0 || k == 0 || j + 1 == grid.ny || k + 1 == grid.nz;
      for (std::size_t g = gaps.offsets[r]; g < gaps.offsets[r + 1]; ++g) {
        if (border_row || gaps.runs[g].first == 0 || gaps.runs[g].second == grid.nx - 1)
          sets.mark_border(static_cast<int>(g));
      }
      for (int side = 0; side < 2; ++side) {
        if ((side == 0 && j == 0) || (side == 1 && k == 0)) continue;
        const std::size_t before = side == 0 ? r - 1 : r - static_cast<std::size_t>(grid.ny);
        std::size_t b = gaps.offsets[before];
        for (std::size_t g = gaps.offsets[r]; g < gaps.offsets[r + 1]; ++g) {
          while (b < gaps.offsets[before + 1] && gaps.runs[b].second < gaps.runs[g].first) ++b;
          for (std::size_t c = b;
               c < gaps.offsets[before + 1] && gaps.runs[c].first <= gaps.runs[g].second; ++c)
            sets.join(static_cast<int>(g), static_cast<int>(c));
        }
      }
    }
  }
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t g = gaps.offsets[r]; g < gaps.offsets[r + 1]; ++g) {
      if (sets.reaches_border(static_cast<int>(g))) continue;
      const std::size_t at = r * nx;
      std::fill(out.state.begin() +
                    static_cast<std::ptrdiff_t>(at + static_cast<std::size_t>(gaps.runs[g].first)),
                out.state.begin() + static_cast<std::ptrdiff_t>(
                                        at + static_cast<std::size_t>(gaps.runs[g].second) + 1),
                kUnreached);
    }
  }
  return out;
}

}  // namespace surfcomp::molsurf::detail
