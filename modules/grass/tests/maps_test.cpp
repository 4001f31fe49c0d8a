// Control maps: sampling conventions and the exact density integral the blade count relies on.
#include <sylva/grass/maps.hpp>
#include <sylva/grass/uv_density_map.hpp>

#include "support/fields.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::grass {
namespace {

double brute_integral(const GrassMaps& maps, const Rect& r, int n) {
  double sum = 0.0;
  const glm::dvec2 step = r.size() / static_cast<double>(n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) sum += maps.density(r.min.x + (i + 0.5) * step.x, r.min.y + (j + 0.5) * step.y);
  return sum * step.x * step.y;
}

TEST(GrassMaps, SamplesPixelCentresAndOrientation) {
  Image img(4, 2, 1);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) img.at(i, j) = 0.1f * static_cast<float>(i + 4 * j);
  auto maps = GrassMaps::from_images({{10.0, 20.0}, {18.0, 24.0}}, &img, nullptr, nullptr);
  ASSERT_TRUE(maps.ok()) << maps.error().message;
  // Pixel (i, j) covers x in [10 + 2i, 12 + 2i], z in [20 + 2j, 22 + 2j]: image y runs along +z.
  EXPECT_NEAR(maps->density(11.0, 21.0), img.at(0, 0), 1e-6);
  EXPECT_NEAR(maps->density(17.0, 23.0), img.at(3, 1), 1e-6);
  EXPECT_NEAR(maps->density(12.0, 21.0), 0.5f * (img.at(0, 0) + img.at(1, 0)), 1e-6);
  // Clamped to the edge inside, zero outside.
  EXPECT_NEAR(maps->density(10.0, 20.0), img.at(0, 0), 1e-6);
  EXPECT_EQ(maps->density(9.99, 21.0), 0.0f);
  EXPECT_EQ(maps->height_scale(11.0, 21.0), 1.0f);
  EXPECT_EQ(maps->tint(11.0, 21.0), glm::vec3(1.0f));
}

TEST(GrassMaps, DensityIntegralIsExact) {
  const Image img = testing::make_density_image(13, 9);
  auto maps = GrassMaps::from_images({{-5.0, 3.0}, {21.0, 21.0}}, &img, nullptr, nullptr);
  ASSERT_TRUE(maps.ok());
  const Rect cases[] = {{{-5.0, 3.0}, {21.0, 21.0}}, {{0.3, 4.1}, {7.7, 9.9}}, {{-9.0, -2.0}, {-4.0, 5.0}},
                        {{15.5, 18.0}, {30.0, 40.0}}, {{2.0, 2.0}, {2.5, 2.5}}};
  for (const Rect& r : cases) {
    const double exact = maps->density_integral(r);
    const Rect clip = r.intersect(maps->rect());
    const double brute = clip.empty() ? 0.0 : brute_integral(*maps, clip, 1200);
    EXPECT_NEAR(exact, brute, 1e-4 * std::max(1.0, brute)) << r.min.x << "," << r.min.y;
  }
  // Additivity: the four quarters sum to the whole.
  const Rect whole{{-5.0, 3.0}, {21.0, 21.0}};
  const glm::dvec2 mid(4.2, 11.7);
  const double quarters = maps->density_integral({whole.min, mid}) + maps->density_integral({{mid.x, whole.min.y}, {whole.max.x, mid.y}}) +
                          maps->density_integral({{whole.min.x, mid.y}, {mid.x, whole.max.y}}) + maps->density_integral({mid, whole.max});
  EXPECT_NEAR(quarters, maps->density_integral(whole), 1e-9 * maps->density_integral(whole));
}

TEST(GrassMaps, BadInputNamesTheMap) {
  Image empty;
  auto a = GrassMaps::from_images({{0, 0}, {1, 1}}, &empty, nullptr, nullptr);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.error().message.find("density map"), std::string::npos);
  Image gray(4, 4, 1);
  auto b = GrassMaps::from_images({{0, 0}, {1, 1}}, nullptr, nullptr, &gray);
  ASSERT_FALSE(b.ok());
  EXPECT_NE(b.error().message.find("tint map"), std::string::npos);
  auto c = GrassMaps::from_images({{0, 0}, {0, 1}}, &gray, nullptr, nullptr);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("rectangle"), std::string::npos);
}

TEST(GrassMaps, NonFiniteValuesReadAsZero) {
  Image img(2, 2, 1);
  img.at(0, 0) = std::nanf("");
  img.at(1, 0) = INFINITY;
  img.at(0, 1) = 2.0f;  // clamped to 1
  img.at(1, 1) = -1.0f; // clamped to 0
  auto maps = GrassMaps::from_images({{0, 0}, {2, 2}}, &img, nullptr, nullptr);
  ASSERT_TRUE(maps.ok());
  EXPECT_EQ(maps->density(0.5, 0.5), 0.0f);
  EXPECT_EQ(maps->density(1.5, 0.5), 0.0f);
  EXPECT_EQ(maps->density(0.5, 1.5), 1.0f);
  EXPECT_TRUE(std::isfinite(maps->density_integral(maps->rect())));
  EXPECT_NEAR(maps->density_integral(maps->rect()), 1.0, 1e-9);
}

TEST(GrassMaps, Seed001ControlTexture) {
  Image ctl(8, 8, 3);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      ctl.at(i, j, 0) = 0.5f;                   // density
      ctl.at(i, j, 1) = 0.25f;                  // blade height scale
      ctl.at(i, j, 2) = i / 7.0f;               // terrain: dark = high
    }
  const Rect rect{{0, 0}, {16, 16}};
  auto maps = GrassMaps::from_control_texture(ctl, rect);
  ASSERT_TRUE(maps.ok());
  EXPECT_NEAR(maps->density(5, 5), 0.5f, 1e-6);
  EXPECT_NEAR(maps->height_scale(5, 5), 0.25f, 1e-6);
  EXPECT_NEAR(maps->density_integral(rect), 0.5 * 256.0, 1e-9);
  auto terrain = control_texture_terrain(ctl, rect, 30.0);
  ASSERT_TRUE(terrain.ok());
  EXPECT_NEAR(terrain->height(1.0, 1.0), 30.0, 1e-4);   // pixel 0: B = 0 -> highest
  EXPECT_NEAR(terrain->height(15.0, 1.0), 0.0, 1e-4);   // pixel 7: B = 1 -> ground level
  Image gray(4, 4, 1);
  EXPECT_FALSE(GrassMaps::from_control_texture(gray, rect).ok());
  EXPECT_FALSE(control_texture_terrain(gray, rect, 30.0).ok());
}

}  // namespace
}  // namespace sylva::grass

// Density over a mesh's UVs (issue 16): channel 0 (red), bilinear between pixel centres, clamped
// to the edge inside [0, 1] (u = 1 is the right column, not a blend with the left one), repeating
// outside; non-finite UVs read 0.
namespace sylva::grass {
TEST(UvDensityMap, SamplesClampsInsideAndRepeatsOutside) {
  Image image(4, 2, 3);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      image.at(i, j, 0) = i < 2 ? 0.0f : 1.0f;  // red: left half 0
      image.at(i, j, 1) = 0.5f;
    }
  auto map = UvDensityMap::create(image, "test map");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_FLOAT_EQ(map->sample({0.125f, 0.25f}), 0.0f);  // pixel centres
  EXPECT_FLOAT_EQ(map->sample({0.875f, 0.75f}), 1.0f);
  EXPECT_FLOAT_EQ(map->sample({0.5f, 0.5f}), 0.5f);     // between columns 1 and 2
  EXPECT_FLOAT_EQ(map->sample({1.0f, 0.5f}), 1.0f);     // the right edge, clamped
  EXPECT_FLOAT_EQ(map->sample({0.0f, 0.5f}), 0.0f);
  EXPECT_FLOAT_EQ(map->sample({-0.125f, -0.25f}), 1.0f);  // repeats: (0.875, 0.75), where clamping gives 0
  EXPECT_FLOAT_EQ(map->sample({1.125f, 0.5f}), 0.0f);     // (0.125, 0.5), where clamping gives 1
  EXPECT_EQ(map->sample({std::nanf(""), 0.5f}), 0.0f);
  EXPECT_FALSE(UvDensityMap::create(Image(), "test map").ok());
}
}  // namespace sylva::grass
