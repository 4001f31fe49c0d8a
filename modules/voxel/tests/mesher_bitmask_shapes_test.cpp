// Whole-chunk shapes that take the bitmask mesher's shortcuts (issue #18): the all-air scan,
// slabs of only empty and full rows (transpose skipped), rows whose only AO work is on their
// edge bits, and widths that are not a multiple of 16 (overlapping tail loads). Each must give
// exactly the reference surface (face_visible / face_ao, face by face).

#include <sylva/voxel/mesher.hpp>

#include <gtest/gtest.h>

#include <cstdlib>
#include <functional>
#include <string>

#include "support/test_chunks.hpp"

namespace sylva::voxel {
namespace {

using testing::FaceCoverage;

// Same unit faces, blocks, AO and lists as the reference; returns the bitmask mesh.
ChunkMesh expect_reference(const PaddedBlocks& blocks, const std::string& what) {
  const auto& palette = testing::test_palette();
  ChunkMesh mesh;
  make_mesher(MesherKind::kBitmask)->mesh(blocks, palette, mesh);
  const FaceCoverage want = testing::reference_coverage(blocks, palette);
  const FaceCoverage got = testing::coverage_of(mesh, blocks.n);
  std::size_t mismatches = 0;
  for (std::size_t k = 0; k < want.count.size(); ++k) {
    const bool same = want.count[k] == got.count[k] &&
                      (want.count[k] == 0 || (want.block[k] == got.block[k] && want.ao[k] == got.ao[k] &&
                                              want.list[k] == got.list[k]));
    mismatches += same ? 0 : 1;
  }
  EXPECT_EQ(mismatches, 0u) << what;
  return mesh;
}

// Fills the padded volume: f(x, y, z) for x, y, z in [-1, n].
PaddedBlocks fill(int n, const std::function<BlockId(int, int, int)>& f) {
  PaddedBlocks b(n);
  for (int y = -1; y <= n; ++y)
    for (int z = -1; z <= n; ++z)
      for (int x = -1; x <= n; ++x) b.set(x, y, z, f(x, y, z));
  return b;
}

bool inside(int n, int x, int y, int z) { return x >= 0 && y >= 0 && z >= 0 && x < n && y < n && z < n; }

constexpr int kSizes[] = {1, 7, 8, 9, 17, 33, 47, 62, 64};

TEST(MesherBitmaskShapes, EmptyChunkWithAnyRingHasNoQuads) {
  for (int n : kSizes) {
    // Stone and glass in the ring only: nothing of the chunk itself to draw.
    const PaddedBlocks b = fill(n, [n](int x, int y, int z) -> BlockId {
      return inside(n, x, y, z) ? kAir : static_cast<BlockId>(((x + y + z) & 1) ? 1 : 5);
    });
    EXPECT_TRUE(expect_reference(b, "ring only n=" + std::to_string(n)).empty()) << n;
  }
}

TEST(MesherBitmaskShapes, OneBlockAnywhereInAnEmptyChunkIsFound) {
  // The all-air scan must look at every block: the last one of each row, the last row, the
  // overlapping tail of rows whose width is not a multiple of 8.
  for (int n : kSizes) {
    for (int c = 0; c < 8; ++c) {
      const int bx = (c & 1) ? n - 1 : 0, by = (c & 2) ? n - 1 : 0, bz = (c & 4) ? n - 1 : 0;
      const PaddedBlocks b = fill(n, [&](int x, int y, int z) -> BlockId {
        return x == bx && y == by && z == bz ? 1 : kAir;
      });
      const ChunkMesh mesh = expect_reference(b, "corner " + std::to_string(c) + " n=" + std::to_string(n));
      EXPECT_EQ(mesh.quad_count(), 6u) << "n=" << n << " corner " << c;
    }
    if (n >= 3) {
      const PaddedBlocks b = fill(n, [n](int x, int y, int z) -> BlockId {
        return x == n - 2 && y == n / 2 && z == 1 ? 4 : kAir;  // leaves, alpha-cut
      });
      EXPECT_EQ(expect_reference(b, "alpha n=" + std::to_string(n)).alpha_cut.size(), 6u) << n;
    }
  }
}

TEST(MesherBitmaskShapes, SolidChunksAndFlatFloorsMatchTheReference) {
  for (int n : kSizes) {
    const std::string size = " n=" + std::to_string(n);
    // Solid with an air ring: one quad per side (AO open: the ring is air).
    const PaddedBlocks solid = fill(n, [n](int x, int y, int z) -> BlockId { return inside(n, x, y, z) ? 1 : kAir; });
    EXPECT_EQ(expect_reference(solid, "solid" + size).quad_count(), 6u) << n;
    // Solid with a patchy ring: AO on the chunk's sides comes from the ring.
    const PaddedBlocks patchy = fill(n, [n](int x, int y, int z) -> BlockId {
      return inside(n, x, y, z) || ((x * 7 + y * 3 + z * 5) % 4 == 0) ? 1 : kAir;
    });
    expect_reference(patchy, "solid, patchy ring" + size);
    // Flat floors of several heights, with and without a ring of stone beside them.
    for (int h : {1, n / 2, n - 1}) {
      const PaddedBlocks floor = fill(n, [h](int, int y, int) -> BlockId { return y < h ? 2 : kAir; });
      expect_reference(floor, "floor " + std::to_string(h) + size);
      const PaddedBlocks walled = fill(n, [n, h](int x, int y, int z) -> BlockId {
        return y < h || !inside(n, x, 0, z) ? 2 : kAir;
      });
      expect_reference(walled, "walled floor " + std::to_string(h) + size);
    }
  }
}

TEST(MesherBitmaskShapes, TwoBlocksMergeTheirSidesAlongEveryAxis) {
  // Faces with no neighbour in their slice are written as unit quads without merging; a face
  // with one beside it (same row, or the row before or after) must still merge: two blocks side
  // by side give 4 side quads of 2 faces and 2 end quads, with AO on or off, in the middle of
  // the chunk and on its edge bits.
  for (bool ao : {true, false}) {
    MesherOptions options;
    options.ambient_occlusion = ao;
    for (int n : {8, 17, 62}) {
      for (int axis = 0; axis < 3; ++axis) {
        for (int at : {0, n / 2, n - 2}) {
          const PaddedBlocks b = fill(n, [&](int x, int y, int z) -> BlockId {
            const int c[3] = {x, y, z};
            const int o1 = (axis + 1) % 3, o2 = (axis + 2) % 3;
            return (c[axis] == at || c[axis] == at + 1) && c[o1] == n / 3 && c[o2] == at ? 1 : kAir;
          });
          ChunkMesh mesh;
          make_mesher(MesherKind::kBitmask, options)->mesh(b, testing::test_palette(), mesh);
          EXPECT_EQ(mesh.quad_count(), 6u) << "ao " << ao << " n=" << n << " axis " << axis << " at " << at;
          if (ao) expect_reference(b, "pair n=" + std::to_string(n));
        }
      }
    }
  }
}

TEST(MesherBitmaskShapes, RandomChunksOfEveryWidthMatchTheReference) {
  // Widths around the 16- and 32-block steps of the row classification.
  for (int n : {15, 16, 17, 31, 47, 48, 49, 62}) {
    for (auto pattern : {testing::Pattern::kMixedAlpha, testing::Pattern::kTerrain}) {
      expect_reference(testing::make_pattern(pattern, n, 7),
                       testing::to_string(pattern) + " n=" + std::to_string(n));
    }
  }
}

TEST(MesherBitmaskShapes, WithoutAoEveryWidthCoversLikeTheCulledMesher) {
  // Without AO open rows go in runs of one block id (the same-id masks of a row, whose last
  // group overlaps the one before for widths that are not a multiple of 16).
  const auto& palette = testing::test_palette();
  MesherOptions off;
  off.ambient_occlusion = false;
  for (int n : {15, 17, 47, 62, 63}) {
    for (auto pattern : {testing::Pattern::kRandom, testing::Pattern::kMixedAlpha, testing::Pattern::kTerrain}) {
      const PaddedBlocks blocks = testing::make_pattern(pattern, n, 5);
      ChunkMesh reference, mesh;
      make_mesher(MesherKind::kCulled, off)->mesh(blocks, palette, reference);
      make_mesher(MesherKind::kBitmask, off)->mesh(blocks, palette, mesh);
      const FaceCoverage want = testing::coverage_of(reference, n);
      const FaceCoverage got = testing::coverage_of(mesh, n);
      const std::string what = testing::to_string(pattern) + " n=" + std::to_string(n);
      EXPECT_EQ(got.count, want.count) << what;
      EXPECT_EQ(got.block, want.block) << what;
      EXPECT_EQ(got.list, want.list) << what;
    }
  }
}

// Meshes the one-id chunk shape(n) and the same chunk with one stone block of another id buried
// at (n / 2, 0, n / 2) (no face of its own, AO unchanged: the general path, ids read), with AO
// on and off, on both row passes, sizes 9-64: the quads must be the same, in the same order.
// more(ao, one, single mesh, what) adds the caller's checks.
void expect_one_id_path_like_general(
    const std::function<PaddedBlocks(int)>& shape,
    const std::function<void(bool, const PaddedBlocks&, const ChunkMesh&, const std::string&)>& more) {
  const auto& palette = testing::test_palette();
  for (bool avx2 : {true, false}) {
    if (!avx2) {
      ASSERT_EQ(setenv("SYLVA_VOXEL_NO_AVX2", "1", 1), 0);
    }
    for (bool ao : {true, false}) {
      MesherOptions options;
      options.ambient_occlusion = ao;
      for (int n : {9, 17, 33, 62, 64}) {
        const PaddedBlocks one = shape(n);
        PaddedBlocks two = one;
        two.set(n / 2, 0, n / 2, 2);
        ChunkMesh single, general;
        make_mesher(MesherKind::kBitmask, options)->mesh(one, palette, single);
        make_mesher(MesherKind::kBitmask, options)->mesh(two, palette, general);
        const std::string what = "avx2 " + std::to_string(avx2) + " ao " + std::to_string(ao) + " n=" + std::to_string(n);
        EXPECT_EQ(single.opaque, general.opaque) << what;
        EXPECT_EQ(single.alpha_cut, general.alpha_cut) << what;
        more(ao, one, single, what);
      }
    }
    unsetenv("SYLVA_VOXEL_NO_AVX2");
  }
}

TEST(MesherBitmaskShapes, OneBlockIdChunksGiveTheQuadsOfTheGeneralPath) {
  // A chunk holding one plain block id (air aside) groups its faces without reading ids: hills
  // against the general path. One alpha-cut or sides-only id keeps the general path.
  auto height = [](int n, int x, int z) { return 2 + ((x + 1) * 7 + (z + 1) * 5 + (x + 1) * (z + 1)) % (n - 2); };
  auto hills = [&](int n, BlockId id) {
    return fill(n, [&](int x, int y, int z) -> BlockId { return y < height(n, x, z) ? id : kAir; });
  };
  expect_one_id_path_like_general([&](int n) { return hills(n, 1); },
                                  [&](bool ao, const PaddedBlocks& one, const ChunkMesh& single, const std::string& what) {
                                    EXPECT_FALSE(single.empty()) << what;
                                    if (!ao) return;
                                    expect_reference(one, "one id " + what);
                                    for (BlockId id : {BlockId{4}, BlockId{7}}) {
                                      expect_reference(hills(one.n, id), "one id " + std::to_string(id) + " " + what);
                                    }
                                  });
}

TEST(MesherBitmaskShapes, OneBlockIdCheckerboardWritesItsAloneFacesLikeTheGeneralPath) {
  // A one-id chunk writes the faces that can merge with nothing (no face beside them in their
  // slice) as unit quads without reading their ids: a 3D checkerboard over a stone floor (every
  // checker face alone) against the general path.
  expect_one_id_path_like_general(
      [](int n) { return fill(n, [](int x, int y, int z) -> BlockId { return y < 2 || ((x + y + z) & 1) ? 1 : kAir; }); },
      [](bool, const PaddedBlocks& one, const ChunkMesh& single, const std::string& what) {
        EXPECT_GT(single.opaque.size(), static_cast<std::size_t>(one.n * one.n)) << what;
        EXPECT_TRUE(single.alpha_cut.empty()) << what;
      });
}

TEST(MesherBitmaskShapes, OccludedRowsSplitOpenFacesFromTheTableOnes) {
  // With AO on, a row with something opaque in front sends only the faces with an opaque block
  // around them through the AO table; the open ones that may merge go to their slot at once.
  // A stone floor under a half of pillars at odd (x, z): its top faces at even (x, z) see only
  // diagonal pillars (uniform AO 2: they take the slot path after the table), the others
  // corner-varying AO (unit quads), and the half without pillars is open and merges, in the
  // same rows. One id (no id reads) and two ids (a buried block, no face of its own) must give
  // the same quads in the same order, and the reference surface.
  for (int n : {9, 17, 33, 62, 64}) {
    const PaddedBlocks one = fill(n, [n](int x, int y, int z) -> BlockId {
      const bool pillar = y == 2 && x < n / 2 && (x & 1) && (z & 1);
      return y < 2 || pillar ? 1 : kAir;
    });
    PaddedBlocks two = one;
    two.set(n / 2, 0, n / 2, 2);
    const ChunkMesh single = expect_reference(one, "one id n=" + std::to_string(n));
    const ChunkMesh general = expect_reference(two, "two ids n=" + std::to_string(n));
    EXPECT_EQ(single.opaque, general.opaque) << n;
    EXPECT_TRUE(single.alpha_cut.empty() && general.alpha_cut.empty()) << n;
    // The open half's top faces merge: fewer quads than the floor has unit top faces.
    EXPECT_LT(single.opaque.size(), static_cast<std::size_t>(n * n)) << n;
  }
}

TEST(MesherBitmaskShapes, MixedIdHillsCoverLikeTheReferenceWithAoOnAndOff) {
  // Hills of stone under dirt under a grass top: their +-X faces merge more than they stay unit
  // quads, so the +-Z slices are meshed with rows along x (bits along y) instead of along y.
  // Same surface, blocks and AO either way: against the reference with AO and against the
  // culled mesher without.
  const auto& palette = testing::test_palette();
  MesherOptions off;
  off.ambient_occlusion = false;
  for (int n : {17, 33, 62, 64}) {
    const PaddedBlocks hills = fill(n, [n](int x, int y, int z) -> BlockId {
      const int h = n / 3 + ((x + 1) * 3 + (z + 1) * 2) % (n / 2) - ((x + 1) / 5) % 3;
      return y < h - 4 ? 1 : y < h - 1 ? 2 : y < h ? 3 : kAir;
    });
    const std::string what = "n=" + std::to_string(n);
    expect_reference(hills, "ao " + what);
    ChunkMesh reference, mesh;
    make_mesher(MesherKind::kCulled, off)->mesh(hills, palette, reference);
    make_mesher(MesherKind::kBitmask, off)->mesh(hills, palette, mesh);
    const FaceCoverage want = testing::coverage_of(reference, n);
    const FaceCoverage got = testing::coverage_of(mesh, n);
    EXPECT_EQ(got.count, want.count) << what;
    EXPECT_EQ(got.block, want.block) << what;
    EXPECT_EQ(got.list, want.list) << what;
    EXPECT_LT(mesh.quad_count(), reference.quad_count()) << what;
  }
}

// A quad of `list` with block `id` on face `face` (+Y 2 or -Y 3) covers the unit face at (x, y,
// z) (+-Y quads: du along z, dv along x).
bool covers_y_face(const std::vector<PackedQuad>& list, BlockId id, std::uint32_t face, int x, int y, int z) {
  for (const PackedQuad& q : list) {
    const auto w = [&q](int shift, std::uint32_t mask) { return static_cast<int>((q.word0 >> shift) & mask); };
    if ((q.word1 & 0xffffu) != id || ((q.word1 >> 16) & 7u) != face || w(6, 63) != y) continue;
    if (x >= w(0, 63) && x <= w(0, 63) + w(24, 63) && z >= w(12, 63) && z <= w(12, 63) + w(18, 63)) return true;
  }
  return false;
}

TEST(MesherBitmaskShapes, OneLeavesOrDirtBlockAtAnyBitOfAStoneRowIsFound) {
  // The row pass looks closer at ids >= the first alpha-cut id only in rows that hold one, and
  // tells one-id chunks by the OR of the ids against the AND of the ids minus one (issue #18).
  // Two stone layers, one block of the lower replaced by leaves (alpha-cut: the stone above it
  // shows its bottom face) or dirt (shows its own bottom face), at every x: on both row passes
  // (every 16- and 32-id group, the overlapping last ones too). Then, on grass in a stone
  // ring, the block in the upper layer shows its top face with its own id: every group of the
  // chunk's own rows must reach the one-id test (dirt missed there makes it a grass chunk).
  const auto& palette = testing::test_palette();
  for (bool avx2 : {true, false}) {
    if (!avx2) {
      ASSERT_EQ(setenv("SYLVA_VOXEL_NO_AVX2", "1", 1), 0);
    }
    auto mesher = make_mesher(MesherKind::kBitmask);
    for (int n : {16, 17, 31, 32, 33, 47, 62, 63, 64}) {
      for (BlockId id : {BlockId{4}, BlockId{2}}) {
        for (int bx = 0; bx < n; ++bx) {
          const int bz = (bx * 7) % n;
          const PaddedBlocks b = fill(n, [&](int x, int y, int z) -> BlockId {
            if (!inside(n, x, y, z) || y > 1) return kAir;
            return x == bx && y == 0 && z == bz ? id : 1;
          });
          ChunkMesh mesh;
          mesher->mesh(b, palette, mesh);
          const std::string what = "avx2 " + std::to_string(avx2) + " id " + std::to_string(id) +
                                   " n=" + std::to_string(n) + " x=" + std::to_string(bx);
          if (id == 4) {
            EXPECT_TRUE(covers_y_face(mesh.alpha_cut, 4, 3, bx, 0, bz)) << what;
            EXPECT_TRUE(covers_y_face(mesh.opaque, 1, 3, bx, 1, bz)) << what;
          } else {
            EXPECT_TRUE(covers_y_face(mesh.opaque, 2, 3, bx, 0, bz)) << what;
          }
          const PaddedBlocks ringed = fill(n, [&](int x, int y, int z) -> BlockId {
            if (!inside(n, x, y, z)) return 1;
            if (y > 1) return kAir;
            return x == bx && y == 1 && z == bz ? id : 3;  // grass: 3 - 1 = 2 hides dirt's 2 - 1 = 1
          });
          mesher->mesh(ringed, palette, mesh);
          EXPECT_TRUE(covers_y_face(id == 4 ? mesh.alpha_cut : mesh.opaque, id, 2, bx, 1, bz)) << "ring " << what;
        }
      }
    }
    unsetenv("SYLVA_VOXEL_NO_AVX2");
  }
}

TEST(MesherBitmaskShapes, Avx2AndSse2RowPassesGiveTheSameMesh) {
  // The row pass runs AVX2 where the CPU has it (dispatch when the mesher is made) and SSE2
  // with SYLVA_VOXEL_NO_AVX2 set: both must give the same quads, in the same order.
  const auto& palette = testing::test_palette();
  for (int n : {32, 33, 47, 62, 63, 64}) {
    for (auto pattern : {testing::Pattern::kMixedAlpha, testing::Pattern::kTerrain, testing::Pattern::kRandom}) {
      const PaddedBlocks blocks = testing::make_pattern(pattern, n, 9);
      ChunkMesh dispatched, baseline;
      make_mesher(MesherKind::kBitmask)->mesh(blocks, palette, dispatched);
      ASSERT_EQ(setenv("SYLVA_VOXEL_NO_AVX2", "1", 1), 0);
      make_mesher(MesherKind::kBitmask)->mesh(blocks, palette, baseline);
      unsetenv("SYLVA_VOXEL_NO_AVX2");
      const std::string what = testing::to_string(pattern) + " n=" + std::to_string(n);
      EXPECT_EQ(dispatched.opaque, baseline.opaque) << what;
      EXPECT_EQ(dispatched.alpha_cut, baseline.alpha_cut) << what;
      EXPECT_FALSE(dispatched.empty()) << what;
    }
  }
}

}  // namespace
}  // namespace sylva::voxel
