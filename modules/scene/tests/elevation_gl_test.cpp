// Elevation rasters through a scene file (issue 15, first section): a terrain or ground section
// names a GeoTIFF relative to the scene ("elevation": {"file": ...}); the scene's ground then has
// the raster's spacing in metres, its heights and its nodata filled or refused; scene overrides
// win; bad rasters are errors naming the section key and the file; the shipped player plays such
// a scene (exit 0, a picture that is not flat). The GeoTIFFs are written here through GDAL.
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/scene.hpp>

#include <run_command.hpp>
#include <support/geotiff_fixture.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <unistd.h>

using namespace sylva;
using namespace sylva::scene;
namespace fs = std::filesystem;

namespace {

using ElevationGl = render::GlTest;

// One folder per process: ctest runs each test as its own process, two at a time, and a folder
// shared between them let one test rewrite dem/hills.tif while another read it.
fs::path scene_dir() {
  const fs::path dir = fs::temp_directory_path() / ("sylva_elevation_gl_test_" + std::to_string(::getpid()));
  fs::create_directories(dir / "dem");
  return dir;
}

// Hills on a slope, 20 m UTM samples, Int16 metres; nodata -32768 in a 2x2 hole and a corner.
constexpr int kColumns = 64, kRows = 48;
constexpr double kNodata = -32768.0;
test::GeoTiffSpec hills() {
  test::GeoTiffSpec s;
  s.columns = kColumns;
  s.rows = kRows;
  s.pixel_x = s.pixel_y = 20.0;
  s.nodata = kNodata;
  for (int j = 0; j < kRows; ++j)
    for (int i = 0; i < kColumns; ++i) s.values.push_back(std::round(150.0 + 120.0 * std::sin(i * 0.15) * std::cos(j * 0.2) + 2.0 * i));
  for (int j = 20; j < 22; ++j)
    for (int i = 30; i < 32; ++i) s.values[j * kColumns + i] = kNodata;
  s.values[kColumns * kRows - 1] = kNodata;
  return s;
}

void write_text(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }

Result<std::unique_ptr<Scene>> load_scene(const fs::path& file) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(file, warnings);
  if (!doc.ok()) return doc.error();
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  return Scene::create(std::move(*doc));
}

const char* ground_section() {
#ifdef SYLVA_HAS_TERRAIN
  return "terrain";
#else
  return "ground";
#endif
}

}  // namespace

TEST_F(ElevationGl, SceneGroundTakesSpacingHeightsAndFilledNodataFromTheGeoTiff) {
  const fs::path dir = scene_dir();
  const auto spec = hills();
  test::write_geotiff(dir / "dem" / "hills.tif", spec);
  const fs::path file = dir / "hills.json";
  write_text(file, std::string(R"({"sylva_scene": 1, ")") + ground_section() +
                       R"(": {"center": [100, -50], "elevation": {"file": "dem/hills.tif"}}})");
  test::LogCapture capture;
  auto scene = load_scene(file);
  ASSERT_TRUE(scene.ok()) << scene.error().describe();
  const HeightField* ground = (*scene)->ground();
  ASSERT_NE(ground, nullptr);
  ASSERT_EQ(ground->columns(), kColumns);
  ASSERT_EQ(ground->rows(), kRows);
  EXPECT_DOUBLE_EQ(ground->spacing(), 20.0);
  EXPECT_DOUBLE_EQ(ground->origin().x, 100.0 - 0.5 * 63 * 20.0);
  EXPECT_DOUBLE_EQ(ground->origin().y, -50.0 - 0.5 * 47 * 20.0);
  for (int j = 0; j < kRows; j += 7) {
    for (int i = 0; i < kColumns; i += 5) {
      if (spec.values[j * kColumns + i] == kNodata) continue;
      ASSERT_EQ(ground->sample(i, j), static_cast<float>(spec.values[j * kColumns + i])) << i << "," << j;
    }
  }
  // The hole is filled with heights from around it, and the user is told how many.
  EXPECT_GT(ground->min_height(), 0.0f);
  const float filled = ground->sample(30, 20);
  EXPECT_GT(filled, static_cast<float>(spec.values[19 * kColumns + 29]) - 60.0f);
  EXPECT_LT(filled, static_cast<float>(spec.values[19 * kColumns + 29]) + 60.0f);
  EXPECT_TRUE(test::LogCapture::any(capture.warnings, "hills.tif", "filled 5 "));

  // Scene overrides win over the file, through the same parameter paths as --set.
  const std::string s = ground_section();
  ASSERT_TRUE((*scene)->set_param(s + ".elevation.spacing", "5").ok());
  ASSERT_TRUE((*scene)->set_param(s + ".elevation.height_scale", "2").ok());
  ASSERT_TRUE((*scene)->set_param(s + ".elevation.height_offset", "-100").ok());
  ground = (*scene)->ground();
  ASSERT_NE(ground, nullptr);
  EXPECT_DOUBLE_EQ(ground->spacing(), 5.0);
  EXPECT_EQ(ground->sample(5, 7), static_cast<float>(spec.values[7 * kColumns + 5] * 2.0 - 100.0));
}

TEST_F(ElevationGl, SaveAsIntoAnotherFolderStillNamesTheSameRaster) {
  const fs::path dir = scene_dir();
  test::write_geotiff(dir / "dem" / "hills.tif", hills());
  write_text(dir / "save.json", R"({"sylva_scene": 1, "ground": {"elevation": {"file": "dem/hills.tif"}}})");
  auto scene = load_scene(dir / "save.json");
  ASSERT_TRUE(scene.ok()) << scene.error().describe();
  fs::create_directories(dir / "elsewhere");
  const fs::path copy = dir / "elsewhere" / "copy.json";
  ASSERT_TRUE((*scene)->save(copy).ok());
  EXPECT_FALSE(fs::exists(dir / "elsewhere" / "copy_maps")) << "the raster is referenced, not copied";
  auto reloaded = load_scene(copy);
  ASSERT_TRUE(reloaded.ok()) << reloaded.error().describe();
  EXPECT_EQ((*reloaded)->get_param("ground.elevation.file").value(), "../dem/hills.tif");
  EXPECT_EQ((*reloaded)->ground()->samples(), (*scene)->ground()->samples());
}

TEST_F(ElevationGl, GeographicRasterWithNodataRefusedIsAnErrorNamingKeyAndFile) {
  const fs::path dir = scene_dir();
  auto spec = hills();
  spec.type = GDT_Float32;
  spec.epsg = 4326;
  spec.left = 7.0;
  spec.top = 46.0;
  spec.pixel_x = spec.pixel_y = 1.0 / 3600.0;
  test::write_geotiff(dir / "dem" / "geo.tif", spec);
  write_text(dir / "geo_refuse.json",
             R"({"sylva_scene": 1, "ground": {"elevation": {"file": "dem/geo.tif", "nodata": "refuse"}}})");
  auto refused = load_scene(dir / "geo_refuse.json");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(refused.error().message.find("ground.elevation.file"), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("geo.tif"), std::string::npos) << refused.error().message;
  EXPECT_NE(refused.error().message.find("5 of 3072"), std::string::npos) << refused.error().message;

  // Filled instead: 1 arc-second at 45.99 N is about 21.5 m east-west, 30.9 m north-south;
  // samples become 21.5 m squares and the ground keeps its north-south extent.
  write_text(dir / "geo.json", R"({"sylva_scene": 1, "ground": {"elevation": {"file": "dem/geo.tif"}}})");
  auto scene = load_scene(dir / "geo.json");
  ASSERT_TRUE(scene.ok()) << scene.error().describe();
  const HeightField* ground = (*scene)->ground();
  EXPECT_NEAR(ground->spacing(), 21.48, 0.05);
  EXPECT_NEAR(ground->extent().y, 47 * 30.87, 0.6 * ground->spacing());
  EXPECT_EQ(ground->columns(), kColumns);
}

TEST_F(ElevationGl, BadRastersAreErrorsNamingKeyAndFile) {
  const fs::path dir = scene_dir();
  test::write_geotiff(dir / "dem" / "cut.tif", [] {
    auto s = hills();
    s.columns = s.rows = 200;
    s.values.assign(200 * 200, 10.0);
    return s;
  }());
  fs::resize_file(dir / "dem" / "cut.tif", fs::file_size(dir / "dem" / "cut.tif") / 4);
  test::write_geotiff(dir / "dem" / "empty.tif", [] {
    auto s = hills();
    std::fill(s.values.begin(), s.values.end(), kNodata);
    return s;
  }());
  write_text(dir / "dem" / "junk.dem", "definitely not elevation data\n");
  struct Case {
    const char* raster;
    ErrorCode code;
  };
  for (const Case& c : {Case{"cut.tif", ErrorCode::kCorrupt}, Case{"empty.tif", ErrorCode::kInvalidArgument},
                        Case{"junk.dem", ErrorCode::kUnsupported}, Case{"missing.tif", ErrorCode::kNotFound}}) {
    const fs::path file = dir / "bad.json";
    write_text(file, std::string(R"({"sylva_scene": 1, "ground": {"elevation": {"file": "dem/)") + c.raster + "\"}}}");
    auto scene = load_scene(file);
    ASSERT_FALSE(scene.ok()) << c.raster;
    EXPECT_EQ(scene.error().code, c.code) << scene.error().describe();
    EXPECT_NE(scene.error().message.find("ground.elevation.file"), std::string::npos) << scene.error().message;
    EXPECT_NE(scene.error().message.find((dir / "dem" / c.raster).string()), std::string::npos) << scene.error().message;
  }
}

TEST_F(ElevationGl, ShippedPlayerPlaysASceneOnAGeoTiff) {
  const fs::path dir = scene_dir();
  test::write_geotiff(dir / "dem" / "hills.tif", hills());
  const fs::path file = dir / "player.json";
  write_text(file, std::string(R"({"sylva_scene": 1, "camera": {"position": [-700, 600, 700], "yaw_deg": -45,
      "pitch_deg": -28, "fov_deg": 60}, ")") + ground_section() + R"(": {"elevation": {"file": "dem/hills.tif"}}})");
  const fs::path png = dir / "player.png";
  fs::remove(png);
  const auto run = test::run_command(SYLVA_PLAYER_EXE, file.string() + " --headless --size 96x64 --frames 2 --screenshot " +
                                                          png.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("hills.tif: 64x48 samples 20.000 m apart"), std::string::npos) << run.output;
  auto image = read_image(png);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  // Not one flat colour, and the ground (bottom centre) differs from the sky (top centre).
  std::set<int> levels;
  for (int y = 0; y < image->height(); ++y)
    for (int x = 0; x < image->width(); ++x) levels.insert(static_cast<int>(image->at(x, y, 1) * 255.0f + 0.5f));
  EXPECT_GT(levels.size(), 20u);
  const int cx = image->width() / 2;
  float diff = 0.0f;
  for (int c = 0; c < 3; ++c) diff += std::abs(image->at(cx, 2, c) - image->at(cx, image->height() - 3, c));
  EXPECT_GT(diff, 0.1f);
}
