#pragma once
// Test chunk contents shared by the voxel tests: random, terrain-like, checkerboard, empty, full.

#include <sylva/voxel/block.hpp>
#include <sylva/voxel/mesher.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace sylva::voxel::testing {

enum class Pattern { kRandom, kTerrain, kCheckerboard, kEmpty, kFull, kMixedAlpha };
std::string to_string(Pattern p);
inline const Pattern kAllPatterns[] = {Pattern::kRandom, Pattern::kTerrain, Pattern::kCheckerboard,
                                       Pattern::kEmpty, Pattern::kFull, Pattern::kMixedAlpha};

// A small palette: stone, dirt, grass (opaque), leaves (alpha-cut, keeps same faces),
// glass (alpha-cut, culls same faces), lamp (opaque, emissive), tuft (alpha-cut, sides only).
const BlockPalette& test_palette();

// Fills the whole padded volume (ring included, so border faces and AO are exercised).
PaddedBlocks make_pattern(Pattern p, int n, std::uint64_t seed);

// Per unit face (x, y, z, face) of an n^3 chunk: how many quads cover it, and the block, AO and
// list (0 opaque, 1 alpha-cut) of the covering quad.
struct FaceCoverage {
  int n = 0;
  std::vector<std::uint8_t> count;
  std::vector<std::uint16_t> block;
  std::vector<std::uint8_t> ao;
  std::vector<std::uint8_t> list;
  std::size_t index(int x, int y, int z, int face) const {
    return static_cast<std::size_t>(((y * n + z) * n + x) * 6 + face);
  }
};
FaceCoverage coverage_of(const ChunkMesh& mesh, int n);
// The coverage the definitions (face_visible, face_ao) demand, computed face by face.
FaceCoverage reference_coverage(const PaddedBlocks& blocks, const BlockPalette& palette);

}  // namespace sylva::voxel::testing
