// sylva-player end to end: a headless run of the default scene gives a non-blank PNG (sky above
// ground) and valid stats JSON; bad arguments give a clear message and a non-zero exit.
#include <sylva/core/image.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

#include "run_command.hpp"

namespace fs = std::filesystem;

namespace {

using sylva::test::RunResult;

RunResult run_player(const std::string& args) { return sylva::test::run_command(SYLVA_PLAYER_EXE, args); }

fs::path out_dir() {
  const fs::path dir = fs::temp_directory_path() / ("sylva_player_run_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

double luminance(const sylva::Image& image, int x, int y) {
  return 0.2126 * image.at(x, y, 0) + 0.7152 * image.at(x, y, 1) + 0.0722 * image.at(x, y, 2);
}

}  // namespace

TEST(PlayerHeadless, DefaultSceneRendersSkyAboveGroundAndWritesStats) {
  const fs::path png = out_dir() / "demo.png";
  const fs::path stats = out_dir() / "stats.json";
  const RunResult run = run_player("--headless --size 160x96 --frames 4 --screenshot " + png.string() +
                                   " --stats " + stats.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find(png.string()), std::string::npos) << "the player prints the PNG path";

  auto image = sylva::read_image(png);
  ASSERT_TRUE(image.ok()) << image.error().message;
  ASSERT_EQ(image->width(), 160);
  ASSERT_EQ(image->height(), 96);
  // Non-blank: the picture has real variance.
  double sum = 0, sum2 = 0;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 160; ++x) {
      const double l = luminance(*image, x, y);
      sum += l;
      sum2 += l * l;
    }
  const double n = 160.0 * 96.0;
  EXPECT_GT(sum2 / n - (sum / n) * (sum / n), 1e-3) << "image is nearly uniform";
  // Sky above ground: the top row is bluer than it is green-brown, the bottom row is not sky.
  const double top_blue = image->at(80, 1, 2) - image->at(80, 1, 0);
  const double bottom_blue = image->at(80, 94, 2) - image->at(80, 94, 0);
  EXPECT_GT(top_blue, 0.05) << "top of the frame should be sky";
  EXPECT_LT(bottom_blue, top_blue - 0.05) << "bottom of the frame should be ground";

  auto text = sylva::read_file(stats);
  ASSERT_TRUE(text.ok());
  auto json = sylva::parse_json_text(*text, stats.string());
  ASSERT_TRUE(json.ok()) << json.error().message;
  EXPECT_EQ((*json)["frames"], 4);
  EXPECT_EQ((*json)["size"], nlohmann::json::array({160, 96}));
  for (const char* key : {"cpu_ms", "gpu_ms", "wall_ms"}) {
    ASSERT_TRUE(json->contains(key)) << key;
    EXPECT_GE((*json)[key]["count"].get<int>(), 1) << key;
    EXPECT_GT((*json)[key]["mean"].get<double>(), 0.0) << key;
    EXPECT_TRUE((*json)[key].contains("p50"));
    EXPECT_TRUE((*json)[key].contains("p99"));
  }
  // Honest frame times: each frame's wall interval contains its CPU interval, so the wall figures
  // can be no smaller (on llvmpipe the GPU queries miss the rasterisation; the wall time may not).
  EXPECT_GE((*json)["wall_ms"]["mean"].get<double>(), (*json)["cpu_ms"]["mean"].get<double>());
  EXPECT_GE((*json)["longest_frame_ms"].get<double>(), (*json)["cpu_ms"]["max"].get<double>());
  EXPECT_TRUE((*json)["timing"].contains("wall_ms"));
  ASSERT_TRUE((*json)["passes"].contains("opaque"));
  EXPECT_GT((*json)["passes"]["opaque"]["triangles"].get<std::uint64_t>(), 10000u);
  EXPECT_GT((*json)["passes"]["opaque"]["samples"].get<std::uint64_t>(), 1000u);
  // Per-module records: every module of the default scene has GPU time per pass and its facts.
  const nlohmann::json& modules = (*json)["modules"];
  ASSERT_TRUE(modules.contains("ground") || modules.contains("terrain")) << modules.dump();
  for (const auto& [name, m] : modules.items()) {
    EXPECT_TRUE(m.contains("passes")) << name;
    EXPECT_TRUE(m["passes"].contains("opaque")) << name;
    EXPECT_GE(m["gpu_ms"]["count"].get<int>(), 1) << name;
    EXPECT_GE(m["update_ms"]["count"].get<int>(), 1) << name;
  }
  const nlohmann::json& ground = modules.contains("ground") ? modules["ground"] : modules["terrain"];
  EXPECT_GT(ground["triangles"].get<std::uint64_t>(), 0u);
  EXPECT_GT(ground["passes"]["opaque"]["samples"].get<std::uint64_t>(), 0u);
  // The effective settings the picture was made with, and the memory it took (issue #20).
  EXPECT_GE((*json)["settings"]["render"]["msaa_samples"].get<int>(), 1);
  const nlohmann::json& memory = (*json)["memory"];
  EXPECT_GT(memory["peak_rss_bytes"].get<std::uint64_t>(), 10u << 20) << memory.dump();
  std::uint64_t owned = 0, targets = 0;
  for (const auto& [owner, bytes] : memory["gpu_bytes"].items()) {
    owned += bytes["total"].get<std::uint64_t>();
    targets += bytes["render_targets"].get<std::uint64_t>();
  }
  EXPECT_EQ(owned, memory["gpu_total_bytes"].get<std::uint64_t>()) << memory.dump();
  EXPECT_GE(targets, 160u * 96u * 4u) << "at least the 160x96 RGBA8 target the frame was read from";
  EXPECT_GE(memory["gpu_peak_bytes"].get<std::uint64_t>(), memory["gpu_total_bytes"].get<std::uint64_t>());
}

TEST(PlayerHeadless, PlaysShippedScenesAlongCameraPaths) {
  const fs::path png = out_dir() / "ground.png";
  const fs::path stats = out_dir() / "ground_stats.json";
  const RunResult run = run_player(std::string(SYLVA_SCENES_DIR) + "/ground.json --headless --size 96x54 --frames 3 "
                                   "--camera-path orbit --screenshot " + png.string() + " --stats " + stats.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  auto json = sylva::parse_json_text(sylva::read_file(stats).value(), stats.string());
  ASSERT_TRUE(json.ok());
  EXPECT_EQ((*json)["modules"].size(), 1u) << "only the module the scene lists";
  EXPECT_TRUE((*json)["modules"].contains("ground"));
  EXPECT_EQ((*json)["scene"], "Ground only: the built-in height-field mesh");

  const RunResult no_path = run_player(std::string(SYLVA_SCENES_DIR) + "/ground.json --headless --frames 1 --camera-path nope");
  EXPECT_EQ(no_path.exit_code, 2);
  EXPECT_NE(no_path.output.find("nope"), std::string::npos);
  const RunResult bookmark = run_player(std::string(SYLVA_SCENES_DIR) + "/ground.json --headless --size 32x32 --frames 1 "
                                        "--bookmark valley");
  EXPECT_EQ(bookmark.exit_code, 0) << bookmark.output;
}

TEST(PlayerHeadless, BadArgumentsExitNonZeroWithAMessage) {
  const RunResult unknown = run_player("--frobnicate");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("--frobnicate"), std::string::npos) << unknown.output;

  const RunResult missing_scene = run_player("/nonexistent/scene.json --headless --frames 1");
  EXPECT_EQ(missing_scene.exit_code, 2);
  EXPECT_NE(missing_scene.output.find("/nonexistent/scene.json"), std::string::npos) << missing_scene.output;

  const RunResult bad_set = run_player("--headless --frames 1 --set ground.resolution=abc");
  EXPECT_EQ(bad_set.exit_code, 2);
  EXPECT_NE(bad_set.output.find("ground.resolution"), std::string::npos) << bad_set.output;

  const RunResult bad_output = run_player("--headless --size 32x32 --frames 1 --screenshot /nonexistent/dir/x.png");
  EXPECT_EQ(bad_output.exit_code, 1);
  EXPECT_NE(bad_output.output.find("/nonexistent/dir/x.png"), std::string::npos) << bad_output.output;
}

TEST(PlayerHeadless, HelpAndListModulesSucceed) {
  const RunResult help = run_player("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("usage: sylva-player"), std::string::npos);
  const RunResult modules = run_player("--list-modules");
  EXPECT_EQ(modules.exit_code, 0);
  EXPECT_NE(modules.output.find("render"), std::string::npos);
  EXPECT_NE(modules.output.find("scene"), std::string::npos);
  EXPECT_NE(modules.output.find("ground"), std::string::npos);
#ifdef SYLVA_HAS_GRASS
  EXPECT_NE(modules.output.find("grass"), std::string::npos);
#endif
}
