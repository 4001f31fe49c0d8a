// World generation: deterministic for a seed on any number of workers, every biome of the seed
// present, flora per biome, and corrupt saved regions regenerated.

#include <sylva/voxel/world_builder.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <sylva/core/image.hpp>

#include <gtest/gtest.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

namespace sylva::voxel {
namespace {

std::shared_ptr<const WorldGenerator> make_generator(std::uint64_t seed) {
  WorldGenSettings s;
  s.seed = seed;
  s.variants_per_species = 4;
  auto g = WorldGenerator::create(s);
  EXPECT_TRUE(g.ok()) << (g.ok() ? "" : g.error().message);
  return g.ok() ? *g : nullptr;
}

bool same_world(const World& a, const World& b) {
  if (a.chunk_coords() != b.chunk_coords()) return false;
  for (const auto& c : a.chunk_coords()) {
    std::vector<BlockId> x(kChunkVolume), y(kChunkVolume);
    a.find(c)->copy_to(x);
    b.find(c)->copy_to(y);
    if (x != y || *a.plants(c) != *b.plants(c)) return false;
  }
  return true;
}

TEST(WorldGen, DeterministicForASeedOnAnyNumberOfWorkers) {
  auto g = make_generator(42);
  ASSERT_TRUE(g);
  std::int64_t y0, y1;
  chunk_y_range(g->settings(), y0, y1);
  const auto coords = chunk_box({3, 0, -2}, 1, y0, y1);
  World one, two, reversed;
  WorkerPool p1(1), p2(2);
  populate(one, *g, coords, p1);
  populate(two, *g, coords, p2);
  std::vector<ChunkCoord> back(coords.rbegin(), coords.rend());
  populate(reversed, *g, back, p2);
  EXPECT_TRUE(same_world(one, two));
  EXPECT_TRUE(same_world(one, reversed)) << "generation order does not matter";
  // A second generator from the same settings (fresh plant caches) agrees too.
  auto g2 = make_generator(42);
  World again;
  populate(again, *g2, coords, p2);
  EXPECT_TRUE(same_world(one, again));
  // Another seed gives another world.
  auto g3 = make_generator(43);
  World other;
  populate(other, *g3, coords, p2);
  EXPECT_FALSE(same_world(one, other));
}

TEST(WorldGen, AllSixBiomesAndTheirFlora) {
  auto g = make_generator(7);
  ASSERT_TRUE(g);
  std::map<Biome, int> count;
  for (std::int64_t z = -4000; z < 4000; z += 37)
    for (std::int64_t x = -4000; x < 4000; x += 37) ++count[g->biome(x, z)];
  for (int b = 0; b < kBiomeCount; ++b) {
    EXPECT_GT(count[static_cast<Biome>(b)], 100) << to_string(static_cast<Biome>(b));
  }
  // Plants found in generated chunks stand on ground of a biome that grows them.
  const std::map<std::string, std::set<Biome>> grows = {
      {"acacia", {Biome::kSavanna}},
      {"jungle", {Biome::kJungle}},
      {"birch", {Biome::kBirchForest}},
      {"oak", {Biome::kOakForest, Biome::kPlains}},
      {"forked_bush", {Biome::kJungle, Biome::kSavanna, Biome::kShrubland, Biome::kOakForest}},
      {"berry_bush", {Biome::kShrubland, Biome::kBirchForest}},
  };
  ASSERT_EQ(g->species().species.size(), grows.size());
  std::set<std::string> seen;
  std::int64_t y0, y1;
  chunk_y_range(g->settings(), y0, y1);
  for (std::int64_t cz = -120; cz <= 120; cz += 20) {
    for (std::int64_t cx = -120; cx <= 120; cx += 20) {
      for (std::int64_t cy = y0; cy <= y1; ++cy) {
        const GeneratedChunk chunk = g->generate({cx, cy, cz});
        for (const auto& p : chunk.plants) {
          const std::string& name = g->species().species.at(p.species).name;
          seen.insert(name);
          EXPECT_TRUE(grows.at(name).count(g->biome(p.ground.x, p.ground.z))) << name;
          EXPECT_EQ(chunk_of(p.ground), chunk.coord);
          EXPECT_EQ(p.ground.y, g->ground_height(p.ground.x, p.ground.z));
          EXPECT_NE(chunk.blocks.get(local_of(p.ground.x), local_of(p.ground.y), local_of(p.ground.z)), kAir);
        }
      }
    }
  }
  EXPECT_EQ(seen.size(), grows.size());
}

TEST(WorldGen, CorruptRegionIsReportedAndRegenerated) {
  auto g = make_generator(5);
  ASSERT_TRUE(g);
  const auto dir = std::filesystem::temp_directory_path() / ("sylva_voxel_gen_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  const std::vector<ChunkCoord> coords = {{0, 0, 0}, {1, 0, 0}};
  WorkerPool pool(2);
  World original;
  populate(original, *g, coords, pool);
  // Edit, save, then damage the file.
  ASSERT_TRUE(original.set({5, 25, 5}, original.palette().id("glowstone")));
  RegionStore store(dir, original.palette());
  std::vector<std::pair<ChunkCoord, const Chunk*>> list;
  for (const auto& c : coords) list.emplace_back(c, original.find(c));
  ASSERT_TRUE(store.save(list).ok());
  {
    RegionStore reader(dir, original.palette());
    World loaded;
    const auto report = populate(loaded, *g, coords, pool, &reader);
    EXPECT_EQ(report.loaded, 2u);
    EXPECT_EQ(loaded.get({5, 25, 5}), original.palette().id("glowstone")) << "the edit was saved";
  }
  const auto path = store.path_of({0, 0, 0});
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(12);
  f.put('\x7f');
  f.close();
  RegionStore reader(dir, original.palette());
  World recovered;
  const auto report = populate(recovered, *g, coords, pool, &reader);
  EXPECT_EQ(report.regenerated, 2u);
  ASSERT_EQ(report.region_errors.size(), 2u);
  EXPECT_NE(report.region_errors[0].message.find("r.0.0.0.svr"), std::string::npos) << report.region_errors[0].message;
  EXPECT_EQ(recovered.get({5, 25, 5}), kAir) << "regenerated from the seed";
  EXPECT_EQ(recovered.chunk_count(), 2u);
  std::filesystem::remove_all(dir);
}

// Region files hold blocks only; plants are regenerated from the seed (world.hpp). Saving every
// chunk of an edited world and loading it with a fresh generator (other caches, other worker
// count) gives back the same blocks and the same plants, except that a plant whose ground block
// was edited is gone, in the edited world and after the reload alike.
TEST(WorldGen, SavedRegionsRoundTripBlocksAndPlantsRegenerateFromTheSeed) {
  auto g = make_generator(7);
  ASSERT_TRUE(g);
  std::int64_t y0, y1;
  chunk_y_range(g->settings(), y0, y1);
  const auto coords = chunk_box({0, 0, 0}, 1, y0, y1);
  WorkerPool p2(2), p1(1);
  World original;
  populate(original, *g, coords, p2);
  // Edits: one plant loses its ground; a block is placed in another chunk.
  std::size_t plants_before = 0;
  const PlantInstance* victim = nullptr;
  for (const auto& c : original.chunk_coords()) {
    plants_before += original.plants(c)->size();
    if (!victim && !original.plants(c)->empty()) victim = &original.plants(c)->front();
  }
  ASSERT_NE(victim, nullptr) << "seed 7 places plants near the origin";
  const PlantInstance removed = *victim;
  const std::uint64_t epoch = original.plant_epoch();
  ASSERT_TRUE(original.set(removed.ground, kAir));
  EXPECT_GT(original.plant_epoch(), epoch);
  std::size_t plants_after = 0;
  for (const auto& c : original.chunk_coords()) {
    for (const PlantInstance& p : *original.plants(c)) EXPECT_FALSE(p == removed);
    plants_after += original.plants(c)->size();
  }
  EXPECT_EQ(plants_after, plants_before - 1);
  const BlockPos lamp = chunk_origin(coords.back());
  ASSERT_TRUE(original.set({lamp.x + 3, lamp.y + 3, lamp.z + 3}, original.palette().id("lantern")));

  const auto dir = std::filesystem::temp_directory_path() / ("sylva_voxel_rt_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  {
    RegionStore store(dir, original.palette());
    std::vector<std::pair<ChunkCoord, const Chunk*>> list;
    for (const auto& c : original.chunk_coords()) list.emplace_back(c, original.find(c));
    ASSERT_TRUE(store.save(list).ok());
  }
  auto fresh = make_generator(7);
  RegionStore reader(dir, original.palette());
  World loaded;
  const auto report = populate(loaded, *fresh, coords, p1, &reader);
  EXPECT_EQ(report.loaded, coords.size());
  EXPECT_TRUE(same_world(original, loaded)) << "blocks and plants survive the save";
  std::filesystem::remove_all(dir);
}

TEST(WorldGen, PopulateReportsProgressAndCanBeCancelled) {
  auto g = make_generator(9);
  ASSERT_TRUE(g);
  const auto coords = chunk_box({0, 0, 0}, 3, 0, 1);  // 98 chunks
  WorkerPool pool(2);
  World world;
  std::atomic<bool> cancel{false};
  std::size_t calls = 0, last = 0;
  const auto report = populate(world, *g, coords, pool, nullptr, &cancel, [&](std::size_t done, std::size_t total) {
    ++calls;
    EXPECT_EQ(total, coords.size());
    EXPECT_GT(done, last);
    last = done;
    if (done >= 16) cancel = true;
  });
  EXPECT_TRUE(report.cancelled);
  EXPECT_GE(calls, 1u);
  EXPECT_LT(world.chunk_count(), coords.size());
  EXPECT_EQ(world.chunk_count(), report.generated);
  // Resuming fills in the rest.
  cancel = false;
  const auto rest = populate(world, *g, coords, pool);
  EXPECT_FALSE(rest.cancelled);
  EXPECT_EQ(world.chunk_count(), coords.size());
}

TEST(WorldGen, BadSettingsNameTheParameter) {
  WorldGenSettings s;
  s.terrain_scale = 1.0;
  auto g = WorldGenerator::create(s);
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.error().message.find("voxel.worldgen.terrain_scale"), std::string::npos) << g.error().message;
}

TEST(WorldGen, WritesABiomeMap) {
  auto g = make_generator(7);
  ASSERT_TRUE(g);
  const float colours[kBiomeCount][3] = {{0.1f, 0.5f, 0.1f}, {0.8f, 0.7f, 0.3f}, {0.5f, 0.8f, 0.3f},
                                         {0.6f, 0.55f, 0.35f}, {0.85f, 0.85f, 0.8f}, {0.2f, 0.35f, 0.15f}};
  Image img(200, 200, 3);
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 200; ++x) {
      const std::int64_t wx = (x - 100) * 20, wz = (y - 100) * 20;
      const auto b = static_cast<int>(g->biome(wx, wz));
      const float shade = 0.7f + 0.3f * static_cast<float>(g->ground_height(wx, wz) - 2) / 40.0f;
      for (int c = 0; c < 3; ++c) img.at(x, y, c) = colours[b][c] * shade;
    }
  EXPECT_TRUE(write_image("biome_map.png", img, PixelFormat::kU8).ok());
}

}  // namespace
}  // namespace sylva::voxel
