// Saving a scene never loses a user's files (scene_save.cpp): a save is one transaction over the
// scene file and its maps; a failure at any file (injected through core/file_fault.hpp at the
// very paths being saved) leaves every old file byte-identical and the scene still unsaved; a
// read-only scene is refused; "save as" copies the maps so the original never changes.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/file_fault.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::scene;

namespace {

class SceneSaveGl : public render::GlTest {
 protected:
  void SetUp() override {
    render::GlTest::SetUp();
    dir_ = fs::temp_directory_path() / ("sylva_scene_save_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A scene "a.json" with one painted and saved height map, loaded back as a user opens it.
    std::vector<std::string> warnings;
    auto doc = SceneDocument::from_text(R"({"ground": {"resolution": 33, "size": 64, "height": 5, "chunk_quads": 16}})",
                                        "a.json", warnings);
    ASSERT_TRUE(doc.ok()) << doc.error().message;
    auto first = Scene::create(std::move(*doc));
    ASSERT_TRUE(first.ok()) << first.error().message;
    paint(**first, 1.0f);
    ASSERT_TRUE((*first)->save(dir_ / "a.json").ok());
    scene_ = reopen(dir_ / "a.json");
  }
  void TearDown() override {
    std::error_code ec;
    fs::permissions(dir_ / "a.json", fs::perms::owner_all, ec);
    fs::remove_all(dir_, ec);
    render::GlTest::TearDown();
  }
  static std::unique_ptr<Scene> reopen(const fs::path& file) { return sylva::scene::testing::open_scene_file(file); }
  static void paint(Scene& scene, float value) {
    SceneMap* map = scene.map("ground.height");
    ASSERT_NE(map, nullptr);
    for (int i = 0; i < 8; ++i) map->grid.at(i + 4, 5) = value + 0.01f * static_cast<float>(i);
    ASSERT_TRUE(scene.map_changed("ground.height", {4, 5, 12, 6}).ok());
  }
  std::string bytes(const fs::path& p) { return read_file(p).value_or("<missing>"); }
  std::vector<std::string> listing() {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) names.push_back(fs::relative(e.path(), dir_).string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
  std::unique_ptr<Scene> scene_;
};

const std::vector<std::string> kSavedFiles = {"a.json", "a_maps", "a_maps/ground_height.exr"};

}  // namespace

TEST_F(SceneSaveGl, FailedSceneRenameAfterTheMapsKeepsEveryOldFile) {
  ASSERT_TRUE(scene_);
  const std::string scene_before = bytes(dir_ / "a.json");
  const std::string map_before = bytes(dir_ / "a_maps/ground_height.exr");
  paint(*scene_, 7.0f);
  {
    // The maps are renamed first; the scene file's rename then fails.
    ScopedFileFault fault([](const fs::path& target, FileFaultPoint point) {
      return point == FileFaultPoint::kRename && target.filename() == "a.json";
    });
    Status s = scene_->save(dir_ / "a.json");
    ASSERT_FALSE(s.ok());
    EXPECT_NE(s.error().message.find("a.json"), std::string::npos) << s.error().message;
  }
  EXPECT_EQ(bytes(dir_ / "a.json"), scene_before);
  EXPECT_EQ(bytes(dir_ / "a_maps/ground_height.exr"), map_before);
  EXPECT_EQ(listing(), kSavedFiles) << "no temporary or new file left";
  EXPECT_TRUE(scene_->maps_unsaved());
  // The same save succeeds once the disk behaves, and reloads with the new heights.
  ASSERT_TRUE(scene_->save(dir_ / "a.json").ok());
  EXPECT_NE(bytes(dir_ / "a_maps/ground_height.exr"), map_before);
  auto back = reopen(dir_ / "a.json");
  ASSERT_TRUE(back);
  EXPECT_EQ(back->map("ground.height")->grid.at(4, 5), 7.0f);
}

TEST_F(SceneSaveGl, DiskFullWhileWritingTheSceneTouchesNoMap) {
  ASSERT_TRUE(scene_);
  const std::string map_before = bytes(dir_ / "a_maps/ground_height.exr");
  const std::string scene_before = bytes(dir_ / "a.json");
  paint(*scene_, 3.0f);
  ScopedFileFault fault([](const fs::path& target, FileFaultPoint point) {
    return point == FileFaultPoint::kWrite && target.filename() == "a.json";
  });
  ASSERT_FALSE(scene_->save(dir_ / "a.json").ok());
  EXPECT_EQ(bytes(dir_ / "a_maps/ground_height.exr"), map_before);
  EXPECT_EQ(bytes(dir_ / "a.json"), scene_before);
  EXPECT_EQ(listing(), kSavedFiles);
}

TEST_F(SceneSaveGl, ReadOnlySceneIsRefusedAndKeepsItsProtection) {
  ASSERT_TRUE(scene_);
  const std::string map_before = bytes(dir_ / "a_maps/ground_height.exr");
  const std::string scene_before = bytes(dir_ / "a.json");
  fs::permissions(dir_ / "a.json", fs::perms::owner_read | fs::perms::group_read | fs::perms::others_read);
  paint(*scene_, 2.0f);
  Status s = scene_->save(dir_ / "a.json");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("read-only"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find((dir_ / "a.json").string()), std::string::npos) << s.error().message;
  EXPECT_EQ(bytes(dir_ / "a.json"), scene_before);
  EXPECT_EQ(bytes(dir_ / "a_maps/ground_height.exr"), map_before);
  EXPECT_EQ(fs::status(dir_ / "a.json").permissions() & fs::perms::owner_write, fs::perms::none);
  // Saving elsewhere still works.
  EXPECT_TRUE(scene_->save(dir_ / "b.json").ok());
}

TEST_F(SceneSaveGl, SaveAsInTheSameFolderNeverChangesTheOriginalsMaps) {
  ASSERT_TRUE(scene_);
  const std::string map_before = bytes(dir_ / "a_maps/ground_height.exr");
  const std::string scene_before = bytes(dir_ / "a.json");
  paint(*scene_, 9.0f);
  ASSERT_TRUE(scene_->save(dir_ / "b.json").ok());
  EXPECT_EQ(bytes(dir_ / "a.json"), scene_before);
  EXPECT_EQ(bytes(dir_ / "a_maps/ground_height.exr"), map_before) << "the original's map was overwritten";
  EXPECT_EQ(scene_->document().module("ground")->maps.at("height"), "b_maps/ground_height.exr");
  auto original = reopen(dir_ / "a.json");
  ASSERT_TRUE(original);
  EXPECT_EQ(original->map("ground.height")->grid.at(4, 5), 1.0f);
  auto copy = reopen(dir_ / "b.json");
  ASSERT_TRUE(copy);
  EXPECT_EQ(copy->map("ground.height")->grid.at(4, 5), 9.0f);
}

TEST_F(SceneSaveGl, SaveAsCopiesUneditedMapsIntoTheNewScenesFolder) {
  ASSERT_TRUE(scene_);
  const fs::path other = dir_ / "elsewhere";
  fs::create_directories(other);
  ASSERT_TRUE(scene_->save(other / "c.json").ok());
  EXPECT_EQ(scene_->document().module("ground")->maps.at("height"), "c_maps/ground_height.exr");
  EXPECT_EQ(bytes(other / "c_maps/ground_height.exr"), bytes(dir_ / "a_maps/ground_height.exr")) << "a byte copy";
  // From now on the scene is c.json: painting and saving it leaves a.json's map alone.
  const std::string map_before = bytes(dir_ / "a_maps/ground_height.exr");
  paint(*scene_, 4.0f);
  ASSERT_TRUE(scene_->save(other / "c.json").ok());
  EXPECT_EQ(bytes(dir_ / "a_maps/ground_height.exr"), map_before);
}
