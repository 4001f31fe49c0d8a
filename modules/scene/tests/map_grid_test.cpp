// Map grids: placement, bit-exact copy/paste of rectangles, changed areas, and map files
// (float files lossless, 16-bit PNG within one level; a failed write keeps the old file).
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/file_fault.hpp>
#include <sylva/scene/height_source.hpp>
#include <sylva/scene/map_grid.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace sylva::scene;

namespace {
fs::path temp_dir() {
  const fs::path dir = fs::temp_directory_path() / ("sylva_scene_maps_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

MapGrid ramp(int w, int h) {
  MapGrid g(w, h, 0.0f, {-10.0, 5.0}, {0.5, 0.25});
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) g.at(i, j) = std::sin(0.37f * i) * 0.4f + 0.5f + 0.001f * j;
  return g;
}
}  // namespace

TEST(MapGrid, PlacementAndRectangles) {
  const MapGrid g = ramp(8, 6);
  EXPECT_EQ(g.world(0, 0), glm::dvec2(-10.0, 5.0));
  EXPECT_EQ(g.world(2, 4), glm::dvec2(-9.0, 6.0));
  EXPECT_EQ(g.texel({-9.0, 6.0}), glm::dvec2(2.0, 4.0));
  const TexelRect r{2, 1, 5, 4};
  EXPECT_EQ(r.intersect({4, 0, 10, 2}), (TexelRect{4, 1, 5, 2}));
  EXPECT_TRUE(r.intersect({6, 0, 9, 9}).empty());
  EXPECT_EQ(r.unite({}), r);
  EXPECT_EQ(r.unite({0, 0, 1, 1}), (TexelRect{0, 0, 5, 4}));
  const WorldArea a = changed_world_area(g, r);
  EXPECT_EQ(a.min, g.world(1, 0));
  EXPECT_EQ(a.max, g.world(5, 4));
}

TEST(MapGrid, CopyPasteIsBitExact) {
  MapGrid g = ramp(16, 9);
  const MapGrid original = g;
  const TexelRect r{3, 2, 11, 9};
  const std::vector<float> saved = g.copy_rect(r);
  ASSERT_EQ(saved.size(), 8u * 7u);
  for (int j = r.y0; j < r.y1; ++j)
    for (int i = r.x0; i < r.x1; ++i) g.at(i, j) = std::nextafter(g.at(i, j), 10.0f) * 3.0f;
  g.paste_rect(r, saved);
  EXPECT_EQ(std::memcmp(g.values.data(), original.values.data(), g.values.size() * sizeof(float)), 0);
  // Rectangles sticking out of the grid are clipped.
  const std::vector<float> clipped = g.copy_rect({14, 7, 20, 20});
  EXPECT_EQ(clipped.size(), 2u * 2u);
}

TEST(MapGrid, FloatFilesAreLosslessAndPngKeeps16Bits) {
  const MapGrid g = ramp(33, 17);
  const fs::path exr = temp_dir() / "m.exr";
  ASSERT_TRUE(write_map_image(exr, g, 1.0f, 0.0f).ok());
  auto back = read_map_image(exr, 1.0f, 0.0f, g.texel_origin, g.texel_size);
  ASSERT_TRUE(back.ok()) << back.error().message;
  ASSERT_EQ(back->width, 33);
  ASSERT_EQ(back->height, 17);
  EXPECT_EQ(std::memcmp(back->values.data(), g.values.data(), g.values.size() * sizeof(float)), 0);

  const fs::path png = temp_dir() / "m.png";
  ASSERT_TRUE(write_map_image(png, g, 1.0f, 0.0f).ok());
  auto png_back = read_map_image(png, 1.0f, 0.0f, g.texel_origin, g.texel_size);
  ASSERT_TRUE(png_back.ok()) << png_back.error().message;
  for (std::size_t k = 0; k < g.values.size(); ++k) EXPECT_NEAR(png_back->values[k], g.values[k], 0.51 / 65535.0);

  // Height in a 16-bit file with a scale and an offset.
  MapGrid heights = g;
  for (float& v : heights.values) v = v * 300.0f - 20.0f;
  ASSERT_TRUE(write_map_image(png, heights, 300.0f, -20.0f).ok());
  auto h_back = read_map_image(png, 300.0f, -20.0f, g.texel_origin, g.texel_size);
  ASSERT_TRUE(h_back.ok());
  for (std::size_t k = 0; k < g.values.size(); ++k) EXPECT_NEAR(h_back->values[k], heights.values[k], 300.0 / 65535.0);
}

// The old map is put at risk: a new map for the same file fails half way (disk full) or at the
// rename; the old map reads back unchanged.
TEST(MapGrid, FailedWriteKeepsTheOldFile) {
  const MapGrid old_map = ramp(33, 17);
  MapGrid new_map = ramp(33, 17);
  for (float& v : new_map.values) v = 1.0f - v;
  for (const char* name : {"keep.exr", "keep.png"}) {
    const fs::path file = temp_dir() / name;
    ASSERT_TRUE(write_map_image(file, old_map, 1.0f, 0.0f).ok());
    const std::string before = sylva::read_file(file).value();
    for (const sylva::FileFaultPoint point : {sylva::FileFaultPoint::kWrite, sylva::FileFaultPoint::kRename}) {
      sylva::ScopedFileFault fault([&](const fs::path& target, sylva::FileFaultPoint p) { return p == point && target == file; });
      const sylva::Status s = write_map_image(file, new_map, 1.0f, 0.0f);
      ASSERT_FALSE(s.ok()) << name;
      EXPECT_NE(s.error().message.find(file.string()), std::string::npos) << s.error().message;
      EXPECT_EQ(sylva::read_file(file).value_or(""), before) << name << ", fault at " << static_cast<int>(point);
    }
    for (const auto& e : fs::directory_iterator(temp_dir())) {
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "temporary file left: " << e.path();
    }
  }
}

TEST(MapGrid, ErrorsNameTheFile) {
  auto missing = read_map_image("/nonexistent/map.png", 1.0f, 0.0f, {0, 0}, {1, 1});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("/nonexistent/map.png"), std::string::npos);
  const MapGrid g = ramp(4, 4);
  auto bad = write_map_image("/nonexistent/dir/map.exr", g, 1.0f, 0.0f);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("/nonexistent/dir/map.exr"), std::string::npos);
}

TEST(HeightSource, GeneratedAndLoadedGroundsArePlacedAroundTheCentre) {
  HeightSourceSettings s;
  s.center = {100.0, -50.0};
  s.size = 64.0f;
  s.resolution = 33;
  auto grid = make_height_grid(s, std::nullopt);
  ASSERT_TRUE(grid.ok());
  EXPECT_EQ(grid->texel_size, glm::dvec2(2.0, 2.0));
  EXPECT_EQ(grid->world(0, 0), glm::dvec2(68.0, -82.0));
  EXPECT_EQ(grid->world(32, 32), glm::dvec2(132.0, -18.0));
  const sylva::HeightField field = height_field_from_grid(*grid);
  EXPECT_EQ(field.sample(7, 9), grid->at(7, 9));
  EXPECT_FLOAT_EQ(field.height(grid->world(7, 9).x, grid->world(7, 9).y), grid->at(7, 9));

  // A non-square height map keeps square samples.
  MapGrid file_grid(9, 5, 0.25f, {0, 0}, {1, 1});
  const fs::path exr = temp_dir() / "h.exr";
  ASSERT_TRUE(write_map_image(exr, file_grid, 1.0f, 0.0f).ok());
  s.map_scale = 8.0f;
  s.map_offset = 1.0f;
  auto loaded = make_height_grid(s, exr);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ(loaded->texel_size, glm::dvec2(8.0, 8.0));
  EXPECT_FLOAT_EQ(loaded->at(3, 2), 0.25f * 8.0f + 1.0f);
  EXPECT_EQ(loaded->world(4, 2), s.center);
}
