// World storage, padded gathering and the re-meshing invariant: an edit re-meshes exactly the
// chunks whose padded ring holds the block.

#include <sylva/voxel/world.hpp>

#include <gtest/gtest.h>

#include <set>

#include "support/test_chunks.hpp"

namespace sylva::voxel {
namespace {

World make_filled_world(int radius) {
  World w(testing::test_palette());
  for (int cy = -radius; cy <= radius; ++cy)
    for (int cz = -radius; cz <= radius; ++cz)
      for (int cx = -radius; cx <= radius; ++cx) {
        Chunk c;
        auto d = c.dense();
        for (int i = 0; i < kChunkVolume; ++i) d[static_cast<std::size_t>(i)] = (i * 2654435761u >> 7) % 3 == 0 ? 1 : 0;
        w.insert({cx, cy, cz}, std::move(c));
      }
  return w;
}

TEST(World, GetSetAcrossNegativeCoordinates) {
  World w(testing::test_palette());
  const BlockPos p{-1, -33, 64};
  EXPECT_EQ(w.get(p), kAir);
  EXPECT_TRUE(w.set(p, 2));
  EXPECT_EQ(w.get(p), 2);
  EXPECT_FALSE(w.set(p, 2));
  EXPECT_EQ(w.chunk_count(), 1u);
  const Chunk* c = w.find({-1, -2, 2});
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->get(31, 31, 0), 2);
  EXPECT_FALSE(w.set({1000, 1000, 1000}, kAir)) << "setting air where nothing is loaded creates nothing";
  EXPECT_EQ(w.chunk_count(), 1u);
}

TEST(World, GatherPaddedMatchesWorldGet) {
  World w = make_filled_world(1);
  w.erase({1, 0, 0});  // a missing neighbour reads as air
  PaddedBlocks pb;
  w.gather_padded({0, 0, 0}, pb);
  for (int y = -1; y <= kChunkSize; ++y)
    for (int z = -1; z <= kChunkSize; ++z)
      for (int x = -1; x <= kChunkSize; ++x) ASSERT_EQ(pb.at(x, y, z), w.get({x, y, z})) << x << " " << y << " " << z;
}

std::set<ChunkCoord> expected_for(const BlockPos& p) {
  std::set<ChunkCoord> out;
  const ChunkCoord c = chunk_of(p);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dz = -1; dz <= 1; ++dz)
      for (int dx = -1; dx <= 1; ++dx) {
        // The neighbour's padded ring spans its blocks -1 .. 32 on each axis.
        const ChunkCoord nc = c.offset(dx, dy, dz);
        const BlockPos o = chunk_origin(nc);
        if (p.x >= o.x - 1 && p.x <= o.x + kChunkSize && p.y >= o.y - 1 && p.y <= o.y + kChunkSize &&
            p.z >= o.z - 1 && p.z <= o.z + kChunkSize)
          out.insert(nc);
      }
  return out;
}

TEST(World, EditRemeshesExactlyTheChunksWhoseBorderItTouches) {
  World w = make_filled_world(1);
  auto mesher = make_mesher(MesherKind::kBitmask);
  EXPECT_EQ(w.remesh(*mesher).size(), 27u);
  EXPECT_TRUE(w.dirty_chunks().empty());
  struct Case {
    BlockPos p;
    std::size_t count;
  };
  const Case cases[] = {
      {{10, 10, 10}, 1},   // interior
      {{0, 10, 10}, 2},    // -x face
      {{31, 10, 10}, 2},   // +x face
      {{31, 0, 10}, 4},    // edge
      {{0, 31, 31}, 8},    // corner
      {{31, 31, 31}, 8},   // corner
      {{-1, 5, 5}, 2},     // the neighbour's +x face from the other side
  };
  for (const auto& c : cases) {
    const BlockId old = w.get(c.p);
    ASSERT_TRUE(w.set(c.p, old == 1 ? 2 : 1));
    const auto done = w.remesh(*mesher);
    const std::set<ChunkCoord> got(done.begin(), done.end());
    EXPECT_EQ(got, expected_for(c.p)) << c.p.x << "," << c.p.y << "," << c.p.z;
    EXPECT_EQ(got.size(), c.count);
  }
}

TEST(World, IncrementalRemeshEqualsFreshMesh) {
  World w = make_filled_world(1);
  auto mesher = make_mesher(MesherKind::kGreedy);
  (void)w.remesh(*mesher);
  const BlockPos edits[] = {{0, 0, 0}, {31, 31, 31}, {-1, -1, -1}, {15, 0, 31}, {32, 5, 5}};
  for (const auto& p : edits) (void)w.set(p, w.get(p) ? kAir : 2);
  (void)w.remesh(*mesher);
  for (const auto& c : w.chunk_coords()) {
    PaddedBlocks pb;
    w.gather_padded(c, pb);
    ChunkMesh fresh;
    mesher->mesh(pb, w.palette(), fresh);
    EXPECT_EQ(fresh.opaque, w.mesh(c)->opaque);
    EXPECT_EQ(fresh.alpha_cut, w.mesh(c)->alpha_cut);
  }
}

TEST(World, InsertMarksNeighboursAndStaleMeshesAreRejected) {
  World w = make_filled_world(0);
  auto mesher = make_mesher(MesherKind::kCulled);
  (void)w.remesh(*mesher);
  const auto rev = w.revision({0, 0, 0});
  w.insert({1, 0, 0}, Chunk(1));
  const auto dirty = w.dirty_chunks();
  EXPECT_EQ(dirty.size(), 2u);
  EXPECT_NE(w.revision({0, 0, 0}), rev);
  EXPECT_FALSE(w.store_mesh({0, 0, 0}, ChunkMesh{}, rev)) << "a mesh built from an older revision is refused";
  EXPECT_TRUE(w.store_mesh({0, 0, 0}, ChunkMesh{}, w.revision({0, 0, 0})));
}

TEST(Chunk, UniformStorageAndCompaction) {
  Chunk c(3);
  EXPECT_TRUE(c.is_uniform());
  EXPECT_EQ(c.get(5, 5, 5), 3);
  EXPECT_FALSE(c.set(5, 5, 5, 3));
  EXPECT_TRUE(c.set(5, 5, 5, 1));
  EXPECT_FALSE(c.is_uniform());
  EXPECT_TRUE(c.set(5, 5, 5, 3));
  c.compact();
  EXPECT_TRUE(c.is_uniform());
  EXPECT_EQ(c.uniform_id(), 3);
}

}  // namespace
}  // namespace sylva::voxel
