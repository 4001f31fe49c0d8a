#pragma once
// Grass tufts and flowers drawn off the block grid. World generation stores them as sides-only
// alpha-cut blocks (seed 004 §1.3's "cube without bases": editable, saved, removed with their
// ground), but drawn as cubes in their cells they stand in exact rows, and merged side faces of
// neighbouring tufts show as long fences. The renderer therefore draws every sides-only block as
// one tuft: two crossed cut-out quads at a position, size, turn and tint hashed from the block's
// world coordinates (the random offset classic voxel games give their plants), so no grid rows
// are visible and the same block always looks the same (deterministic, chunk-border independent).

#include <sylva/voxel/block.hpp>
#include <sylva/voxel/chunk.hpp>
#include <sylva/voxel/coords.hpp>

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace sylva::voxel {

// Largest offset of a tuft's foot from its block's centre along x and z [blocks]. Below 0.5 so a
// tuft never leaves its cell (it cannot stand inside a neighbouring wall).
inline constexpr float kTuftJitter = 0.3f;

struct Tuft {
  glm::vec3 foot;      // bottom centre, chunk-relative [blocks]: block centre + jitter in x/z, block bottom in y
  float height = 1.0f; // [blocks], in [0.55, 1.15]
  float width = 1.0f;  // quad width [blocks], in [0.8, 1.1]
  float yaw = 0.0f;    // turn of the cross about y [radians], in [0, pi/2)
  glm::vec3 tint{1.0f}; // multiplier of the texture colour, each channel in [0.8, 1.1]
  BlockId block = kAir;
};

// Appends one Tuft per sides-only block of `chunk` (chunk coordinate `c`; the hash uses world
// coordinates, so a block's tuft does not depend on the chunk it was meshed in).
void place_tufts(const Chunk& chunk, const ChunkCoord& c, const BlockPalette& palette, std::vector<Tuft>& out);

// The tuft of the sides-only block `block` at world position `p`; its foot is relative to the
// origin of the chunk holding p.
Tuft tuft_at(const BlockPos& p, BlockId block);

}  // namespace sylva::voxel
