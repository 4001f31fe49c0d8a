// The bitmask mesher's AO-off merge for chunks of plain opaque blocks (issue #18): rectangles
// taken straight from a slice's face rows with the block ids compared in place, instead of per-id
// slot planes. It must give the same set of quads as the slot planes (same faces, same ids, same
// count), only in another order, on every benchmark content and chunk size, on both row passes.

#include <sylva/voxel/mesher.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include "../bench/bench_chunks.hpp"
#include "support/test_chunks.hpp"

namespace sylva::voxel {
namespace {

// The standard palette with an alpha-cut block put in front as id 1 (every other id one higher).
// A chunk whose ids are shifted to match holds no id-1 block, so it has the same faces, but the
// mesher sees an alpha-cut id among those up to its ids' OR and keeps the slot planes.
BlockPalette shifted_palette() {
  const BlockPalette& standard = BlockPalette::standard();
  BlockPalette shifted;
  BlockType dummy;
  dummy.name = "test_alpha_cut_front";
  dummy.render = RenderClass::kAlphaCut;
  EXPECT_TRUE(shifted.add(dummy).ok());
  for (std::size_t id = 1; id < standard.size(); ++id) EXPECT_TRUE(shifted.add(standard[static_cast<BlockId>(id)]).ok());
  return shifted;
}

// Quads in one order, block ids moved down by `shift` (word1's low 16 bits).
std::vector<PackedQuad> sorted(std::vector<PackedQuad> quads, std::uint32_t shift) {
  for (PackedQuad& q : quads) q.word1 -= shift;
  std::sort(quads.begin(), quads.end(),
            [](const PackedQuad& a, const PackedQuad& b) { return a.word0 != b.word0 ? a.word0 < b.word0 : a.word1 < b.word1; });
  return quads;
}

TEST(MesherBitmaskMerge, WithoutAoEveryBenchContentGivesTheQuadsOfTheSlotPlanes) {
  const BlockPalette& standard = BlockPalette::standard();
  const BlockPalette shifted = shifted_palette();
  MesherOptions off;
  off.ambient_occlusion = false;
  for (bool avx2 : {true, false}) {
    if (!avx2) {
      ASSERT_EQ(setenv("SYLVA_VOXEL_NO_AVX2", "1", 1), 0);
    }
    auto mesher = make_mesher(MesherKind::kBitmask, off);
    for (int c = 0; c < bench::kContentCount; ++c) {
      const auto content = static_cast<bench::Content>(c);
      for (int n = 5; n <= 64; ++n) {
        // The row passes give the same masks (Avx2AndSse2RowPassesGiveTheSameMesh): the SSE2 one
        // at a few sizes only, to keep the test short.
        if (!avx2 && n != 5 && n != 16 && n != 33 && n != 62 && n != 63 && n != 64) continue;
        const PaddedBlocks blocks = bench::make_content(content, n);
        PaddedBlocks moved = blocks;
        for (BlockId& id : moved.ids) id = id == kAir ? kAir : static_cast<BlockId>(id + 1);
        ChunkMesh direct, planes;
        mesher->mesh(blocks, standard, direct);
        mesher->mesh(moved, shifted, planes);
        const std::string what =
            "avx2 " + std::to_string(avx2) + " " + bench::content_name(content) + " n=" + std::to_string(n);
        EXPECT_EQ(sorted(direct.opaque, 0), sorted(planes.opaque, 1)) << what;
        EXPECT_EQ(sorted(direct.alpha_cut, 0), sorted(planes.alpha_cut, 1)) << what;
        if (avx2 && (n == 5 || n == 33 || n == 62 || n == 64)) {
          // And the faces of the culled mesher, one quad per face, with their blocks.
          ChunkMesh culled;
          make_mesher(MesherKind::kCulled, off)->mesh(blocks, standard, culled);
          const testing::FaceCoverage want = testing::coverage_of(culled, n);
          const testing::FaceCoverage got = testing::coverage_of(direct, n);
          EXPECT_EQ(got.count, want.count) << what;
          EXPECT_EQ(got.block, want.block) << what;
        }
      }
    }
    unsetenv("SYLVA_VOXEL_NO_AVX2");
  }
}

}  // namespace
}  // namespace sylva::voxel
