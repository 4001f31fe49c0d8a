#include <sylva/voxel/chunk.hpp>

#include <sylva/core/assert.hpp>

#include <algorithm>

namespace sylva::voxel {

namespace {
void check_local(int x, int y, int z) {
  SYLVA_ASSERT(x >= 0 && x < kChunkSize && y >= 0 && y < kChunkSize && z >= 0 && z < kChunkSize,
               "local block ({}, {}, {}) outside [0, {})", x, y, z, kChunkSize);
}
}  // namespace

BlockId Chunk::get(int x, int y, int z) const {
  check_local(x, y, z);
  return blocks_.empty() ? uniform_ : blocks_[static_cast<std::size_t>(local_index(x, y, z))];
}

bool Chunk::set(int x, int y, int z, BlockId id) {
  check_local(x, y, z);
  if (blocks_.empty()) {
    if (id == uniform_) return false;
    blocks_.assign(kChunkVolume, uniform_);
  }
  BlockId& slot = blocks_[static_cast<std::size_t>(local_index(x, y, z))];
  if (slot == id) return false;
  slot = id;
  ++revision_;
  return true;
}

std::span<BlockId> Chunk::dense() {
  if (blocks_.empty()) blocks_.assign(kChunkVolume, uniform_);
  return blocks_;
}

void Chunk::copy_to(std::span<BlockId> out) const {
  SYLVA_ASSERT(out.size() == static_cast<std::size_t>(kChunkVolume), "copy_to needs {} ids, got {}", kChunkVolume,
               out.size());
  if (blocks_.empty()) {
    std::fill(out.begin(), out.end(), uniform_);
  } else {
    std::copy(blocks_.begin(), blocks_.end(), out.begin());
  }
}

void Chunk::compact() {
  if (blocks_.empty()) return;
  const BlockId first = blocks_.front();
  if (std::all_of(blocks_.begin(), blocks_.end(), [first](BlockId b) { return b == first; })) {
    uniform_ = first;
    blocks_.clear();
    blocks_.shrink_to_fit();
  }
}

}  // namespace sylva::voxel
