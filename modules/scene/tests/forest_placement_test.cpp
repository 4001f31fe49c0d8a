// Forest placement: deterministic, world-anchored (a sub-region gives exactly the trees of its
// cells), minimum spacing kept, density respected, trees on the ground.
#include <sylva/scene/forest_placement.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

using namespace sylva;
using namespace sylva::scene;

namespace {
std::set<std::tuple<double, double, double>> keys(const std::vector<PlacedTree>& trees) {
  std::set<std::tuple<double, double, double>> s;
  for (const PlacedTree& t : trees) s.insert({t.position.x, t.position.y, t.position.z});
  return s;
}
}  // namespace

TEST(ForestPlacement, DeterministicAndWorldAnchored) {
  ForestPlacement p;
  p.area_min = {-100, -80};
  p.area_max = {120, 90};
  p.trees_per_hectare = 50;
  const auto all = place_trees(p, nullptr, nullptr, p.area_min, p.area_max);
  const auto again = place_trees(p, nullptr, nullptr, p.area_min, p.area_max);
  EXPECT_EQ(keys(all), keys(again));
  // Expected count: area in hectares * trees per hectare (one candidate per cell, density 1).
  const double expected = 220.0 * 170.0 / 1e4 * 50.0;
  EXPECT_NEAR(static_cast<double>(all.size()), expected, 0.1 * expected);
  // A sub-region gives exactly the trees of the full placement in the cells it overlaps.
  const glm::dvec2 lo{-20, 5}, hi{31, 47};
  const auto part = place_trees(p, nullptr, nullptr, lo, hi);
  glm::ivec2 cmin, cmax;
  forest_cells(p, lo, hi, cmin, cmax);
  std::vector<PlacedTree> expected_part;
  for (const PlacedTree& t : all) {
    if (t.cell.x >= cmin.x && t.cell.x <= cmax.x && t.cell.y >= cmin.y && t.cell.y <= cmax.y) expected_part.push_back(t);
  }
  EXPECT_EQ(keys(part), keys(expected_part));
  EXPECT_FALSE(part.empty());
  // A different seed moves the trees.
  p.seed = 2;
  EXPECT_NE(keys(place_trees(p, nullptr, nullptr, p.area_min, p.area_max)), keys(all));
}

TEST(ForestPlacement, SpacingDensityAndGround) {
  ForestPlacement p;
  p.area_min = {0, 0};
  p.area_max = {200, 200};
  p.trees_per_hectare = 100;  // 10 m cells
  p.min_spacing = 6.0f;
  p.scale_min = 0.5f;
  p.scale_max = 0.7f;
  HeightField ground(41, 41, 5.0, {0.0, 0.0});
  for (int j = 0; j < 41; ++j)
    for (int i = 0; i < 41; ++i) ground.sample(i, j) = 0.3f * i - 0.1f * j;
  ground.update_range();
  // Density: 1 on the left half, 0 on the right.
  MapGrid density(64, 64, 0.0f, {200.0 / 128, 200.0 / 128}, {200.0 / 64, 200.0 / 64});
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 32; ++i) density.at(i, j) = 1.0f;
  const auto trees = place_trees(p, &density, &ground, p.area_min, p.area_max);
  ASSERT_GT(trees.size(), 150u);
  for (std::size_t a = 0; a < trees.size(); ++a) {
    EXPECT_LT(trees[a].position.x, 104.0) << "no trees where the density is 0";
    EXPECT_NEAR(trees[a].position.y, ground.height(trees[a].position.x, trees[a].position.z), 1e-5) << "on the ground";
    EXPECT_GE(trees[a].scale, 0.5f);
    EXPECT_LE(trees[a].scale, 0.7f);
    for (std::size_t b = a + 1; b < trees.size(); ++b) {
      EXPECT_GE(glm::distance(glm::dvec2(trees[a].position.x, trees[a].position.z), glm::dvec2(trees[b].position.x, trees[b].position.z)),
                6.0 - 1e-9);
    }
  }
  p.trees_per_hectare = 0.0f;
  EXPECT_TRUE(place_trees(p, nullptr, nullptr, p.area_min, p.area_max).empty());
}

// Clearings: about the asked share of the area is left open (in patches, not as thinning
// everywhere: the open share shows at the scale of the noise), and a sub-region still gives
// exactly the trees of the whole placement in its cells (the threshold comes from the whole area).
TEST(ForestPlacement, ClearingsOpenTheAskedShareInPatches) {
  ForestPlacement p;
  p.area_min = {-400, -400};
  p.area_max = {400, 400};
  p.trees_per_hectare = 40;
  p.clearing_size = 120.0f;
  const auto full = place_trees(p, nullptr, nullptr, p.area_min, p.area_max);
  p.clearings = 0.4f;
  const auto open = place_trees(p, nullptr, nullptr, p.area_min, p.area_max);
  const double kept = static_cast<double>(open.size()) / static_cast<double>(full.size());
  EXPECT_NEAR(kept, 0.6, 0.07);
  // Patches: most 40 m squares are either nearly full or nearly empty.
  std::map<std::pair<int, int>, int> before, after;
  for (const PlacedTree& t : full) ++before[{int(std::floor(t.position.x / 40)), int(std::floor(t.position.z / 40))}];
  for (const PlacedTree& t : open) ++after[{int(std::floor(t.position.x / 40)), int(std::floor(t.position.z / 40))}];
  int decided = 0;
  for (const auto& [square, n] : before) {
    const double share = after.count(square) ? double(after[square]) / n : 0.0;
    decided += (share < 0.2 || share > 0.8) ? 1 : 0;
  }
  // Measured 0.67 (squares of about 6 trees straddling the soft edges are the rest); thinning
  // every square to 60 % instead would decide about one square in ten.
  EXPECT_GT(double(decided) / double(before.size()), 0.55);
  const glm::dvec2 lo{-50, 10}, hi{80, 120};
  glm::ivec2 cmin, cmax;
  forest_cells(p, lo, hi, cmin, cmax);
  std::vector<PlacedTree> expected;
  for (const PlacedTree& t : open) {
    if (t.cell.x >= cmin.x && t.cell.x <= cmax.x && t.cell.y >= cmin.y && t.cell.y <= cmax.y) expected.push_back(t);
  }
  EXPECT_EQ(keys(place_trees(p, nullptr, nullptr, lo, hi)), keys(expected));
}

// Grid layout (the thesis experiments' exact arrangements): trees at every multiple of the cell
// side inside the area, none missing where the density allows them, one tree at the origin for a
// small area around it.
TEST(ForestPlacement, GridLayoutIsExact) {
  ForestPlacement p;
  p.layout = ForestLayout::kGrid;
  p.trees_per_hectare = 100;  // cell side 10 m
  p.area_min = {-25, -15};
  p.area_max = {25, 15};
  const auto trees = place_trees(p, nullptr, nullptr, p.area_min, p.area_max);
  ASSERT_EQ(trees.size(), 5u * 3u);  // x in {-20, -10, 0, 10, 20}, z in {-10, 0, 10}
  for (const PlacedTree& t : trees) {
    EXPECT_DOUBLE_EQ(std::fmod(std::abs(t.position.x), 10.0), 0.0);
    EXPECT_DOUBLE_EQ(std::fmod(std::abs(t.position.z), 10.0), 0.0);
  }
  p.area_min = {-1, -1};
  p.area_max = {1, 1};
  const auto one = place_trees(p, nullptr, nullptr, p.area_min, p.area_max);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].position, glm::dvec3(0.0));
}
