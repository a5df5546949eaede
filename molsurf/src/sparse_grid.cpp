#include "sparse_grid.hpp"

#include <algorithm>

namespace surfcomp::molsurf::detail {
namespace {

/// floor(c / block_width), for negative c too.
int floor_div(int c) {
  return c >= 0 ? c / SparseGrid::block_width : -((-(c + 1)) / SparseGrid::block_width) - 1;
}

}  // namespace

GridCoord SparseGrid::block_of(const GridCoord& node) {
  return {floor_div(node[0]), floor_div(node[1]), floor_div(node[2])};
}

GridCoord SparseGrid::offset_in_block(const GridCoord& node) {
  const GridCoord block = block_of(node);
  return {node[0] - block_width * block[0], node[1] - block_width * block[1],
          node[2] - block_width * block[2]};
}

const SparseGrid::Block* SparseGrid::find_block(const GridCoord& block) const {
  const auto it = index_.find(block);
  return it == index_.end() ? nullptr : &blocks_[it->second];
}

SparseGrid::Block& SparseGrid::block_for_write(const GridCoord& block) {
  if (!blocks_.empty() && block_coords_[last_written_] == block) return blocks_[last_written_];
  const auto [it, inserted] = index_.try_emplace(block, blocks_.size());
  if (inserted) {
    Block fresh;
    fresh.uniform_value = background_;
    blocks_.push_back(std::move(fresh));
    block_coords_.push_back(block);
  }
  last_written_ = it->second;
  return blocks_[it->second];
}

void SparseGrid::make_dense(Block& block) {
  if (!block.uniform) return;
  block.values.assign(block_nodes, block.uniform_value);
  block.uniform = false;
}

void SparseGrid::set(const GridCoord& node, float value) {
  Block& block = block_for_write(block_of(node));
  make_dense(block);
  const GridCoord local = offset_in_block(node);
  block.values[Block::index(local[0], local[1], local[2])] = value;
}

void SparseGrid::fill(const GridCoord& origin, int size, float value) {
  const GridCoord last = {origin[0] + size - 1, origin[1] + size - 1, origin[2] + size - 1};
  const GridCoord first_block = block_of(origin);
  const GridCoord last_block = block_of(last);
  for (int bi = first_block[0]; bi <= last_block[0]; ++bi) {
    for (int bj = first_block[1]; bj <= last_block[1]; ++bj) {
      for (int bk = first_block[2]; bk <= last_block[2]; ++bk) {
        const GridCoord base = {bi * block_width, bj * block_width, bk * block_width};
        GridCoord lo{}, hi{};  // the box's nodes in this block, block-local, inclusive
        bool whole = true;
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::max(origin[a], base[a]) - base[a];
          hi[a] = std::min(last[a], base[a] + block_width - 1) - base[a];
          whole = whole && lo[a] == 0 && hi[a] == block_width - 1;
        }
        Block& block = block_for_write({bi, bj, bk});
        if (whole) {
          block.uniform = true;
          block.uniform_value = value;
          block.values.clear();
          continue;
        }
        make_dense(block);
        for (int i = lo[0]; i <= hi[0]; ++i) {
          for (int j = lo[1]; j <= hi[1]; ++j) {
            for (int k = lo[2]; k <= hi[2]; ++k) block.values[Block::index(i, j, k)] = value;
          }
        }
      }
    }
  }
}

float SparseGrid::value(const GridCoord& node) const {
  const Block* block = find_block(block_of(node));
  if (block == nullptr) return background_;
  const GridCoord local = offset_in_block(node);
  return block->at(local[0], local[1], local[2]);
}

}  // namespace surfcomp::molsurf::detail
