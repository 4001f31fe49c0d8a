#pragma once
// Chunk contents for the meshing benchmarks (header-only; benches link only sylva::voxel).

#include <sylva/core/rng.hpp>
#include <sylva/voxel/block.hpp>
#include <sylva/voxel/mesher.hpp>

#include <cmath>

namespace sylva::voxel::bench {

// kTerrain keeps the earlier tables comparable; the kHills*, kEmpty and kSolid cases are the
// ones the side-by-side race with cgerikj/binary-greedy-meshing uses (issue #18, README).
enum class Content { kRandom50, kTerrain, kCheckerboard, kHills1, kHills3, kEmpty, kSolid };
inline constexpr int kContentCount = 7;

inline const char* content_name(Content c) {
  switch (c) {
    case Content::kRandom50: return "random50";
    case Content::kTerrain: return "terrain";
    case Content::kCheckerboard: return "checkerboard";
    case Content::kHills1: return "hills1";
    case Content::kHills3: return "hills3";
    case Content::kEmpty: return "empty";
    case Content::kSolid: return "solid";
  }
  return "?";
}

// Filled with standard-palette blocks: random 50 % stone/dirt; terrain = rolling height field
// of stone, dirt and grass with leaves on top; checkerboard = 3D parity (worst case: every face
// visible, nothing merges); hills = opaque height field (heights 0.13 n .. 0.9 n, 8-56 for
// n = 62) of stone only (hills1) or stone, dirt and a grass top (hills3); empty = all air
// (padding included); solid = stone in the chunk, air in the padding ring (6 visible sides).
inline PaddedBlocks make_content(Content c, int n) {
  const BlockPalette& pal = BlockPalette::standard();
  const BlockId stone = pal.id("stone"), dirt = pal.id("dirt"), grass = pal.id("grass"), leaves = pal.id("oak_leaves");
  PaddedBlocks b(n);
  Pcg32 rng(42, 1);
  for (int y = -1; y <= n; ++y)
    for (int z = -1; z <= n; ++z)
      for (int x = -1; x <= n; ++x) {
        BlockId id = kAir;
        switch (c) {
          case Content::kRandom50:
            if (rng.next_below(2)) id = rng.next_below(4) ? stone : dirt;
            break;
          case Content::kTerrain: {
            const double h = n * (0.5 + 0.18 * std::sin(0.13 * x) * std::cos(0.11 * z) + 0.08 * std::sin(0.37 * (x + z)));
            if (y < h - 4) id = stone;
            else if (y < h - 1) id = dirt;
            else if (y < h) id = grass;
            else if (y < h + 3 && (x % 9) > 5 && (z % 11) > 7) id = leaves;
            break;
          }
          case Content::kCheckerboard:
            if (((x + y + z) & 1) == 0) id = stone;
            break;
          case Content::kHills1:
          case Content::kHills3: {
            const double h =
                n * (0.515 + 0.25 * std::sin(0.21 * x + 0.4) * std::cos(0.17 * z) + 0.135 * std::sin(0.43 * (x - z)));
            if (y < h - 4 || (c == Content::kHills1 && y < h)) id = stone;
            else if (y < h - 1) id = dirt;
            else if (y < h) id = grass;
            break;
          }
          case Content::kEmpty:
            break;
          case Content::kSolid:
            if (x >= 0 && y >= 0 && z >= 0 && x < n && y < n && z < n) id = stone;
            break;
        }
        b.set(x, y, z, id);
      }
  return b;
}

}  // namespace sylva::voxel::bench
