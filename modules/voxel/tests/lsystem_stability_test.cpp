// L-system stability at the extremes. Each test names the invariant it checks.

#include <sylva/voxel/plant.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sylva::voxel {
namespace {

LSystem parse_one(const std::string& text) {
  auto r = parse_lsystems(text, "stability.lsys");
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
  return r.ok() ? r->front() : LSystem{};
}

bool all_finite(const PlantModel& m) {
  for (const auto& out : m.outputs)
    for (const auto& p : out) {
      if (!std::isfinite(p.position.x) || !std::isfinite(p.position.y) || !std::isfinite(p.position.z) ||
          !std::isfinite(p.size) || !std::isfinite(p.orientation.w))
        return false;
    }
  return std::isfinite(m.bounds_min.x) && std::isfinite(m.bounds_max.y);
}

// Invariant: the pitch guard (seed §4.5.2) keeps the turtle frame finite when the pitch passes
// through +-90 degrees in exact steps, with and without jitter, with oriented parts.
TEST(LSystemStability, PitchThroughVerticalStaysFinite) {
  const LSystem s = parse_one("90 90 0.9\n^F^F^F^F^U^U&&&&&&&&FUFU\n");
  for (float var : {0.0f, 0.2f, 1.0f}) {
    LSystemExecutorSettings e;
    e.angle_variation = var;
    e.orient_parts = true;
    e.min_derivations = e.max_derivations = 0;
    for (std::uint64_t salt = 0; salt < 50; ++salt) {
      auto m = generate_plant(s, e, salt);
      ASSERT_TRUE(m.ok()) << m.error().message;
      EXPECT_TRUE(all_finite(*m)) << "variation " << var << " salt " << salt;
      EXPECT_EQ(m->part_count(), 10u);
    }
  }
}

// Invariant: block size stays within [1e-3, 1e3] x the start size however often x or X repeat.
TEST(LSystemStability, SizeIsClampedUnderRepeatedShrinkAndGrow) {
  const LSystem grow = parse_one("10 10 0.5\n" + std::string(5000, 'X') + "F\n");
  const LSystem shrink = parse_one("10 10 0.5\n" + std::string(5000, 'x') + "F\n");
  LSystemExecutorSettings e;
  e.min_derivations = e.max_derivations = 0;
  e.size_at_min = e.size_at_max = 1.0f;
  auto g = generate_plant(grow, e, 1);
  auto s = generate_plant(shrink, e, 1);
  ASSERT_TRUE(g.ok() && s.ok());
  EXPECT_FLOAT_EQ(g->outputs[0].front().size, 1000.0f);
  EXPECT_FLOAT_EQ(s->outputs[0].front().size, 0.001f);
  EXPECT_TRUE(all_finite(*g));
}

// Invariant: deep bracket nesting is refused with kLimit (max_depth), never a stack explosion.
TEST(LSystemStability, DeepNestingHitsTheDepthCap) {
  const LSystem s = parse_one("30 30 0.8\nA\nA > [FA]\n");
  LSystemExecutorSettings e;
  e.min_derivations = e.max_derivations = 1200;
  e.limits.max_depth = 1000;
  auto m = generate_plant(s, e, 1);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.error().code, ErrorCode::kLimit);
  EXPECT_NE(m.error().message.find("max_depth=1000"), std::string::npos) << m.error().message;
}

// Invariant: many derivations of a grammar that does not grow stay cheap and exact; zero
// derivations return the axiom; a negative count is refused.
TEST(LSystemStability, DerivationCountExtremes) {
  const LSystem s = parse_one("30 30 0.8\nAF\nA > A\n");
  auto many = derive(s, 100000, 3);
  ASSERT_TRUE(many.ok());
  EXPECT_EQ(*many, "AF");
  EXPECT_EQ(*derive(s, 0, 3), "AF");
  EXPECT_FALSE(derive(s, -1, 3).ok());
  LSystemExecutorSettings e;
  e.min_derivations = 4;
  e.max_derivations = 2;
  EXPECT_FALSE(generate_plant(s, e, 1).ok()) << "min > max is an error, not a crash";
}

// Invariant: a grammar without any drawing symbol gives an empty, finite model.
TEST(LSystemStability, EmptyPlant) {
  const LSystem s = parse_one("30 30 0.8\nAB+-[]\nA > B\n");
  LSystemExecutorSettings e;
  auto m = generate_plant(s, e, 9);
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->part_count(), 0u);
  EXPECT_TRUE(all_finite(*m));
}

}  // namespace
}  // namespace sylva::voxel
