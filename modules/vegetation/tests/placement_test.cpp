// Tree placement on a core height field: Poisson-disk spacing, density maps, slopes, world
// anchoring, determinism and the output cap.
#include <sylva/vegetation/placement.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sylva::vegetation {
namespace {

HeightField flat(int n = 101, double spacing = 2.0, glm::dvec2 origin = {0.0, 0.0}) {
  HeightField f(n, n, spacing, origin);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) f.sample(i, j) = 3.0f + 0.01f * static_cast<float>(i);
  f.update_range();
  return f;
}

TEST(Placement, PoissonDiskKeepsTheMinimumDistanceAndLeavesNoHoles) {
  const HeightField g = flat();
  PlacementSettings s;
  s.min_distance = 8.0f;
  Result<std::vector<TreeInstance>> trees = place_poisson_disk(g, s);
  ASSERT_TRUE(trees.ok()) << trees.error().describe();
  const double area = 200.0 * 200.0;
  // Bridson packs about 0.6-0.7 disks of radius r/2 per (pi r^2 / 4) of area.
  const double expected = area / (std::numbers::pi * 8.0 * 8.0 / 4.0) * 0.65;
  EXPECT_GT(static_cast<double>(trees->size()), 0.75 * expected);
  EXPECT_LT(static_cast<double>(trees->size()), 1.25 * expected);
  double closest = 1e9;
  for (std::size_t a = 0; a < trees->size(); ++a)
    for (std::size_t b = a + 1; b < trees->size(); ++b) {
      const glm::dvec3 d = (*trees)[a].position - (*trees)[b].position;
      closest = std::min(closest, std::hypot(d.x, d.z));
    }
  EXPECT_GE(closest, 8.0 - 1e-9);
  // No hole: every probe point has a tree within 2 r.
  for (double x = 10.0; x < 190.0; x += 13.0)
    for (double z = 10.0; z < 190.0; z += 13.0) {
      double best = 1e9;
      for (const TreeInstance& t : *trees) best = std::min(best, std::hypot(t.position.x - x, t.position.z - z));
      ASSERT_LT(best, 16.0) << x << ", " << z;
    }
  // On the ground (minus the sink), with attributes in their ranges.
  for (const TreeInstance& t : *trees) {
    EXPECT_NEAR(t.position.y, g.height(t.position.x, t.position.z) - s.sink, 1e-5);
    EXPECT_GE(t.scale, s.scale_min);
    EXPECT_LE(t.scale, s.scale_max);
    EXPECT_LE(t.season_offset, 0.0f);
    EXPECT_GE(t.season_offset, -s.season_spread);
    EXPECT_GE(t.time_offset, 0.0f);
    EXPECT_LT(t.time_offset, s.time_offset_range);
  }
}

TEST(Placement, DensityMapDecidesWhereTreesGrow) {
  const HeightField g = flat();
  // Left half (x < 100 m) density 1, right half 0.
  Image map(64, 64, 1);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) map.at(x, y) = x < 32 ? 1.0f : 0.0f;
  PlacementSettings s;
  s.density = 0.01f;
  Result<std::vector<TreeInstance>> trees = place_by_density(g, map, s);
  ASSERT_TRUE(trees.ok()) << trees.error().describe();
  std::size_t left = 0;
  for (const TreeInstance& t : *trees) {
    EXPECT_LT(t.position.x, 103.0);  // the bilinear edge is a few metres wide
    left += t.position.x < 97.0 ? 1u : 0u;
  }
  const double expected = 0.01 * 97.0 * 200.0;
  EXPECT_NEAR(static_cast<double>(left), expected, 0.1 * expected);
  // The same map thins Poisson-disk samples.
  s.min_distance = 6.0f;
  Result<std::vector<TreeInstance>> thinned = place_poisson_disk(g, s, &map);
  ASSERT_TRUE(thinned.ok());
  for (const TreeInstance& t : *thinned) EXPECT_LT(t.position.x, 103.0);
  EXPECT_GT(thinned->size(), 100u);
}

TEST(Placement, DensityPlacementIsWorldAnchored) {
  Image ones(4, 4, 1);
  for (float& v : ones.data()) v = 1.0f;
  PlacementSettings s;
  s.density = 0.02f;
  const HeightField big = flat(101, 2.0, {0.0, 0.0});
  const HeightField part = flat(41, 2.0, {60.0, 60.0});
  Result<std::vector<TreeInstance>> a = place_by_density(big, ones, s);
  Result<std::vector<TreeInstance>> b = place_by_density(part, ones, s);
  ASSERT_TRUE(a.ok() && b.ok());
  // Every tree of the part exists in the big field at the same place with the same attributes.
  ASSERT_GT(b->size(), 20u);
  for (const TreeInstance& t : *b) {
    bool found = false;
    for (const TreeInstance& u : *a)
      if (u.position.x == t.position.x && u.position.z == t.position.z) {
        EXPECT_EQ(u.yaw, t.yaw);
        EXPECT_EQ(u.scale, t.scale);
        found = true;
      }
    EXPECT_TRUE(found) << t.position.x << ", " << t.position.z;
  }
}

TEST(Placement, SteepGroundStaysBare) {
  HeightField g(51, 51, 1.0);
  for (int j = 0; j < 51; ++j)
    for (int i = 0; i < 51; ++i) g.sample(i, j) = i < 25 ? 0.0f : 1.5f * static_cast<float>(i - 25);  // 56 deg
  g.update_range();
  PlacementSettings s;
  s.min_distance = 2.0f;
  s.max_slope_deg = 30.0f;
  Result<std::vector<TreeInstance>> trees = place_poisson_disk(g, s);
  ASSERT_TRUE(trees.ok());
  ASSERT_GT(trees->size(), 30u);
  for (const TreeInstance& t : *trees) EXPECT_LT(t.position.x, 26.5);
}

TEST(Placement, DeterministicAndCapped) {
  const HeightField g = flat();
  PlacementSettings s;
  Result<std::vector<TreeInstance>> a = place_poisson_disk(g, s);
  Result<std::vector<TreeInstance>> b = place_poisson_disk(g, s);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a->size(), b->size());
  for (std::size_t i = 0; i < a->size(); ++i) EXPECT_EQ((*a)[i].position, (*b)[i].position);
  s.seed = 2;
  Result<std::vector<TreeInstance>> c = place_poisson_disk(g, s);
  ASSERT_TRUE(c.ok());
  EXPECT_NE((*a)[0].position, (*c)[0].position);
  s.max_instances = 50;
  Result<std::vector<TreeInstance>> capped = place_poisson_disk(g, s);
  ASSERT_FALSE(capped.ok());
  EXPECT_EQ(capped.error().code, ErrorCode::kLimit);
  EXPECT_NE(capped.error().message.find("placement.max_instances = 50"), std::string::npos);
  // Bad settings name the parameter.
  PlacementSettings bad;
  bad.scale_min = 2.0f;
  bad.scale_max = 1.0f;
  Result<std::vector<TreeInstance>> e = place_poisson_disk(g, bad);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("placement.scale_min"), std::string::npos);
  bad = PlacementSettings{};
  bad.min_distance = -1.0f;
  e = place_poisson_disk(g, bad);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("placement.min_distance"), std::string::npos);
  Image empty;
  EXPECT_FALSE(place_by_density(g, empty, PlacementSettings{}).ok());
}

TEST(Placement, TinyFieldsWork) {
  const HeightField one(1, 1, 1.0);
  Result<std::vector<TreeInstance>> t = place_poisson_disk(one, PlacementSettings{});
  ASSERT_TRUE(t.ok()) << t.error().describe();
  EXPECT_LE(t->size(), 1u);
}

}  // namespace
}  // namespace sylva::vegetation
