// The chunk-tree cache through the shipped player (issue 15: "baked on first use into a cache file
// keyed by the source's content hash and the tree settings, so the second launch reopens it
// without rebuilding"): a scene whose terrain comes from a height map, with its cache folder
// beside the scene, run headless several times. Invariants: the first launch misses and writes one
// cache file, the second hits; a truncated cache file is a warning naming it, a rebuild and a
// replacement; every launch draws the same picture, pixel for pixel; below min_samples nothing is
// cached.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/params_json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

#include "run_command.hpp"

namespace fs = std::filesystem;

namespace {

using sylva::test::RunResult;

RunResult run_player(const std::string& args) { return sylva::test::run_command(SYLVA_PLAYER_EXE, args); }

fs::path scene_dir() {
  const fs::path dir = fs::temp_directory_path() / ("sylva_player_terrain_cache_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A 16-bit height map of smooth hills and a scene that names it, its cache folder beside it.
fs::path write_scene(const fs::path& dir) {
  sylva::Image h(257, 257, 1, sylva::PixelFormat::kU16);
  for (int y = 0; y < 257; ++y)
    for (int x = 0; x < 257; ++x)
      h.at(x, y) = static_cast<float>(0.5 + 0.25 * std::sin(x * 0.045) * std::cos(y * 0.06) + 0.15 * std::sin((x + 2 * y) * 0.02));
  EXPECT_TRUE(sylva::write_image(dir / "hills.png", h, sylva::PixelFormat::kU16).ok());
  const fs::path scene = dir / "scene.json";
  EXPECT_TRUE(sylva::write_file_atomic(scene, R"({"sylva_scene": 1, "name": "cached terrain",
    "camera": {"position": [-300, 160, 300], "yaw_deg": -42, "pitch_deg": -18, "fov_deg": 60},
    "terrain": {"size": 1024, "map_scale": 120, "maps": {"height": "hills.png"},
                "tree": {"leaf_dimension": 17},
                "tree_cache": {"directory": "cache", "min_samples": 0}}})").ok());
  return scene;
}

struct Launch {
  RunResult run;
  nlohmann::json terrain;  // the terrain module's facts from --stats
  sylva::Image image;
};

Launch launch(const fs::path& scene, const std::string& name, const std::string& extra = "") {
  const fs::path dir = scene.parent_path();
  const fs::path png = dir / (name + ".png"), stats = dir / (name + ".json");
  Launch l;
  l.run = run_player(scene.string() + " --headless --size 160x96 --frames 2 --screenshot " + png.string() + " --stats " +
                     stats.string() + " " + extra);
  EXPECT_EQ(l.run.exit_code, 0) << l.run.output;
  auto text = sylva::read_file(stats);
  if (!text.ok()) return l;
  auto json = sylva::parse_json_text(*text, stats.string());
  EXPECT_TRUE(json.ok());
  if (json.ok()) l.terrain = (*json)["modules"]["terrain"];
  auto image = sylva::read_image(png);
  EXPECT_TRUE(image.ok());
  if (image.ok()) l.image = std::move(*image);
  return l;
}

std::vector<fs::path> cache_files(const fs::path& dir) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "cache", ec)) out.push_back(e.path());
  return out;
}

// Pixels that differ in any channel.
std::size_t differing_pixels(const sylva::Image& a, const sylva::Image& b) {
  if (a.width() != b.width() || a.height() != b.height() || a.channels() != b.channels()) return ~std::size_t{0};
  std::size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < a.channels(); ++c)
        if (a.at(x, y, c) != b.at(x, y, c)) {
          ++n;
          break;
        }
  return n;
}

}  // namespace

TEST(PlayerTerrainCache, SecondLaunchReopensTheTreeAndATruncatedCacheIsRebuilt) {
  const fs::path dir = scene_dir();
  const fs::path scene = write_scene(dir);

  const Launch first = launch(scene, "first");
  ASSERT_EQ(first.run.exit_code, 0);
  EXPECT_EQ(first.terrain["tree_cache"], "miss") << first.terrain.dump();
  EXPECT_EQ(first.terrain["tree_cache_hit"], 0);
  EXPECT_GT(first.terrain["tree_build_ms"].get<double>(), 0.0);
  const std::vector<fs::path> files = cache_files(dir);
  ASSERT_EQ(files.size(), 1u) << "one cache file, in the folder named relative to the scene";
  EXPECT_TRUE(files[0].filename().string().starts_with("terrain-")) << files[0];
  const auto full = fs::file_size(files[0]);

  const Launch second = launch(scene, "second");
  EXPECT_EQ(second.terrain["tree_cache"], "hit") << second.terrain.dump();
  EXPECT_EQ(second.terrain["tree_cache_hit"], 1);
  EXPECT_EQ(second.terrain["tree_chunks"], first.terrain["tree_chunks"]);
  EXPECT_EQ(second.terrain["triangles"], first.terrain["triangles"]);
  EXPECT_EQ(cache_files(dir).size(), 1u);
  ASSERT_FALSE(first.image.empty());
  EXPECT_EQ(differing_pixels(first.image, second.image), 0u) << "the cached tree draws the same picture";

  // A truncated cache (a launch killed while another copied it, a full disk): a warning naming
  // the file, a rebuild, the same picture, and a whole file again.
  fs::resize_file(files[0], full / 3);
  const Launch third = launch(scene, "third");
  EXPECT_EQ(third.terrain["tree_cache"], "miss") << third.terrain.dump();
  EXPECT_NE(third.run.output.find("rejected the chunk-tree cache"), std::string::npos) << third.run.output;
  EXPECT_NE(third.run.output.find(files[0].filename().string()), std::string::npos) << third.run.output;
  EXPECT_EQ(differing_pixels(first.image, third.image), 0u);
  EXPECT_EQ(fs::file_size(files[0]), full);
  EXPECT_EQ(launch(scene, "fourth").terrain["tree_cache"], "hit");

  // Another tree setting is another key: a miss and a second file; below min_samples: off.
  EXPECT_EQ(launch(scene, "fifth", "--set terrain.tree.flat_tolerance=0.05").terrain["tree_cache"], "miss");
  EXPECT_EQ(cache_files(dir).size(), 2u);
  EXPECT_EQ(launch(scene, "sixth", "--set terrain.tree_cache.min_samples=2000000").terrain["tree_cache"], "off");
  EXPECT_EQ(cache_files(dir).size(), 2u);
  fs::remove_all(dir);
}
