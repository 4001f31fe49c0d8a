#pragma once
// World, chunk and local block coordinates. The world is unbounded: block and chunk coordinates
// are int64, so nothing overflows within +-2^62 blocks (y is up; chunks tile all three axes;
// the seed laid chunks on the x-z plane only, §1.2, which cannot hold caves or tall trees that
// cross a chunk's top). Rendering subtracts a double-precision camera origin (camera-relative),
// so far-away chunks keep float precision on the GPU.

#include <cstdint>
#include <functional>

namespace sylva::voxel {

// Edge length of a world chunk in blocks. 32 keeps a padded chunk (34 wide) inside one 64-bit
// column mask for the bitmask mesher and a chunk at 64 KiB of block ids.
inline constexpr int kChunkShift = 5;
inline constexpr int kChunkSize = 1 << kChunkShift;
inline constexpr int kChunkVolume = kChunkSize * kChunkSize * kChunkSize;

struct BlockPos {
  std::int64_t x = 0, y = 0, z = 0;
  bool operator==(const BlockPos&) const = default;
};

struct ChunkCoord {
  std::int64_t x = 0, y = 0, z = 0;
  bool operator==(const ChunkCoord&) const = default;
  auto operator<=>(const ChunkCoord&) const = default;
  ChunkCoord offset(int dx, int dy, int dz) const { return {x + dx, y + dy, z + dz}; }
};

// Floor division by the chunk size (arithmetic shift is well defined for negative values in C++20).
constexpr ChunkCoord chunk_of(const BlockPos& p) {
  return {p.x >> kChunkShift, p.y >> kChunkShift, p.z >> kChunkShift};
}
// Local coordinate in [0, kChunkSize).
constexpr int local_of(std::int64_t v) { return static_cast<int>(v & (kChunkSize - 1)); }
constexpr BlockPos chunk_origin(const ChunkCoord& c) {
  return {c.x * kChunkSize, c.y * kChunkSize, c.z * kChunkSize};
}

// Index of a local block inside a chunk: x fastest, then z, then y (horizontal slabs).
constexpr int local_index(int x, int y, int z) { return x + kChunkSize * (z + kChunkSize * y); }

struct ChunkCoordHash {
  std::size_t operator()(const ChunkCoord& c) const {
    // splitmix64-style mixing of the three coordinates.
    auto mix = [](std::uint64_t v) {
      v += 0x9e3779b97f4a7c15ULL;
      v = (v ^ (v >> 30)) * 0xbf58476d1ce4e5b9ULL;
      v = (v ^ (v >> 27)) * 0x94d049bb133111ebULL;
      return v ^ (v >> 31);
    };
    return static_cast<std::size_t>(mix(static_cast<std::uint64_t>(c.x) ^
                                        mix(static_cast<std::uint64_t>(c.y) ^ mix(static_cast<std::uint64_t>(c.z)))));
  }
};

}  // namespace sylva::voxel
