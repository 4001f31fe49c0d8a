// Turtle interpretation, growth stages, variants and the part cap. Writes preview PNGs of the
// shipped plants into the test's working directory (plants_*.png) for inspection.

#include <sylva/voxel/plant.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "support/plant_preview.hpp"

namespace sylva::voxel {
namespace {

const LSystem& system_of(const char* file, std::size_t index = 0) {
  static std::map<std::string, std::vector<LSystem>> cache;
  auto it = cache.find(file);
  if (it == cache.end()) {
    auto r = load_builtin_lsystems(file);
    EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
    it = cache.emplace(file, r.ok() ? *r : std::vector<LSystem>{}).first;
  }
  return it->second.at(index);
}

bool same_parts(const PlantModel& a, const PlantModel& b) {
  for (int o = 0; o < kPlantOutputs; ++o) {
    const auto& pa = a.outputs[static_cast<std::size_t>(o)];
    const auto& pb = b.outputs[static_cast<std::size_t>(o)];
    if (pa.size() != pb.size()) return false;
    for (std::size_t i = 0; i < pa.size(); ++i) {
      if (pa[i].position != pb[i].position || pa[i].size != pb[i].size) return false;
    }
  }
  return true;
}

TEST(Plant, DeterministicForASaltAndVariedAcrossSalts) {
  const LSystem& acacia = system_of("acacia.lsys");
  LSystemExecutorSettings s;
  s.min_derivations = 4;
  s.max_derivations = 6;
  auto a = generate_plant(acacia, s, 11);
  auto b = generate_plant(acacia, s, 11);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_TRUE(same_parts(*a, *b));
  int distinct = 0;
  for (std::uint64_t salt = 12; salt < 22; ++salt) distinct += !same_parts(*generate_plant(acacia, s, salt), *a);
  EXPECT_EQ(distinct, 10);
}

TEST(Plant, AcaciaHasAFlatWideCrownAboveALeaningTrunk) {
  // Seed §4.5.4: the turtle pitches up, lays branches, pitches down and lays leaves in one plane:
  // a wide, flat crown (Fig. 4.5, 4.7) whose height varies only through the jittered turns.
  const LSystem& acacia = system_of("acacia.lsys");
  LSystemExecutorSettings s;
  s.min_derivations = 5;
  s.max_derivations = 5;
  s.size_at_max = 1.0f;
  int wide = 0;
  for (std::uint64_t salt = 1; salt <= 10; ++salt) {
    auto m = generate_plant(acacia, s, salt);
    ASSERT_TRUE(m.ok()) << m.error().message;
    const auto& wood = m->outputs[0];
    const auto& leaves = m->outputs[1];
    ASSERT_FALSE(wood.empty());
    ASSERT_FALSE(leaves.empty());
    glm::vec3 lo(1e9f), hi(-1e9f);
    float wood_top = -1e9f;
    for (const auto& p : leaves) {
      lo = glm::min(lo, p.position);
      hi = glm::max(hi, p.position);
    }
    for (const auto& p : wood) wood_top = std::max(wood_top, p.position.y);
    const float width = std::max(hi.x - lo.x, hi.z - lo.z);
    const float height = hi.y - lo.y;
    wide += width > 1.5f * height;
    EXPECT_GT(hi.y, 2.0f) << "the crown sits above the ground";
    EXPECT_LE(wood_top, hi.y + 1.0f);
  }
  EXPECT_GE(wide, 8) << "most acacias have crowns wider than tall";
}

TEST(Plant, GrowthStagesScaleTrunkLinearlyAndGrowTaller) {
  // Seed §4.6.1: bushes of 2, 3 and 4 derivations; trunk thickness linear in the count.
  LSystemExecutorSettings s;
  s.min_derivations = 2;
  s.max_derivations = 4;
  s.size_at_min = 0.5f;
  s.size_at_max = 1.0f;
  EXPECT_FLOAT_EQ(start_size_for(s, 2), 0.5f);
  EXPECT_FLOAT_EQ(start_size_for(s, 3), 0.75f);
  EXPECT_FLOAT_EQ(start_size_for(s, 4), 1.0f);
  std::set<int> seen;
  for (std::uint64_t salt = 0; salt < 64; ++salt) seen.insert(derivations_for(s, salt));
  EXPECT_EQ(seen, (std::set<int>{2, 3, 4}));
  for (std::size_t species = 0; species < 2; ++species) {
    const LSystem& bush = system_of("bushes.lsys", species);
    float mean_height[3] = {};
    for (int d = 2; d <= 4; ++d) {
      LSystemExecutorSettings fixed = s;
      fixed.min_derivations = fixed.max_derivations = d;
      fixed.size_at_min = fixed.size_at_max = start_size_for(s, d);
      for (std::uint64_t salt = 0; salt < 16; ++salt) {
        auto m = generate_plant(bush, fixed, salt);
        ASSERT_TRUE(m.ok()) << m.error().message;
        EXPECT_FLOAT_EQ(m->outputs[0].front().size, start_size_for(s, d)) << "trunk block size";
        mean_height[d - 2] += m->bounds_max.y / 16.0f;
      }
    }
    EXPECT_LT(mean_height[0], mean_height[1]) << "species " << species;
    EXPECT_LT(mean_height[1], mean_height[2]) << "species " << species;
  }
}

TEST(Plant, KochIslandIsAClosedCurveInTheGroundPlane) {
  const LSystem& koch = system_of("seed_examples.lsys", 0);
  LSystemExecutorSettings s;
  s.angle_variation = 0.0f;
  s.size_at_min = s.size_at_max = 1.0f;
  auto d = derive(koch, 2, 1);
  ASSERT_TRUE(d.ok());
  auto m = interpret(koch, *d, 1.0f, s, 1);
  ASSERT_TRUE(m.ok());
  const auto& parts = m->outputs[0];
  ASSERT_EQ(parts.size(), 4u * 64u);
  for (const auto& p : parts) EXPECT_NEAR(p.position.y, 0.0f, 1e-4f);
  EXPECT_NEAR(glm::length(parts.back().position), 0.0f, 1e-3f) << "the island closes on its start";
}

TEST(Plant, PartCapStopsHugePlants) {
  const LSystem& acacia = system_of("acacia.lsys");
  LSystemExecutorSettings s;
  s.min_derivations = s.max_derivations = 9;
  s.limits.max_parts = 500;
  auto m = generate_plant(acacia, s, 3);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, ErrorCode::kLimit);
  EXPECT_NE(m.error().message.find("max_parts=500"), std::string::npos) << m.error().message;
}

TEST(Plant, VariantsAreCachedPerSeedAndPickedByPosition) {
  const LSystem& bush = system_of("bushes.lsys", 0);
  LSystemExecutorSettings s;
  auto v1 = PlantVariants::build(bush, s, 1234, 7, 12);
  auto v2 = PlantVariants::build(bush, s, 1234, 7, 12);
  auto other = PlantVariants::build(bush, s, 99, 7, 12);
  ASSERT_TRUE(v1.ok() && v2.ok() && other.ok());
  std::set<std::size_t> used;
  for (int x = -50; x < 50; x += 3) {
    for (int z = -50; z < 50; z += 7) {
      EXPECT_EQ(v1->index_for(x, z), v2->index_for(x, z));
      used.insert(v1->index_for(x, z));
    }
  }
  EXPECT_GE(used.size(), 10u) << "positions spread over the buffer";
  for (std::size_t i = 0; i < v1->size(); ++i) EXPECT_TRUE(same_parts(v1->at(i), v2->at(i)));
  int differs = 0;
  for (std::size_t i = 0; i < v1->size(); ++i) differs += !same_parts(v1->at(i), other->at(i));
  EXPECT_GE(differs, 10) << "another world seed gives other plants";
}

TEST(Plant, WritesPreviews) {
  std::vector<PlantModel> models;
  auto add = [&](const LSystem& sys, int d0, int d1, std::uint64_t salt) {
    LSystemExecutorSettings s;
    s.min_derivations = d0;
    s.max_derivations = d1;
    auto m = generate_plant(sys, s, salt);
    ASSERT_TRUE(m.ok()) << m.error().message;
    models.push_back(std::move(*m));
  };
  for (std::uint64_t salt = 1; salt <= 3; ++salt) add(system_of("acacia.lsys"), 5, 5, salt);
  for (std::uint64_t salt = 1; salt <= 2; ++salt) add(system_of("broadleaf.lsys"), 4, 5, salt);
  for (std::uint64_t salt = 1; salt <= 2; ++salt) add(system_of("jungle.lsys"), 4, 5, salt);
  for (int d = 2; d <= 4; ++d) add(system_of("bushes.lsys", 0), d, d, 5);
  for (int d = 2; d <= 4; ++d) add(system_of("bushes.lsys", 1), d, d, 5);
  std::vector<const PlantModel*> ptrs;
  for (const auto& m : models) ptrs.push_back(&m);
  testing::save_preview("plants_preview.png", ptrs);
  EXPECT_TRUE(std::filesystem::exists("plants_preview.png"));
}

}  // namespace
}  // namespace sylva::voxel
