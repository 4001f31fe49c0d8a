// Grass tufts and flowers stand off the block grid (issue #19): in a generated region their feet
// are jittered inside their cells, so neighbouring tufts do not line up in rows, and their size,
// turn and tint vary; each tuft is a pure function of its block's world position.

#include <sylva/voxel/tufts.hpp>
#include <sylva/voxel/world_builder.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace sylva::voxel {
namespace {

struct Placed {
  BlockPos cell;  // world block
  glm::dvec3 foot;  // world
  Tuft tuft;
};

// Every tuft of a generated 3 x 3-chunk-column region of seed 3 (the shipped world's seed),
// keyed by its block's (x, z); at most one tuft per column.
std::map<std::pair<std::int64_t, std::int64_t>, Placed> generated_tufts() {
  WorldGenSettings s;
  s.seed = 3;
  s.variants_per_species = 2;
  auto g = WorldGenerator::create(s);
  EXPECT_TRUE(g.ok()) << (g.ok() ? "" : g.error().message);
  std::map<std::pair<std::int64_t, std::int64_t>, Placed> out;
  if (!g.ok()) return out;
  std::int64_t y0 = 0, y1 = 0;
  chunk_y_range(s, y0, y1);
  std::vector<Tuft> tufts;
  for (const ChunkCoord& c : chunk_box({0, 0, 0}, 1, y0, y1)) {
    const GeneratedChunk gen = (*g)->generate(c);
    tufts.clear();
    place_tufts(gen.blocks, c, (*g)->palette(), tufts);
    const BlockPos o = chunk_origin(c);
    for (const Tuft& t : tufts) {
      const BlockPos cell{o.x + static_cast<std::int64_t>(std::floor(t.foot.x)), o.y + static_cast<std::int64_t>(t.foot.y),
                          o.z + static_cast<std::int64_t>(std::floor(t.foot.z))};
      const glm::dvec3 foot(static_cast<double>(o.x) + t.foot.x, static_cast<double>(o.y) + t.foot.y,
                            static_cast<double>(o.z) + t.foot.z);
      EXPECT_TRUE(out.emplace(std::make_pair(cell.x, cell.z), Placed{cell, foot, t}).second);
    }
  }
  return out;
}

TEST(Tufts, GeneratedTuftsStandInNoGridRows) {
  const auto tufts = generated_tufts();
  ASSERT_GT(tufts.size(), 300u) << "the region has meadows";
  // Neighbouring tufts along x (along z): with the old block-centred tufts every pair had equal z
  // (equal x), i.e. 100 % lay in rows. Jittered uniformly over +-0.3 blocks, |dz| < 0.02 happens
  // for about 6.6 % of pairs; we allow 12 %.
  int pairs = 0, in_row = 0;
  for (const auto& [key, a] : tufts) {
    for (const auto& step : {std::make_pair(1, 0), std::make_pair(0, 1)}) {
      auto it = tufts.find({key.first + step.first, key.second + step.second});
      if (it == tufts.end()) continue;
      ++pairs;
      const double across = step.first != 0 ? it->second.foot.z - a.foot.z : it->second.foot.x - a.foot.x;
      if (std::abs(across) < 0.02) ++in_row;
    }
  }
  ASSERT_GT(pairs, 100);
  EXPECT_LE(in_row, pairs * 12 / 100) << in_row << " of " << pairs << " neighbouring pairs line up";
  // The fractional offsets spread over the cell: no offset (to 1/50 block) holds more than 8 %.
  std::map<int, int> offsets;
  for (const auto& [key, p] : tufts) ++offsets[static_cast<int>(std::floor((p.foot.x - std::floor(p.foot.x)) * 50.0))];
  int most = 0;
  for (const auto& [bin, n] : offsets) most = std::max(most, n);
  EXPECT_GE(offsets.size(), 25u);
  EXPECT_LE(most, static_cast<int>(tufts.size()) * 8 / 100);
}

TEST(Tufts, StayInsideTheirCellAndVaryInSizeTurnAndTint) {
  const auto tufts = generated_tufts();
  ASSERT_FALSE(tufts.empty());
  float h_lo = 10.0f, h_hi = 0.0f, yaw_lo = 10.0f, yaw_hi = -10.0f, tint_lo = 10.0f, tint_hi = 0.0f;
  for (const auto& [key, p] : tufts) {
    const double cx = static_cast<double>(p.cell.x) + 0.5, cz = static_cast<double>(p.cell.z) + 0.5;
    // Never into a neighbouring block (a wall there would swallow it).
    EXPECT_LE(std::abs(p.foot.x - cx), kTuftJitter + 1e-4);
    EXPECT_LE(std::abs(p.foot.z - cz), kTuftJitter + 1e-4);
    EXPECT_EQ(p.foot.y, static_cast<double>(p.cell.y)) << "the foot stands on the ground block";
    h_lo = std::min(h_lo, p.tuft.height), h_hi = std::max(h_hi, p.tuft.height);
    yaw_lo = std::min(yaw_lo, p.tuft.yaw), yaw_hi = std::max(yaw_hi, p.tuft.yaw);
    tint_lo = std::min(tint_lo, p.tuft.tint.g), tint_hi = std::max(tint_hi, p.tuft.tint.g);
    EXPECT_GE(p.tuft.width, 0.8f);
    EXPECT_LE(p.tuft.width, 1.1f);
  }
  EXPECT_GE(h_lo, 0.55f);
  EXPECT_LE(h_hi, 1.15f);
  EXPECT_GT(h_hi - h_lo, 0.4f);
  EXPECT_GT(yaw_hi - yaw_lo, 1.2f);
  EXPECT_GT(tint_hi - tint_lo, 0.15f);
}

TEST(Tufts, ATuftIsAFunctionOfItsWorldPosition) {
  // The same block gives the same tuft from place_tufts of any chunk layout and from tuft_at;
  // far from the origin (int64 coordinates) as well.
  BlockPalette palette;
  BlockType grass;
  grass.name = "tuft";
  grass.render = RenderClass::kAlphaCut;
  grass.sides_only = true;
  const BlockId id = palette.add(grass).value();
  for (const ChunkCoord c : {ChunkCoord{0, 0, 0}, ChunkCoord{-3, 1, 7}, ChunkCoord{31250000000, 0, -31250000000}}) {
    Chunk chunk;
    chunk.set(5, 6, 7, id);
    std::vector<Tuft> out;
    place_tufts(chunk, c, palette, out);
    ASSERT_EQ(out.size(), 1u);
    const BlockPos p{chunk_origin(c).x + 5, chunk_origin(c).y + 6, chunk_origin(c).z + 7};
    const Tuft again = tuft_at(p, id);
    EXPECT_EQ(out[0].foot, again.foot);
    EXPECT_EQ(out[0].height, again.height);
    EXPECT_EQ(out[0].yaw, again.yaw);
    EXPECT_EQ(out[0].block, id);
    EXPECT_NEAR(out[0].foot.x, 5.5f, kTuftJitter + 1e-4f);
    EXPECT_NEAR(out[0].foot.z, 7.5f, kTuftJitter + 1e-4f);
  }
  // Two different blocks get different tufts.
  EXPECT_NE(tuft_at({0, 0, 0}, id).foot.x, tuft_at({1, 0, 0}, id).foot.x - 1.0f);
  // Opaque and air blocks get none; a uniform chunk of tufts gets one per block.
  std::vector<Tuft> none;
  place_tufts(Chunk(kAir), {0, 0, 0}, palette, none);
  EXPECT_TRUE(none.empty());
  place_tufts(Chunk(id), {0, 0, 0}, palette, none);
  EXPECT_EQ(none.size(), static_cast<std::size_t>(kChunkVolume));
}

}  // namespace
}  // namespace sylva::voxel
