#include <sylva/voxel/tufts.hpp>

#include <sylva/core/rng.hpp>

namespace sylva::voxel {

namespace {

std::uint32_t lo32(std::int64_t v) { return static_cast<std::uint32_t>(static_cast<std::uint64_t>(v)); }
std::uint32_t hi32(std::int64_t v) { return static_cast<std::uint32_t>(static_cast<std::uint64_t>(v) >> 32); }

// Uniform in [0, 1) from 8 bits of a hash.
float byte01(std::uint32_t h, int shift) { return static_cast<float>((h >> shift) & 0xffu) * (1.0f / 256.0f); }

}  // namespace

Tuft tuft_at(const BlockPos& p, BlockId block) {
  // Two independent 32-bit hashes of the world position (a fixed salt: a tuft's look is a
  // property of its place, like the seed's per-position variant choice, §4.7).
  const std::uint32_t a = hash_u32(lo32(p.x), hi32(p.x) ^ lo32(p.y), lo32(p.z), hi32(p.z) ^ 0x74756674u);
  const std::uint32_t b = hash_u32(a, 0x9e3779b9u);
  Tuft t;
  t.block = block;
  const int lx = local_of(p.x), ly = local_of(p.y), lz = local_of(p.z);
  t.foot = glm::vec3(static_cast<float>(lx) + 0.5f + (2.0f * byte01(a, 0) - 1.0f) * kTuftJitter,
                     static_cast<float>(ly),
                     static_cast<float>(lz) + 0.5f + (2.0f * byte01(a, 8) - 1.0f) * kTuftJitter);
  t.height = 0.55f + 0.6f * byte01(a, 16);
  t.width = 0.8f + 0.3f * byte01(a, 24);
  t.yaw = 1.5707963f * byte01(b, 0);
  // Tint: a brightness and a small yellow/green shift, so a meadow is not one flat colour.
  const float bright = 0.85f + 0.25f * byte01(b, 8);
  const float warm = (byte01(b, 16) - 0.5f) * 0.12f;
  t.tint = glm::vec3(bright * (1.0f + warm), bright, bright * (1.0f - warm));
  return t;
}

void place_tufts(const Chunk& chunk, const ChunkCoord& c, const BlockPalette& palette, std::vector<Tuft>& out) {
  const BlockPos o = chunk_origin(c);
  if (chunk.is_uniform()) {
    if (!palette.sides_only(chunk.uniform_id())) return;
    for (int y = 0; y < kChunkSize; ++y)
      for (int z = 0; z < kChunkSize; ++z)
        for (int x = 0; x < kChunkSize; ++x) out.push_back(tuft_at({o.x + x, o.y + y, o.z + z}, chunk.uniform_id()));
    return;
  }
  const auto blocks = chunk.blocks();
  const auto& sides_only = palette.sides_only_table();
  for (int i = 0; i < kChunkVolume; ++i) {
    const BlockId id = blocks[static_cast<std::size_t>(i)];
    if (!sides_only[id]) continue;
    const int x = i % kChunkSize, z = (i / kChunkSize) % kChunkSize, y = i / (kChunkSize * kChunkSize);
    out.push_back(tuft_at({o.x + x, o.y + y, o.z + z}, id));
  }
}

}  // namespace sylva::voxel
