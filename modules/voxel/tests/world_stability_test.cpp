// Stability of storage and meshing at the extremes. Each test names the invariant it checks.

#include <sylva/voxel/region.hpp>
#include <sylva/voxel/world.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <limits>

#include "support/test_chunks.hpp"

namespace sylva::voxel {
namespace {

// Invariant: block <-> chunk <-> local conversion is exact for any int64 coordinate (no overflow,
// floor semantics for negatives), including the extremes of the type.
TEST(VoxelStability, CoordinateConversionExactAtInt64Extremes) {
  const std::int64_t values[] = {0, -1, 31, 32, -32, -33, 1'000'000, -1'000'000, std::int64_t{1} << 40,
                                 std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min()};
  for (std::int64_t v : values) {
    const ChunkCoord c = chunk_of({v, v, v});
    const int l = local_of(v);
    ASSERT_GE(l, 0);
    ASSERT_LT(l, kChunkSize);
    // origin + local == v, computed in unsigned arithmetic to avoid overflow in the check itself.
    EXPECT_EQ(static_cast<std::uint64_t>(c.x) * kChunkSize + static_cast<std::uint64_t>(l), static_cast<std::uint64_t>(v));
  }
}

// Invariant: edits far from the origin (+-1e6 blocks and +-2^60) store, read back, mesh and save
// exactly like edits at the origin.
TEST(VoxelStability, FarFromOriginBehavesLikeOrigin) {
  const auto& palette = testing::test_palette();
  auto mesher = make_mesher(MesherKind::kBitmask);
  const std::int64_t offsets[] = {0, 1'000'000, -1'000'000, std::int64_t{1} << 60, -(std::int64_t{1} << 60)};
  ChunkMesh reference;
  const auto dir = std::filesystem::temp_directory_path() / ("sylva_voxel_far_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  for (std::int64_t o : offsets) {
    World w(palette);
    for (int i = 0; i < 20; ++i) ASSERT_TRUE(w.set({o + i, o + (i * 7) % 13, o - i}, static_cast<BlockId>(1 + i % 3)));
    for (int i = 0; i < 20; ++i) EXPECT_EQ(w.get({o + i, o + (i * 7) % 13, o - i}), 1 + i % 3);
    (void)w.remesh(*mesher);
    const ChunkMesh* m = w.mesh(chunk_of({o, o, o}));
    ASSERT_NE(m, nullptr);
    if (o == 0) reference = *m;
    else EXPECT_EQ(m->opaque, reference.opaque) << "offset " << o;
    RegionStore store(dir, palette);
    const ChunkCoord c = chunk_of({o, o, o});
    const std::vector<std::pair<ChunkCoord, const Chunk*>> list = {{c, w.find(c)}};
    ASSERT_TRUE(store.save(list).ok());
    RegionStore reader(dir, palette);
    auto back = reader.load(c);
    ASSERT_TRUE(back.ok() && back->has_value()) << "offset " << o;
    EXPECT_EQ((*back)->get(local_of(o), local_of(o), local_of(o)), w.get({o, o, o}));
  }
  std::filesystem::remove_all(dir);
}

// Invariant: degenerate chunk contents (1^3 chunks, all alpha-cut, all emissive, a 64^3 chunk
// whose runs span whole 64-bit rows) mesh without asserting and keep the one-quad-per-face rule.
TEST(VoxelStability, DegenerateChunksMeshConsistently) {
  const auto& palette = testing::test_palette();
  for (int n : {1, 2, 64}) {
    for (BlockId fill : {BlockId{4}, BlockId{6}}) {
      PaddedBlocks b(n, kAir);
      for (int y = 0; y < n; ++y)
        for (int z = 0; z < n; ++z)
          for (int x = 0; x < n; ++x) b.set(x, y, z, fill);
      const auto want = testing::reference_coverage(b, palette);
      for (auto kind : {MesherKind::kCulled, MesherKind::kGreedy, MesherKind::kBitmask}) {
        ChunkMesh mesh;
        make_mesher(kind)->mesh(b, palette, mesh);
        const auto got = testing::coverage_of(mesh, n);
        EXPECT_EQ(got.count, want.count) << "n=" << n << " fill=" << fill << " " << to_string(kind);
      }
    }
  }
}

}  // namespace
}  // namespace sylva::voxel
