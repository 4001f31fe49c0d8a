// The bitmask mesher's output buffers: chunks up to 32^3 are written into the mesher's own
// scratch lists and copied into the ChunkMesh at the end; a list passing 4096 quads moves to the
// ChunkMesh mid-way; 64^3 chunks write into the ChunkMesh directly. Invariant checked here: one
// mesher object reused across sizes, contents and ChunkMeshes gives exactly what a fresh mesher
// gives into a fresh ChunkMesh, and covers the reference surface, whichever path each list took.

#include <sylva/voxel/mesher.hpp>

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/test_chunks.hpp"

namespace sylva::voxel {
namespace {

using testing::Pattern;

// 3D parity of one block id: every face visible, nothing merges (3 n^3 quads in one list).
PaddedBlocks checkerboard_of(BlockId id, int n) {
  PaddedBlocks b(n);
  for (int y = -1; y <= n; ++y)
    for (int z = -1; z <= n; ++z)
      for (int x = -1; x <= n; ++x) b.set(x, y, z, ((x + y + z) & 1) == 0 ? id : kAir);
  return b;
}

TEST(MesherBitmaskBuffers, ReusedMesherEqualsFreshMesherOnEveryBufferPath) {
  const auto& palette = testing::test_palette();
  const BlockId leaves = palette.id("leaves");
  struct Case {
    std::string name;
    PaddedBlocks blocks;
  };
  std::vector<Case> cases;
  cases.push_back({"terrain 32", testing::make_pattern(Pattern::kTerrain, 32, 7)});
  // 3 * 32^3 = 98304 alpha-cut quads: the alpha-cut list passes 4096 and moves mid-chunk.
  cases.push_back({"leaf checkerboard 32", checkerboard_of(leaves, 32)});
  cases.push_back({"mixed alpha 31", testing::make_pattern(Pattern::kMixedAlpha, 31, 3)});
  // 3 * 32^3 opaque quads: the opaque list moves mid-chunk.
  cases.push_back({"checkerboard 32", testing::make_pattern(Pattern::kCheckerboard, 32, 1)});
  cases.push_back({"terrain 64 (direct)", testing::make_pattern(Pattern::kTerrain, 64, 2)});
  cases.push_back({"empty 32", testing::make_pattern(Pattern::kEmpty, 32, 1)});
  cases.push_back({"mixed alpha 5", testing::make_pattern(Pattern::kMixedAlpha, 5, 4)});
  cases.push_back({"random 33 (direct)", testing::make_pattern(Pattern::kRandom, 33, 9)});
  cases.push_back({"terrain 32 again", testing::make_pattern(Pattern::kTerrain, 32, 8)});

  auto reused = make_mesher(MesherKind::kBitmask);
  ChunkMesh reused_mesh;  // also reused: holds the previous case's (larger or smaller) result
  for (int round = 0; round < 2; ++round) {
    for (const Case& c : cases) {
      ChunkMesh fresh;
      make_mesher(MesherKind::kBitmask)->mesh(c.blocks, palette, fresh);
      reused->mesh(c.blocks, palette, reused_mesh);
      EXPECT_EQ(reused_mesh.opaque, fresh.opaque) << c.name << " round " << round;
      EXPECT_EQ(reused_mesh.alpha_cut, fresh.alpha_cut) << c.name << " round " << round;
      // A ChunkMesh of its own, meshed by the reused mesher, too.
      ChunkMesh own;
      reused->mesh(c.blocks, palette, own);
      EXPECT_EQ(own.opaque, fresh.opaque) << c.name << " round " << round;
      EXPECT_EQ(own.alpha_cut, fresh.alpha_cut) << c.name << " round " << round;
    }
  }
  // The large cases really took the paths named above, and are the right surface.
  const int n = 32;
  const PaddedBlocks& leaf_board = cases[1].blocks;
  ChunkMesh mesh;
  reused->mesh(leaf_board, palette, mesh);
  EXPECT_EQ(mesh.alpha_cut.size(), 3u * 32u * 32u * 32u);
  EXPECT_TRUE(mesh.opaque.empty());
  const testing::FaceCoverage want = testing::reference_coverage(leaf_board, palette);
  const testing::FaceCoverage got = testing::coverage_of(mesh, n);
  EXPECT_EQ(want.count, got.count);
  EXPECT_EQ(want.block, got.block);
  EXPECT_EQ(want.ao, got.ao);
  EXPECT_EQ(want.list, got.list);
}

}  // namespace
}  // namespace sylva::voxel
