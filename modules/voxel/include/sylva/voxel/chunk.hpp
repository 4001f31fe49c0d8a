#pragma once
// Chunk: kChunkSize^3 block ids. A chunk filled with a single block (all air, all stone) keeps
// only that id and allocates the dense array on its first differing write, so the empty sky and
// solid rock under a world cost almost nothing.

#include <sylva/voxel/block.hpp>
#include <sylva/voxel/coords.hpp>

#include <span>
#include <vector>

namespace sylva::voxel {

class Chunk {
 public:
  Chunk() = default;
  explicit Chunk(BlockId fill) : uniform_(fill) {}

  // x, y, z in [0, kChunkSize) (asserted).
  BlockId get(int x, int y, int z) const;
  // Returns true when the stored id changed.
  bool set(int x, int y, int z, BlockId id);

  bool is_uniform() const { return blocks_.empty(); }
  // The id of a uniform chunk (meaningless otherwise).
  BlockId uniform_id() const { return uniform_; }
  bool is_empty() const { return blocks_.empty() && uniform_ == kAir; }

  // Dense view (allocates the array if the chunk is uniform). Index with local_index().
  std::span<BlockId> dense();
  // Dense ids or an empty span for a uniform chunk.
  std::span<const BlockId> blocks() const { return blocks_; }
  // Copies all ids into out (kChunkVolume entries) in local_index order.
  void copy_to(std::span<BlockId> out) const;

  // Collapses the dense array back to uniform storage when every id is equal.
  void compact();

  // Bumped on every change; meshes remember the revision they were built from.
  std::uint64_t revision() const { return revision_; }
  void touch() { ++revision_; }

 private:
  std::vector<BlockId> blocks_;
  BlockId uniform_ = kAir;
  std::uint64_t revision_ = 0;
};

}  // namespace sylva::voxel
