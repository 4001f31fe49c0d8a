// The GL-free half of the terrain material (material.hpp): altitude lines for a latitude and a
// season, the tiling detail noise, and the per-sample shape (normal, curvature).
#include <sylva/terrain/material.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::terrain {
namespace {

using namespace testing;

TEST(TerrainMaterial, LatitudeScalesTheLinesLikeMeasuredOnes) {
  EXPECT_NEAR(latitude_factor(45.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(latitude_factor(0.0f), 2.0f, 1e-6f);
  EXPECT_NEAR(latitude_factor(60.0f), 0.5f, 1e-6f);
  EXPECT_NEAR(latitude_factor(-60.0f), 0.5f, 1e-6f);
  EXPECT_NEAR(latitude_factor(90.0f), 0.0f, 1e-6f);
  EXPECT_NEAR(latitude_factor(200.0f), 0.0f, 1e-6f);  // clamped
  MaterialSettings m;
  const MaterialLines summer45 = material_lines(m, {45.0f, 0.4f});
  EXPECT_NEAR(summer45.snow, 2800.0f, 1e-2f);
  EXPECT_NEAR(summer45.rock, 2500.0f, 1e-2f);
  EXPECT_NEAR(summer45.tree, 2000.0f, 1e-2f);
  // Alps (46 N) summer ~2700 m, Norway (61 N) ~1300 m, tropics ~5600 m.
  EXPECT_NEAR(material_lines(m, {46.0f, 0.4f}).snow, 2702.0f, 5.0f);
  EXPECT_NEAR(material_lines(m, {61.0f, 0.4f}).snow, 1317.0f, 5.0f);
  EXPECT_NEAR(material_lines(m, {0.0f, 0.4f}).snow, 5600.0f, 1e-1f);
}

TEST(TerrainMaterial, OnlySnowFollowsTheSeasonAndTheHemisphere) {
  MaterialSettings m;
  const MaterialLines summer = material_lines(m, {45.0f, 0.4f}), winter = material_lines(m, {45.0f, 0.9f});
  EXPECT_NEAR(winter.snow, 2800.0f * (1.0f - 0.8f), 1.0f);
  EXPECT_EQ(winter.rock, summer.rock);
  EXPECT_EQ(winter.tree, summer.tree);
  // Spring (0.15) lies between; the southern hemisphere's winter is the northern summer.
  const float spring = material_lines(m, {45.0f, 0.15f}).snow;
  EXPECT_GT(spring, winter.snow);
  EXPECT_LT(spring, summer.snow);
  EXPECT_NEAR(material_lines(m, {-45.0f, 0.4f}).snow, winter.snow, 1e-2f);
  EXPECT_NEAR(material_lines(m, {-45.0f, 0.9f}).snow, summer.snow, 1e-2f);
  // No seasons at the equator; snow comes down to the sea (~30 m) at 60 N in late winter.
  EXPECT_NEAR(material_lines(m, {0.0f, 0.9f}).snow, material_lines(m, {0.0f, 0.4f}).snow, 1e-2f);
  EXPECT_LT(material_lines(m, {60.0f, 0.9f}).snow, 50.0f);
}

TEST(TerrainMaterial, LinesAreWorldHeightsAboveTheBaseAltitude) {
  MaterialSettings m;
  m.base_altitude_m = 1200.0f;
  m.water_level_m = 1250.0f;
  const MaterialLines l = material_lines(m, {45.0f, 0.4f});
  EXPECT_NEAR(l.snow, 1600.0f, 1e-2f);
  EXPECT_NEAR(l.water, 50.0f, 1e-6f);
  // Non-finite climate values fall back to the defaults instead of poisoning the shader.
  const MaterialLines nan = material_lines(m, {std::nanf(""), std::numeric_limits<float>::infinity()});
  EXPECT_EQ(nan.snow, material_lines(m, Climate{}).snow);
}

TEST(TerrainMaterial, DetailNoiseTilesWithFixedStatistics) {
  const Image a = make_detail_noise(64, 3u), b = make_detail_noise(64, 3u), c = make_detail_noise(64, 4u);
  ASSERT_EQ(a.channels(), 4);
  EXPECT_TRUE(std::equal(a.data().begin(), a.data().end(), b.data().begin())) << "not deterministic";
  EXPECT_FALSE(std::equal(a.data().begin(), a.data().end(), c.data().begin())) << "the seed changes nothing";
  for (int ch = 0; ch < 4; ++ch) {
    double sum = 0.0, sum2 = 0.0, step_inside = 0.0, step_wrap = 0.0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) {
        sum += a.at(x, y, ch);
        sum2 += a.at(x, y, ch) * a.at(x, y, ch);
        if (x + 1 < 64) step_inside += std::fabs(a.at(x + 1, y, ch) - a.at(x, y, ch)) / 63.0;
      }
    for (int y = 0; y < 64; ++y) step_wrap += std::fabs(a.at(0, y, ch) - a.at(63, y, ch));
    const double n = 64.0 * 64.0, mean = sum / n;
    if (ch < 2) {
      EXPECT_NEAR(mean, 0.0, 1e-4) << ch;
      EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), 0.4, 1e-3) << ch;
    }
    // Across the tile's seam the noise steps no more than between neighbours inside it.
    EXPECT_LT(step_wrap / 64.0, 2.0 * step_inside / 64.0) << "channel " << ch << " does not tile";
  }
  double g2 = 0.0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) g2 += a.at(x, y, 2) * a.at(x, y, 2) + a.at(x, y, 3) * a.at(x, y, 3);
  EXPECT_NEAR(g2 / (2.0 * 64 * 64), 1.0, 1e-3);
}

TEST(TerrainMaterial, CurvatureTellsHollowsFromRidges) {
  // A bowl (hollow) in the west half and a dome (ridge) in the east, on a 2 m grid.
  const HeightField f = make_field(101, 41, 2.0, [](int i, int j) {
    const double z = (j - 20) * 2.0;
    const double xb = (i - 25) * 2.0, xd = (i - 75) * 2.0;
    return static_cast<float>(i < 50 ? 0.01 * (xb * xb + z * z) : -0.01 * (xd * xd + z * z));
  });
  std::vector<float> out;
  compute_terrain_shape(f, 10.0f, 0, 0, f.columns(), f.rows(), out);
  ASSERT_EQ(out.size(), 101u * 41u * 4u);
  auto at = [&](int i, int j, int c) { return out[(static_cast<std::size_t>(j) * 101 + i) * 4 + c]; };
  EXPECT_GT(at(25, 20, 2), 0.05f) << "a bowl's bottom is a hollow";
  EXPECT_LT(at(75, 20, 2), -0.05f) << "a dome's top is a ridge";
  // The normal of the bowl's west flank points east (+x) and up.
  EXPECT_GT(at(15, 20, 0), 0.1f);
  EXPECT_NEAR(at(15, 20, 1), 0.0f, 1e-3f);
  // A sub-rectangle holds exactly the full computation's samples.
  std::vector<float> part;
  compute_terrain_shape(f, 10.0f, 40, 5, 60, 30, part);
  ASSERT_EQ(part.size(), 20u * 25u * 4u);
  for (int j = 5; j < 30; ++j)
    for (int i = 40; i < 60; ++i)
      for (int c = 0; c < 4; ++c) ASSERT_EQ(part[(static_cast<std::size_t>(j - 5) * 20 + (i - 40)) * 4 + c], at(i, j, c));
  // A radius under half a sample spacing gives no curvature; empty and NaN radii are safe.
  compute_terrain_shape(f, 0.5f, 0, 0, 101, 41, out);
  EXPECT_EQ(out[(20 * 101 + 25) * 4 + 2], 0.0f);
  compute_terrain_shape(f, std::nanf(""), 0, 0, 101, 41, out);
  EXPECT_EQ(out[(20 * 101 + 25) * 4 + 2], 0.0f);
  compute_terrain_shape(f, 10.0f, 60, 0, 40, 41, out);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace sylva::terrain
