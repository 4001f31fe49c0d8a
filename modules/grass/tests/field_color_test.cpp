// The field colour (field_color.hpp) and the far field's map margins (extend_maps):
//  - the colour multiplier averages to (1, 1, 1) over a field, so the variation settings do not
//    shift the field's mean colour (the far layers' calibration relies on it); it varies in
//    patches (dry yellow-green against lush green) and per clump cell; it is deterministic,
//    bounded, and (1, 1, 1) for non-finite input or zero variation;
//  - extended maps keep the original maps inside the rectangle and continue their edge outside;
//  - far grass (clumps, ground layer) thins out between max_slope_deg - 8 and max_slope_deg.
#include <sylva/grass/far_field.hpp>
#include <sylva/grass/field_color.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva::grass {
namespace {

TEST(GrassFieldColor, AveragesToOneAndVariesInPatchesAndClumps) {
  const BladeSettings blade;
  glm::dvec3 sum(0.0);
  double red_spread = 0.0;
  int n = 0;
  for (double z = -200.0; z < 200.0; z += 0.37) {
    for (double x = -200.0; x < 200.0; x += 1.13) {
      const glm::vec3 c = field_color(x, z, blade, 7u);
      ASSERT_TRUE(glm::all(glm::greaterThanEqual(c, glm::vec3(0.3f))) && glm::all(glm::lessThanEqual(c, glm::vec3(1.7f))));
      sum += glm::dvec3(c);
      red_spread += std::abs(c.r - 1.0);
      ++n;
    }
  }
  const glm::dvec3 mean = sum / static_cast<double>(n);
  for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(mean[ch], 1.0, 0.03) << "channel " << ch;
  EXPECT_GT(red_spread / n, 0.08) << "patches and clumps vary the colour";

  // Dry patches are yellower: red and blue move in opposite directions across the field.
  double cov = 0.0;
  for (double x = 0.0; x < 400.0; x += 3.1) {
    const glm::vec3 c = field_color(x, 11.0, blade, 7u);
    cov += (c.r - 1.0) * (c.b - 1.0);
  }
  EXPECT_LT(cov, 0.0);

  // Neighbours within one clump cell share the clump's offset; patches change over metres.
  BladeSettings clumps_only = blade;
  clumps_only.patch_variation = 0.0f;
  const float cs = clumps_only.clump_size;
  EXPECT_EQ(field_color(0.1 * cs, 0.1 * cs, clumps_only, 7u), field_color(0.8 * cs, 0.9 * cs, clumps_only, 7u));
  int differing = 0;
  for (int i = 0; i < 20; ++i) differing += field_color((i + 0.5) * cs, 0.5 * cs, clumps_only, 7u) != field_color(0.5 * cs, 0.5 * cs, clumps_only, 7u);
  EXPECT_GE(differing, 15);
}

TEST(GrassFieldColor, DeterministicAndNeutralWhereItShouldBe) {
  BladeSettings blade;
  EXPECT_EQ(field_color(12.5, -3.25, blade, 1u), field_color(12.5, -3.25, blade, 1u));
  EXPECT_NE(field_color(12.5, -3.25, blade, 1u), field_color(12.5, -3.25, blade, 2u));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(field_color(nan, 0.0, blade, 1u), glm::vec3(1.0f));
  EXPECT_EQ(field_color(0.0, inf, blade, 1u), glm::vec3(1.0f));
  blade.patch_variation = 0.0f;
  blade.clump_variation = 0.0f;
  EXPECT_EQ(field_color(5.0, 6.0, blade, 1u), glm::vec3(1.0f));
}

TEST(GrassFieldColor, ExtendedMapsContinueTheEdge) {
  Image density(4, 4, 1);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) density.at(x, y, 0) = 0.25f * static_cast<float>(x);  // 0 .. 0.75 along +x
  const auto maps = GrassMaps::from_images({{0.0, 0.0}, {8.0, 8.0}}, &density, nullptr, nullptr);
  ASSERT_TRUE(maps.ok());
  const auto wide = extend_maps(*maps, 10.0);
  ASSERT_TRUE(wide.ok()) << wide.error().message;
  EXPECT_EQ(wide->rect().min, glm::dvec2(-10.0));
  EXPECT_EQ(wide->rect().max, glm::dvec2(18.0));
  for (double z : {1.0, 4.0, 7.0}) {
    for (double x : {1.0, 3.0, 5.0, 7.0}) EXPECT_NEAR(wide->density(x, z), maps->density(x, z), 0.13) << x << ", " << z;
    EXPECT_NEAR(wide->density(-9.0, z), maps->density(0.01, z), 1e-4);  // left of the map: its left edge
    EXPECT_NEAR(wide->density(17.0, z), maps->density(7.99, z), 1e-4);  // right of it: its right edge
  }
  EXPECT_NEAR(wide->density(4.0, 17.0), maps->density(4.0, 7.99), 0.13);
  const auto same = extend_maps(*maps, 0.0);
  ASSERT_TRUE(same.ok());
  EXPECT_EQ(same->rect().max, maps->rect().max);
}

TEST(GrassFieldColor, FarGrassThinsOutOnSteepSlopes) {
  auto y = [](float deg) { return std::cos(deg * 3.14159265f / 180.0f); };
  EXPECT_EQ(slope_keep(1.0f, 40.0f), 1.0f);
  EXPECT_EQ(slope_keep(y(31.0f), 40.0f), 1.0f);
  EXPECT_NEAR(slope_keep(y(36.0f), 40.0f), 0.5f, 1e-3f);
  EXPECT_EQ(slope_keep(y(41.0f), 40.0f), 0.0f);
  EXPECT_EQ(slope_keep(y(80.0f), 90.0f), 1.0f);  // 90 degrees: grass on any slope
}

// Seed 003 §3.4 motion by colour: the phase 2 pi f t is reduced in double precision, so it is
// exact after days of simulation time, and bad times give phase 0.
TEST(GrassFieldColor, ColorMotionPhaseStaysExactForLongTimes) {
  constexpr double kTwoPi = 6.283185307179586;
  EXPECT_FLOAT_EQ(color_motion_uniform(0.3f, 0.5f, 0.5).y, static_cast<float>(kTwoPi / 4.0));
  EXPECT_EQ(color_motion_uniform(0.3f, 0.5f, 0.5).x, 0.3f);
  const double day = 86400.0 * 3.0 + 0.5;  // 3 days + a quarter period at 0.5 Hz
  EXPECT_NEAR(color_motion_uniform(0.3f, 0.5f, day).y, kTwoPi / 4.0, 1e-6);
  for (const double t : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -1e300}) {
    const glm::vec2 u = color_motion_uniform(0.3f, 0.5f, t);
    EXPECT_TRUE(std::isfinite(u.y)) << t;
    EXPECT_GE(u.y, 0.0f) << t;
    EXPECT_LE(u.y, static_cast<float>(kTwoPi)) << t;
  }
}

}  // namespace
}  // namespace sylva::grass
