#pragma once
// Scenes with files of their own, for tests: a fresh folder per test, a scene made from JSON whose
// relative paths resolve in that folder, and a scene opened from its file as the player does.
#include <sylva/core/log.hpp>
#include <sylva/scene/scene.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sylva::scene::testing {

// <temp>/<prefix>_<run seed>_<test name>, empty at the start, removed at the end (the run's random
// seed keeps parallel ctest processes of one binary apart).
struct TestDir {
  std::filesystem::path path;
  explicit TestDir(const std::string& prefix) {
    const ::testing::UnitTest& run = *::testing::UnitTest::GetInstance();
    path = std::filesystem::temp_directory_path() /
           (prefix + "_" + std::to_string(run.random_seed()) + "_" + run.current_test_info()->name());
    std::filesystem::remove_all(path);
    std::filesystem::create_directories(path);
  }
  ~TestDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TestDir(const TestDir&) = delete;
  TestDir& operator=(const TestDir&) = delete;
};

// A scene from a JSON document whose relative paths (maps, meshes, species) resolve in `dir`.
inline Result<std::unique_ptr<Scene>> scene_from_json(const nlohmann::json& json, const std::filesystem::path& dir,
                                                      const std::string& source = "test stage") {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::from_json(json, source, warnings);
  if (!doc.ok()) return doc.error();
  doc->set_directory(dir);
  return Scene::create(std::move(*doc));
}

// The scene file `file` opened as the player does (load, then create); null, with the failure
// recorded, when either step fails.
inline std::unique_ptr<Scene> open_scene_file(const std::filesystem::path& file) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(file, warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  if (!doc.ok()) return nullptr;
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

// Opens the scene of `json` (as scene_from_json) with the log captured and returns the warnings
// it logged, for a scene that must open with `section` left out (Scene::left_out); an error
// naming what happened instead (the scene failed, or kept the section).
inline Result<std::string> open_leaving_out(const nlohmann::json& json, const std::filesystem::path& dir,
                                            const std::string& section) {
  std::string warnings;
  set_log_sink([&](LogLevel level, std::string_view message) {
    if (level == LogLevel::kWarn) warnings += std::string(message) + "\n";
  });
  auto made = scene_from_json(json, dir);
  set_log_sink(nullptr);
  if (!made.ok()) return make_error(made.error().code, "the scene failed instead: " + made.error().message);
  if (!(*made)->left_out(section)) return make_error(ErrorCode::kInvalidArgument, "the scene kept " + section);
  return warnings;
}

}  // namespace sylva::scene::testing
