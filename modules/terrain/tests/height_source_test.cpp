// Height fields from images through core (seed 002 §3.1 reads a grey-scale map; the issue asks
// for 16-bit PNG, float EXR/TIFF and 8-bit with a warning), any size, with world scale, height
// scale and offset; errors name the file.
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>
#include <sylva/terrain/chunk_tree.hpp>
#include <sylva/terrain/height_source.hpp>

#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace sylva::terrain {
namespace {

std::filesystem::path temp(const char* name) { return testing::unique_temp(name); }

// Captures warnings while alive.
struct WarningCapture {
  std::vector<std::string> warnings;
  WarningCapture() {
    set_log_sink([this](LogLevel level, std::string_view m) {
      if (level == LogLevel::kWarn) warnings.emplace_back(m);
    });
  }
  ~WarningCapture() { set_log_sink(nullptr); }
};

TEST(HeightSource, EightBitImageLoadsWithAQuantisationWarning) {
  Image img(33, 17, 1, PixelFormat::kU8);
  for (int y = 0; y < 17; ++y)
    for (int x = 0; x < 33; ++x) img.at(x, y) = static_cast<float>((x + y) % 256) / 255.0f;
  const auto path = temp("sylva_terrain_u8.png");
  ASSERT_TRUE(write_image(path, img, PixelFormat::kU8).ok());
  HeightImageSettings hs;
  hs.height_scale = 255.0;
  WarningCapture capture;
  auto f = load_height_field(path, hs);
  std::filesystem::remove(path);
  ASSERT_TRUE(f.ok()) << f.error().describe();
  EXPECT_EQ(f->columns(), 33);
  EXPECT_EQ(f->rows(), 17);
  EXPECT_NEAR(f->sample(5, 3), 8.0f, 1e-3f);
  ASSERT_EQ(capture.warnings.size(), 1u);
  EXPECT_NE(capture.warnings[0].find("8-bit"), std::string::npos) << capture.warnings[0];
  EXPECT_NE(capture.warnings[0].find("sylva_terrain_u8.png"), std::string::npos) << capture.warnings[0];
}

TEST(HeightSource, SixteenBitPngHasNoWarningAndKeepsEveryLevel) {
  Image img(21, 6, 1, PixelFormat::kU16);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 21; ++x) img.at(x, y) = static_cast<float>(x * 3000 + y) / 65535.0f;
  const auto path = temp("sylva_terrain_u16_levels.png");
  ASSERT_TRUE(write_image(path, img, PixelFormat::kU16).ok());
  HeightImageSettings hs;
  hs.height_scale = 65535.0;  // one metre per level
  WarningCapture capture;
  auto f = load_height_field(path, hs);
  std::filesystem::remove(path);
  ASSERT_TRUE(f.ok()) << f.error().describe();
  EXPECT_TRUE(capture.warnings.empty());
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 21; ++x) EXPECT_NEAR(f->sample(x, y), x * 3000.0f + y, 1e-2f) << x << "," << y;
}

// Float TIFF and EXR, non-power-of-two and non-square, with spacing, scale and offset; the tree
// builds on them (padding to the quadtree grid).
TEST(HeightSource, FloatTiffAndExrWithWorldScaleHeightScaleAndOffset) {
  Image img(45, 19, 1, PixelFormat::kF32);
  for (int y = 0; y < 19; ++y)
    for (int x = 0; x < 45; ++x) img.at(x, y) = 0.01f * static_cast<float>(x) - 0.02f * static_cast<float>(y);
  for (const char* name : {"sylva_terrain_f32.tif", "sylva_terrain_f32.exr"}) {
    const auto path = temp(name);
    ASSERT_TRUE(write_image(path, img, PixelFormat::kF32).ok()) << name;
    HeightImageSettings hs;
    hs.spacing = 2.5;
    hs.height_scale = 100.0;
    hs.height_offset = 40.0;
    auto f = load_height_field(path, hs);
    std::filesystem::remove(path);
    ASSERT_TRUE(f.ok()) << f.error().describe();
    EXPECT_EQ(f->columns(), 45);
    EXPECT_EQ(f->rows(), 19);
    EXPECT_DOUBLE_EQ(f->spacing(), 2.5);
    EXPECT_NEAR(f->sample(30, 10), 100.0f * (0.3f - 0.2f) + 40.0f, 1e-3f) << name;
    EXPECT_NEAR(f->extent().x, 44 * 2.5, 1e-9);
    auto tree = ChunkTree::build(*f, ChunkTreeSettings{});
    ASSERT_TRUE(tree.ok()) << tree.error().describe();
    EXPECT_EQ(tree->field_columns(), 45);
  }
}

TEST(HeightSource, MissingAndCorruptFilesNameTheFile) {
  auto missing = load_height_field(temp("sylva_terrain_does_not_exist.png"), {});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("sylva_terrain_does_not_exist.png"), std::string::npos) << missing.error().message;
  const auto path = temp("sylva_terrain_garbage.png");
  {
    std::FILE* f = std::fopen(path.string().c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fputs("not a png at all", f);
    std::fclose(f);
  }
  auto corrupt = load_height_field(path, {});
  std::filesystem::remove(path);
  ASSERT_FALSE(corrupt.ok());
  EXPECT_NE(corrupt.error().message.find("sylva_terrain_garbage.png"), std::string::npos) << corrupt.error().message;
}

}  // namespace
}  // namespace sylva::terrain
