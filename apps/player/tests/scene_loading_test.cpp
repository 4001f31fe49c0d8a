// The player's scene settings: defaults, JSON files, --set overrides, and bad input.
#include "scene_loading.hpp"

#include <sylva/core/atomic_file.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using sylva::player::load_scene;

namespace {
fs::path write_temp(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("sylva_player_scene_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / name;
  EXPECT_TRUE(sylva::write_file_atomic(path, text).ok());
  return path;
}
}  // namespace

TEST(SceneLoading, DefaultSceneIsValid) {
  auto scene = load_scene(std::nullopt, {});
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_TRUE(scene->warnings.empty());
  // The default stands on a ground (terrain when built in, else the plain ground).
  EXPECT_TRUE(scene->document.has_module("terrain") || scene->document.has_module("ground"));
  EXPECT_TRUE(scene->document.validate().ok());
}

TEST(SceneLoading, FileAndOverridesApplyInOrder) {
  const fs::path path = write_temp("ok.json", R"({"sun": {"elevation_deg": 45}, "ground": {"noise": {"octaves": 3}},
                                               "camera": {"position": [1, 2, 3]}})");
  auto scene = load_scene(path.string(), {{"ground.noise.octaves", "5"}});
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  EXPECT_EQ(scene->document.sun.elevation_deg, 45.f);
  EXPECT_EQ(scene->document.to_json()["ground"]["noise"]["octaves"], 5);
  EXPECT_EQ(scene->document.camera.position, glm::dvec3(1, 2, 3));
  EXPECT_EQ(scene->document.directory(), path.parent_path());
}

TEST(SceneLoading, UnknownKeysWarnWithTheFileName) {
  const fs::path path = write_temp("typo.json", R"({"sun": {"elevaton_deg": 45}})");
  auto scene = load_scene(path.string(), {});
  ASSERT_TRUE(scene.ok());
  ASSERT_EQ(scene->warnings.size(), 1u);
  EXPECT_NE(scene->warnings[0].find("typo.json"), std::string::npos);
  EXPECT_NE(scene->warnings[0].find("elevaton_deg"), std::string::npos);
}

TEST(SceneLoading, BadInputNamesFileAndPath) {
  struct Case {
    std::string file_text;
    std::vector<std::pair<std::string, std::string>> overrides;
    std::string must_mention;
  };
  const Case cases[] = {
      {R"({"sun": {"elevation_deg": "high"}})", {}, "sun.elevation_deg"},
      {R"({"ground": {"resolution": 1}})", {}, "ground.resolution"},
      {R"({"ground": )", {}, "bad.json:1"},
      {R"([1, 2])", {}, "JSON object"},
      {R"({})", {{"ground.nope", "1"}}, "ground.nope"},
      {R"({})", {{"sun.elevation_deg", "nan"}}, "sun.elevation_deg"},
      {R"({"camera_paths": {"p": {"keys": [{"time_s": 2}, {"time_s": 1}]}}})", {}, "camera_paths.p.keys[1].time_s"},
  };
  for (const Case& c : cases) {
    const fs::path path = write_temp("bad.json", c.file_text);
    auto scene = load_scene(path.string(), c.overrides);
    ASSERT_FALSE(scene.ok()) << c.file_text;
    EXPECT_NE(scene.error().message.find(c.must_mention), std::string::npos) << scene.error().message;
  }
  auto missing = load_scene(std::string("/nonexistent/scene.json"), {});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("/nonexistent/scene.json"), std::string::npos);
}
