// Far field CPU parts: fades partition the distance axis, clumps follow the density map and are
// world-anchored, procedural textures have the threshold distributions the shaders rely on.
#include <sylva/grass/far_field.hpp>

#include "support/fields.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace sylva::grass {
namespace {

TEST(GrassFarField, FadesAreContinuousAndHandOver) {
  FarFieldSettings s;
  s.clump_fade_in = 10.0f;
  s.mid_distance = 120.0f;
  s.mid_fade = 30.0f;
  s.far_distance = 1000.0f;
  s.far_fade = 100.0f;
  const float near = 50.0f;
  float prev_c = clump_fade(0.0f, near, s), prev_g = ground_fade(0.0f, s);
  for (float d = 0.0f; d < 1200.0f; d += 0.25f) {
    const float c = clump_fade(d, near, s), g = ground_fade(d, s);
    EXPECT_GE(c, 0.0f);
    EXPECT_LE(c, 1.0f);
    EXPECT_LE(std::abs(c - prev_c), 0.25f / 10.0f + 1e-5f) << d;  // Lipschitz: no jumps
    EXPECT_LE(std::abs(g - prev_g), 0.25f / 30.0f + 1e-5f) << d;
    // Clumps hand over to the ground layer: their weights sum to 1 across the mid band.
    if (d >= near && d <= s.mid_distance) {
      EXPECT_NEAR(c + g, 1.0f, 1e-5f) << d;
    }
    prev_c = c;
    prev_g = g;
  }
  EXPECT_EQ(clump_fade(near - 10.0f, near, s), 0.0f);
  EXPECT_EQ(clump_fade(near, near, s), 1.0f);
  EXPECT_EQ(ground_fade(s.mid_distance, s), 1.0f);
  EXPECT_EQ(ground_fade(s.far_distance, s), 0.0f);
}

TEST(GrassFarField, ClumpsFollowTheMapAndAreWorldAnchored) {
  GrassFieldSettings field;
  BladeSettings blade;
  FarFieldSettings far;
  far.clumps_per_m2 = 2.0f;
  const Image density = testing::make_density_image(32, 32);
  const HeightField ground = testing::make_ground(-10.0, 110.0);
  const GrassMaps maps = GrassMaps::from_images({{0, 0}, {100, 100}}, &density, nullptr, nullptr).value();
  auto a = generate_clumps(field, blade, maps, ground, {50, 0, 50}, far);
  ASSERT_TRUE(a.ok()) << a.error().message;
  const double expected = maps.density_integral(maps.rect()) * far.clumps_per_m2;
  EXPECT_NEAR(static_cast<double>(a->clumps.size()), expected, 0.01 * expected);
  for (const GrassTile& t : a->tiles) EXPECT_LT(std::abs(t.count - t.expected), 1.0);
  auto b = generate_clumps(field, blade, maps, ground, {50, 0, 50}, far);
  ASSERT_EQ(a->clumps.size(), b->clumps.size());
  EXPECT_EQ(std::memcmp(a->clumps.data(), b->clumps.data(), a->clumps.size() * sizeof(Clump)), 0);
  for (const Clump& c : a->clumps) {
    EXPECT_NEAR(c.root.y + 0.0f, ground.height(c.root.x + 50.0, c.root.z + 50.0), 1e-3);
    EXPECT_GT(c.size.y, 0.0f);
    EXPECT_GE(c.size.w, 0.0f);
    EXPECT_LE(c.size.w, 3.0f);
  }
  FarFieldSettings bad = far;
  bad.clumps_per_m2 = -1.0f;
  auto e = generate_clumps(field, blade, maps, ground, {0, 0, 0}, bad);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.error().message.find("grass.far.clumps_per_m2"), std::string::npos);
}

// Seed 003 Tab. 4.2: 20 wide billboards per 5 x 5-tile group at the densest, 20 ceil(N/5)^2 for
// an N x N map of 1 m tiles (groups clipped to the map), each no wider than its group.
TEST(GrassFarField, WideBillboardsAreTwentyPerGroupOfFiveByFiveTiles) {
  GrassFieldSettings field;
  field.tile_size = 1.0f;
  BladeSettings blade;
  FarFieldSettings far;
  far.wide_billboards = true;
  const HeightField ground = testing::make_ground(-10.0, 110.0);
  for (const int n : {1, 4, 8, 32, 64}) {
    Image ones(8, 8, 1);
    for (float& v : ones.data()) v = 1.0f;
    const GrassMaps maps = GrassMaps::from_images({{0, 0}, {n, n}}, &ones, nullptr, nullptr).value();
    auto w = generate_wide_billboards(field, blade, maps, ground, {0, 0, 0}, far);
    ASSERT_TRUE(w.ok()) << w.error().message;
    const int groups = (n + 4) / 5;
    EXPECT_EQ(static_cast<int>(w->tiles.size()), groups * groups) << n;
    EXPECT_NEAR(static_cast<double>(w->clumps.size()), 20.0 * groups * groups, 0.5 * groups) << n;  // thesis: 20, 20, 80, 980, 3380
    for (const Clump& c : w->clumps) {
      EXPECT_LE(c.size.x, std::min(5.0f, static_cast<float>(n)) + 1e-4f);
      EXPECT_GT(c.size.z, 0.0f);  // the group's strand keep
      EXPECT_LE(c.size.z, 1.0f);
    }
  }
  // The wide level takes over from the small clumps: their fades add up to one clump's fade.
  far.wide_distance = 80.0f;
  far.wide_fade = 20.0f;
  for (float d = 0.0f; d < 300.0f; d += 2.5f) {
    FarFieldSettings off = far;
    off.wide_billboards = false;
    EXPECT_NEAR(clump_fade(d, 50.0f, far) + wide_fade_at(d, 50.0f, far), clump_fade(d, 50.0f, off), 1e-6f) << d;
  }
  EXPECT_EQ(wide_fade_at(55.0f, 50.0f, far), 0.0f);
  EXPECT_EQ(clump_fade(100.0f, 50.0f, far), 0.0f);
  // Threshold shift: a full 5 m group of 20 billboards has 4 m of strands per m^2 against the small
  // clumps' 0.81, so each wide strand is kept with 0.2025.
  EXPECT_NEAR(wide_keep(far, 25.0, 5.0f), 0.81f / 4.0f, 1e-6f);
}

TEST(GrassFarField, GroundTextureAlphaIsUniformAndTiles) {
  const Image tex = make_ground_texture(64, 3);
  // Equalised: the share of texels below t is t.
  for (const float t : {0.1f, 0.25f, 0.5f, 0.9f}) {
    int below = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x) below += tex.at(x, y, 3) < t;
    EXPECT_NEAR(below / 4096.0, t, 0.01);
  }
  // Tileable: the wrap-around step is no larger than an interior step (colour channel).
  double edge = 0.0, inner = 0.0;
  for (int y = 0; y < 64; ++y) {
    edge += std::abs(tex.at(63, y, 1) - tex.at(0, y, 1));
    inner += std::abs(tex.at(31, y, 1) - tex.at(32, y, 1));
  }
  EXPECT_LT(edge, 2.0 * inner + 0.5);
}

TEST(GrassFarField, ClumpAtlasThresholdsAreGraded) {
  const Image atlas = make_clump_atlas(128, 9);
  // Covered share grows steadily with the threshold (strands appear one by one).
  double prev = 0.0;
  for (int k = 1; k <= 10; ++k) {
    int covered = 0;
    for (int y = 0; y < 128; ++y)
      for (int x = 0; x < 128; ++x) covered += atlas.at(x, y, 3) < k / 10.0f;
    const double share = covered / (128.0 * 128.0);
    EXPECT_GT(share, prev) << k;
    prev = share;
  }
  EXPECT_GT(prev, 0.15);  // a full clump covers a good part of its quad
  EXPECT_LT(prev, 0.9);
}

}  // namespace
}  // namespace sylva::grass
