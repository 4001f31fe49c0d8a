// The chunk-tree cache in the editor (issue 15): the same script run twice on a scene whose
// terrain comes from a height map, with the cache beside the scene. The first run builds and
// caches the tree, the second reopens it; painting a height stroke on the reopened tree gives the
// very picture it gives on a built one (the edit changes the live tree, never the cache file).
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "image_files.hpp"
#include "run_command.hpp"

namespace fs = std::filesystem;

namespace {

using sylva::test::differing_pixels;
using sylva::test::RunResult;

RunResult run_editor(const std::string& args) { return sylva::test::run_command(SYLVA_EDITOR_EXE, args); }

std::size_t cache_files(const fs::path& dir) {
  std::size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir / "cache", ec)) n += e.path().extension() == ".sylvaterrain" ? 1 : 0;
  return n;
}

}  // namespace

TEST(EditorTerrainCache, PaintingAReopenedTreeGivesThePictureOfABuiltOne) {
  const fs::path dir = fs::temp_directory_path() / ("sylva_editor_terrain_cache_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  sylva::Image h(129, 129, 1, sylva::PixelFormat::kU16);
  for (int y = 0; y < 129; ++y)
    for (int x = 0; x < 129; ++x)
      h.at(x, y) = static_cast<float>(0.5 + 0.3 * std::sin(x * 0.08) * std::cos(y * 0.1));
  ASSERT_TRUE(sylva::write_image(dir / "hills.png", h, sylva::PixelFormat::kU16).ok());
  ASSERT_TRUE(sylva::write_file_atomic(dir / "scene.json", R"({"sylva_scene": 1,
    "camera": {"position": [-160, 90, 160], "yaw_deg": -42, "pitch_deg": -25, "fov_deg": 60},
    "terrain": {"size": 512, "map_scale": 60, "maps": {"height": "hills.png"}, "tree": {"leaf_dimension": 17},
                "tree_cache": {"directory": "cache", "min_samples": 0}}})").ok());
  auto script = [&](const std::string& run) {
    return "load scene.json\nframes 2\nscreenshot " + run + "_before.png 128x72\n" +
           "brush op=raise radius=40 strength=25 falloff=constant\nstroke terrain.height 0,0\n" +
           "frames 2\nscreenshot " + run + "_after.png 128x72\nquit\n";
  };
  for (const std::string run : {"first", "second"}) {
    ASSERT_TRUE(sylva::write_file_atomic(dir / (run + ".sylva"), script(run)).ok());
  }
  const RunResult first = run_editor("--headless --size 128x72 --script " + (dir / "first.sylva").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("cached in"), std::string::npos) << first.output;
  EXPECT_EQ(cache_files(dir), 1u);
  const RunResult second = run_editor("--headless --size 128x72 --script " + (dir / "second.sylva").string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("loaded from the cache"), std::string::npos) << second.output;
  EXPECT_EQ(cache_files(dir), 1u) << "the stroke wrote no cache file";

  EXPECT_EQ(differing_pixels(dir / "first_before.png", dir / "second_before.png"), 0u);
  EXPECT_GT(differing_pixels(dir / "first_before.png", dir / "first_after.png"), 100u) << "the stroke shows";
  EXPECT_EQ(differing_pixels(dir / "first_after.png", dir / "second_after.png"), 0u)
      << "painting the reopened tree draws what painting the built tree drew";
  fs::remove_all(dir);
}
