// Internal to the molsurf module (not installed): node values of a regular grid kept only where
// they are set, the storage between build_ses's sampling of the distance field and its mesher.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace surfcomp::molsurf::detail {

/// Integer node coordinates (i, j, k); the node lies at (i, j, k) * spacing.
using GridCoord = std::array<int, 3>;

/// A hash of grid coordinates for unordered containers.
struct GridCoordHash {
  std::size_t operator()(const GridCoord& c) const {
    const auto x = static_cast<std::uint64_t>(static_cast<std::uint32_t>(c[0]));
    const auto y = static_cast<std::uint64_t>(static_cast<std::uint32_t>(c[1]));
    const auto z = static_cast<std::uint64_t>(static_cast<std::uint32_t>(c[2]));
    return static_cast<std::size_t>((x * 0x9E3779B97F4A7C15ULL) ^ (y * 0xC2B2AE3D27D4EB4FULL) ^
                                    (z * 0x165667B19E3779F9ULL));
  }
};

/// Values at the nodes of the integer lattice, stored in blocks of 8 x 8 x 8 nodes keyed by
/// block coordinate (node >> 3). A node never written holds the background value; a block
/// written as a whole holds one value for all its nodes until a node in it is set. Reads are
/// safe from several threads; writes are not.
class SparseGrid {
 public:
  static constexpr int block_log2 = 3;
  static constexpr int block_width = 1 << block_log2;  ///< nodes per block side
  static constexpr int block_nodes = block_width * block_width * block_width;

  /// One block: either uniform (every node holds `uniform_value`) or dense (`values`, node
  /// (i, j, k) of the block at index (i * 8 + j) * 8 + k).
  struct Block {
    bool uniform = true;
    float uniform_value = 0.0F;
    std::vector<float> values;
    float at(int i, int j, int k) const { return uniform ? uniform_value : values[index(i, j, k)]; }
    /// The index in `values` of node (i, j, k) of the block.
    static std::size_t index(int i, int j, int k) {
      constexpr auto w = static_cast<std::size_t>(block_width);
      return (static_cast<std::size_t>(i) * w + static_cast<std::size_t>(j)) * w +
             static_cast<std::size_t>(k);
    }
  };

  explicit SparseGrid(float background) : background_(background) {}

  float background() const { return background_; }

  /// Sets node `node` to `value`.
  void set(const GridCoord& node, float value);

  /// Sets every node of the cube [origin, origin + size)^3 to `value`; size >= 1.
  void fill(const GridCoord& origin, int size, float value);

  /// The value at `node`: the one set, filled or the background.
  float value(const GridCoord& node) const;

  /// The block holding `node`, and the node's position (i, j, k) in it.
  static GridCoord block_of(const GridCoord& node);
  static GridCoord offset_in_block(const GridCoord& node);

  /// The block with block coordinate `block`, or nullptr when nothing in it was written.
  const Block* find_block(const GridCoord& block) const;

  /// The coordinates of the stored blocks, in the order they were first written.
  const std::vector<GridCoord>& block_coords() const { return block_coords_; }

 private:
  Block& block_for_write(const GridCoord& block);
  static void make_dense(Block& block);

  float background_;
  std::unordered_map<GridCoord, std::size_t, GridCoordHash> index_;  ///< block coord -> blocks_
  std::vector<Block> blocks_;
  std::vector<GridCoord> block_coords_;
  std::size_t last_written_ = 0;  ///< blocks_ index of the last write, tried first
};

}  // namespace surfcomp::molsurf::detail
