// Species files reach a scene (issue #16): a scene file on disk names species JSON files
// (`vegetation.species_files.N.file`, relative to the scene), which name an OBJT tree written as
// seed 000 §4.3.1 shows it. Checked on pixels: the loaded tree stands where it is placed with its
// model's height (its units applied), a forest of two species from files shows both, one of three
// species with leaf images shows each leaf colour at LOD0 and LOD1, its slices are baked for
// LOD1, and a species file that fails is left out with a warning.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/module_instance.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>

#include <unistd.h>

using namespace sylva;
using namespace sylva::scene;
namespace fs = std::filesystem;

namespace {

constexpr const char* kRedSpecies = R"({"name": "red", "model": {"objt": "../trees/seed.objt"}, "units": 2,
    "objt": {"branch_radius": 0.06, "branch_taper": 0.5}, "bark_color": [0.7, 0.05, 0.05]})";
constexpr const char* kBlueSpecies = R"({"name": "blue", "model": {"objt": "../trees/seed.objt"}, "units": 1.5,
    "objt": {"branch_radius": 0.06, "branch_taper": 0.5}, "bark_color": [0.05, 0.1, 0.7]})";

class SpeciesFilesGl : public render::GlTest {
 protected:
  void SetUp() override {
    render::GlTest::SetUp();
    dir_ = fs::temp_directory_path() /
           fmt::format("sylva_species_gl_{}_{}", ::getpid(), ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "trees");
    fs::create_directories(dir_ / "species");
    // Seed 000 §4.3.1's plain layout (no radii, no leaf sizes; the species files give the rules),
    // as shipped with the example scenes.
    fs::copy_file(fs::path(SYLVA_SCENES_DIR) / "species" / "trees" / "seed_example.objt", dir_ / "trees" / "seed.objt");
    ASSERT_TRUE(write_file_atomic(dir_ / "species" / "red.json", kRedSpecies).ok());
    ASSERT_TRUE(write_file_atomic(dir_ / "species" / "blue.json", kBlueSpecies).ok());
  }
  void TearDown() override {
    fs::remove_all(dir_);
    render::GlTest::TearDown();
  }

  // Writes scene.json (camera, flat ground, no wind, no shadows, plus `vegetation` when given)
  // and opens it from the file as the player does.
  // `extra`: more top-level sections (",\"environment\": {...}").
  std::unique_ptr<Scene> open(const std::string& camera, const std::string& vegetation, const std::string& extra = "") {
    std::string text = R"({"camera": )" + camera + R"(, "wind": {"strength": 0, "gust_amplitude": 0},
        "render": {"msaa_samples": 1, "shadows": {"enabled": false}},
        "ground": {"resolution": 33, "size": 512, "generator": "flat"})" + extra;
    if (!vegetation.empty()) text += R"(, "vegetation": )" + vegetation;
    text += "}";
    EXPECT_TRUE(write_file_atomic(dir_ / "scene.json", text).ok());
    return sylva::scene::testing::open_scene_file(dir_ / "scene.json");
  }

  static Image frame(Scene& scene, glm::ivec2 size) {
    auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
    render::FrameProfiler profiler;
    const render::Camera camera = scene.make_camera(scene.document().camera, size);
    for (int i = 0; i < 2; ++i) {  // the forest hands its instances over at the first update
      scene.update(camera, 2.0, 0.0f, size);
      scene.render(fb, profiler);
    }
    return render::read_color(fb).value();
  }

  // Pixels that differ from the scene without trees.
  static std::vector<std::uint8_t> tree_mask(const Image& with, const Image& without) {
    std::vector<std::uint8_t> mask(static_cast<std::size_t>(with.width() * with.height()), 0);
    for (int y = 0; y < with.height(); ++y)
      for (int x = 0; x < with.width(); ++x)
        for (int c = 0; c < 3; ++c)
          if (std::abs(with.at(x, y, c) - without.at(x, y, c)) > 0.02f) mask[static_cast<std::size_t>(y * with.width() + x)] = 1;
    return mask;
  }

  // An 8-bit image file in species/ (w x h, `channels` channels, texel (x, y) = fn(x, y)).
  void write_png(const std::string& name, int w, int h, int channels, const std::function<glm::vec4(int, int)>& fn) {
    Image img(w, h, channels, PixelFormat::kU8);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < channels; ++c) img.at(x, y, c) = fn(x, y)[c];
    ASSERT_TRUE(write_image(dir_ / "species" / name, img).ok()) << name;
  }
  // A leaf image: the inscribed ellipse in `color`, transparent around it.
  void write_leaf_png(const std::string& name, glm::vec3 color) {
    write_png(name, 32, 32, 4, [&](int x, int y) {
      const float u = (x + 0.5f) / 32.0f - 0.5f, v = (y + 0.5f) / 32.0f - 0.5f;
      return u * u + v * v < 0.2f ? glm::vec4(color, 1.0f) : glm::vec4(0.0f);
    });
  }
  // Tree pixels (mask) whose channel `c` is at least twice each of the other two.
  static int dominant(const Image& img, const std::vector<std::uint8_t>& mask, int c) {
    int n = 0;
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) {
        if (!mask[static_cast<std::size_t>(y * img.width() + x)]) continue;
        const float v = img.at(x, y, c), a = img.at(x, y, (c + 1) % 3), b = img.at(x, y, (c + 2) % 3);
        if (v > 0.02f && v > 2.0f * a && v > 2.0f * b) ++n;
      }
    return n;
  }
  static int count(const std::vector<std::uint8_t>& mask) {
    int n = 0;
    for (std::uint8_t m : mask) n += m;
    return n;
  }

  fs::path dir_;
};

// Camera 80 m south of the origin at 5 m height, looking north, 12 deg vertical field of view.
constexpr const char* kSideCamera = R"({"position": [0, 5, 80], "yaw_deg": 0, "pitch_deg": 0, "fov_deg": 12})";
constexpr const char* kOneTree = R"({"area_min": [-1, -1], "area_max": [1, 1], "layout": "grid", "trees_per_hectare": 1,
    "scale_min": 1, "scale_max": 1, "leaf_texture_size": 32, "forest": {"lod": {"enabled": false}},
    "species_files": {"0": {"file": "species/red.json"}}})";

TEST_F(SpeciesFilesGl, TheLoadedTreeStandsWithItsModelsHeight) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  auto scene = open(kSideCamera, kOneTree);
  ASSERT_TRUE(scene);
  auto bare = open(kSideCamera, "");
  ASSERT_TRUE(bare);
  const nlohmann::json stats = scene->module_stats()["vegetation"];
  ASSERT_EQ(stats["trees_per_species"].size(), 1u) << stats.dump();
  EXPECT_EQ(stats["trees_per_species"]["red"].get<int>(), 1) << stats.dump();

  // The loaded model's rest bounds (the tree stands at the origin with scale 1).
  const std::vector<render::Aabb> bounds = scene->module("vegetation")->debug_bounds();
  ASSERT_EQ(bounds.size(), 1u);
  const glm::dvec3 lo = bounds[0].min, hi = bounds[0].max - glm::dvec3(0.0, scene->ground_height(0.0, 0.0), 0.0);
  ASSERT_GT(hi.y, 10.0) << "units 2: the 5 m trunk is 10 m";
  ASSERT_LT(hi.y, 11.0) << "the highest point, branch 2 at 2 x 5.06 m, plus its radius";

  const glm::ivec2 size(128, 128);
  const Image with = frame(*scene, size), without = frame(*bare, size);
  const std::vector<std::uint8_t> mask = tree_mask(with, without);
  int top = size.y, bottom = -1, left = size.x, right = -1, count = 0, red = 0;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      if (!mask[static_cast<std::size_t>(y * size.x + x)]) continue;
      ++count;
      top = std::min(top, y);
      bottom = std::max(bottom, y);
      left = std::min(left, x);
      right = std::max(right, x);
      if (with.at(x, y, 0) > 1.5f * with.at(x, y, 2)) ++red;
    }
  ASSERT_GT(count, 40) << "the tree is drawn";
  EXPECT_GT(red, count / 2) << "with the species file's red bark";
  // Rows of the image (row 0 at the top or the bottom, whichever read_color gives: compare
  // extents, not positions) against the model projected from 80 +- its horizontal radius.
  const double radius = std::max({std::abs(lo.x), std::abs(hi.x), std::abs(lo.z), std::abs(hi.z)});
  const double ground = scene->ground_height(0.0, 0.0);
  const double px_per_rad = size.y / (2.0 * std::tan(glm::radians(6.0)));
  const auto row = [&](double y, double dist) { return px_per_rad * std::atan((y - 5.0) / dist); };
  const double height_min = row(ground + hi.y, 80.0 + radius) - row(ground, 80.0 - radius);
  const double height_max = row(ground + hi.y, 80.0 - radius) - row(ground, 80.0 + radius);
  const int rows = bottom - top + 1;
  std::printf("tree: %d rows (model %.1f-%.1f), %d columns, %d pixels, %d red\n", rows, height_min, height_max, right - left + 1, count, red);
  EXPECT_GE(rows, height_min - 2.0) << "the silhouette is as tall as the model: " << rows << " rows";
  EXPECT_LE(rows, height_max + 2.0) << "the silhouette is as tall as the model: " << rows << " rows";
  const double width_max = 2.0 * px_per_rad * std::atan(radius / (80.0 - radius));
  EXPECT_LE(right - left + 1, width_max + 2.0);
  EXPECT_GE(right - left + 1, 4) << "the trunk's 1.2 m base at least";
}

// "Save as" into another folder keeps naming the same species file (its relative path rebased,
// the file not copied), so the saved scene opens with the same tree.
TEST_F(SpeciesFilesGl, SaveAsIntoAnotherFolderKeepsTheSpeciesFile) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  auto scene = open(kSideCamera, kOneTree);
  ASSERT_TRUE(scene);
  fs::create_directories(dir_ / "elsewhere");
  const fs::path copy = dir_ / "elsewhere" / "copy.json";
  ASSERT_TRUE(scene->save(copy).ok());
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(copy, warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto reloaded = Scene::create(std::move(*doc));
  ASSERT_TRUE(reloaded.ok()) << reloaded.error().message;
  EXPECT_EQ((*reloaded)->get_param("vegetation.species_files.0.file").value(), "../species/red.json");
  EXPECT_FALSE(fs::exists(dir_ / "elsewhere" / "species")) << "referenced, not copied";
  EXPECT_EQ((*reloaded)->module_stats()["vegetation"]["trees_per_species"]["red"], 1)
      << (*reloaded)->module_stats()["vegetation"].dump();
}

TEST_F(SpeciesFilesGl, AForestOfTwoSpeciesFromFilesShowsBoth) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  const std::string camera = R"({"position": [0, 8, 70], "yaw_deg": 0, "pitch_deg": -4, "fov_deg": 40})";
  const std::string stand = R"({"area_min": [-30, -30], "area_max": [30, 30], "layout": "grid", "trees_per_hectare": 100,
      "leaf_texture_size": 32, "species_files": {"0": {"file": "species/red.json", "weight": 1},
                                                 "1": {"file": "species/blue.json", "weight": 1}}})";
  auto scene = open(camera, stand);
  ASSERT_TRUE(scene);
  auto bare = open(camera, "");
  ASSERT_TRUE(bare);
  const nlohmann::json stats = scene->module_stats()["vegetation"];
  const nlohmann::json per = stats["trees_per_species"];
  ASSERT_EQ(per.size(), 2u) << stats.dump();
  EXPECT_GT(per["red"].get<int>(), 10) << stats.dump();
  EXPECT_GT(per["blue"].get<int>(), 10) << stats.dump();

  const glm::ivec2 size(160, 96);
  const Image with = frame(*scene, size), without = frame(*bare, size);
  const std::vector<std::uint8_t> mask = tree_mask(with, without);
  int red = 0, blue = 0;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      if (!mask[static_cast<std::size_t>(y * size.x + x)]) continue;
      const float r = with.at(x, y, 0), b = with.at(x, y, 2);
      if (r > 1.5f * b) ++red;
      if (b > 1.5f * r) ++blue;
    }
  std::printf("two species: %d red, %d blue pixels\n", red, blue);
  EXPECT_GT(red, 30) << "red trunks";
  EXPECT_GT(blue, 30) << "blue trunks";
}

// Issue #16's test list: "a forest of three species from files with image textures". Three
// species files, each a generated broadleaf with its own leaf image (pure red, green, blue), share
// one stand; the near rows are drawn at LOD0 and the far rows from the slices baked per species,
// and each species' leaf colour reaches the screen.
TEST_F(SpeciesFilesGl, AForestOfThreeSpeciesWithLeafImagesShowsEachColour) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  const std::array<std::pair<const char*, glm::vec3>, 3> kinds = {
      {{"reds", {1, 0, 0}}, {"greens", {0, 1, 0}}, {"blues", {0, 0, 1}}}};
  for (std::size_t i = 0; i < kinds.size(); ++i) {
    const std::string name = kinds[i].first;
    write_leaf_png(name + ".png", kinds[i].second);
    ASSERT_TRUE(write_file_atomic(dir_ / "species" / (name + ".json"),
                                  fmt::format(R"({{"name": "{}", "leaf": {{"color": "{}.png"}},
                                                 "model": {{"preset": "broadleaf", "seed": {}, "parameters": {{"trunk_length": 5}}}}}})",
                                              name, name, i + 2))
                    .ok());
  }
  const std::string camera = R"({"position": [0, 10, 60], "yaw_deg": 0, "pitch_deg": -6, "fov_deg": 50})";
  const std::string stand = R"({"area_min": [-30, -30], "area_max": [30, 30], "layout": "grid", "trees_per_hectare": 60,
      "leaf_texture_size": 32, "forest": {"lod": {"v1": 55, "v2": 400, "cache_directory": ""}},
      "species_files": {"0": {"file": "species/reds.json"}, "1": {"file": "species/greens.json"},
                        "2": {"file": "species/blues.json"}}})";
  auto scene = open(camera, stand);
  ASSERT_TRUE(scene);
  auto bare = open(camera, "");
  ASSERT_TRUE(bare);
  const nlohmann::json stats = scene->module_stats()["vegetation"];
  ASSERT_EQ(stats["trees_per_species"].size(), 3u) << stats.dump();
  for (const auto& [name, colour] : kinds) EXPECT_GT(stats["trees_per_species"][name].get<int>(), 3) << stats.dump();

  const glm::ivec2 size(192, 108);
  const Image with = frame(*scene, size), without = frame(*bare, size);
  const nlohmann::json lods = scene->module_stats()["vegetation"]["instances_per_lod"];
  EXPECT_GT(lods["lod0"].get<int>(), 0) << lods.dump();
  EXPECT_GT(lods["lod1"].get<int>(), 0) << lods.dump();
  const std::vector<std::uint8_t> mask = tree_mask(with, without);
  const int red = dominant(with, mask, 0), green = dominant(with, mask, 1), blue = dominant(with, mask, 2);
  std::printf("three species with leaf images: %d red, %d green, %d blue of %d tree pixels (lods %s)\n", red, green, blue,
              count(mask), lods.dump().c_str());
  ASSERT_GT(count(mask), 1000) << "the stand is drawn";
  EXPECT_GT(red, count(mask) / 12) << "the red species' leaf image";
  EXPECT_GT(green, count(mask) / 12) << "the green species' leaf image";
  EXPECT_GT(blue, count(mask) / 12) << "the blue species' leaf image";
}

// Slices (LOD1/LOD2) are baked for a loaded model as for a generated one: the same tree 80 m away
// at LOD1 covers about the pixels its LOD0 covers.
TEST_F(SpeciesFilesGl, ALoadedTreeGetsSlices) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  std::string lod = kOneTree;
  lod.replace(lod.find(R"("enabled": false)"), 16, R"("v1": 30, "v2": 200, "cache_directory": "")");
  auto near = open(kSideCamera, kOneTree);
  ASSERT_TRUE(near);
  auto sliced = open(kSideCamera, lod);
  ASSERT_TRUE(sliced);
  auto bare = open(kSideCamera, "");
  ASSERT_TRUE(bare);
  const glm::ivec2 size(128, 128);
  const Image without = frame(*bare, size);
  const std::vector<std::uint8_t> a = tree_mask(frame(*near, size), without);
  const std::vector<std::uint8_t> b = tree_mask(frame(*sliced, size), without);
  EXPECT_EQ(sliced->module_stats()["vegetation"]["instances_per_lod"]["lod1"].get<int>(), 1)
      << sliced->module_stats()["vegetation"].dump();
  int both = 0, either = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    both += a[i] && b[i];
    either += a[i] || b[i];
  }
  std::printf("LOD1 against LOD0: %d of %d pixels in both\n", both, either);
  ASSERT_GT(either, 40);
  EXPECT_GT(static_cast<double>(both) / either, 0.5) << "LOD1 silhouette overlaps LOD0's: " << both << " / " << either;
}

// Single trees at given spots (`vegetation.trees.N`): species files of weight 0 place no stand,
// the two named trees stand where they are told, the red one left of the blue one.
TEST_F(SpeciesFilesGl, SingleTreesStandWhereTheSceneSays) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  std::vector<std::string> logged;
  set_log_sink([&](LogLevel level, std::string_view message) {
    if (level == LogLevel::kWarn) logged.emplace_back(message);
  });
  const std::string camera = R"({"position": [0, 5, 60], "yaw_deg": 0, "pitch_deg": 0, "fov_deg": 30})";
  auto scene = open(camera, R"({"leaf_texture_size": 32, "forest": {"lod": {"enabled": false}},
      "species_files": {"0": {"file": "species/red.json", "weight": 0}, "1": {"file": "species/blue.json", "weight": 0}},
      "trees": {"0": {"species": "red", "position": [-6, 0]}, "1": {"species": "blue", "position": [6, 0], "yaw_deg": 90},
                "2": {"species": "oak", "position": [0, 0]}}})");
  set_log_sink(nullptr);
  ASSERT_TRUE(scene);
  auto bare = open(camera, "");
  ASSERT_TRUE(bare);
  const nlohmann::json stats = scene->module_stats()["vegetation"];
  EXPECT_EQ(stats["trees"].get<int>(), 2) << "weight 0: no stand, only the single trees; " << stats.dump();
  EXPECT_EQ(stats["trees_per_species"]["red"].get<int>(), 1) << stats.dump();
  EXPECT_EQ(stats["trees_per_species"]["blue"].get<int>(), 1) << stats.dump();
  const std::vector<glm::dvec3> at = scene->module("vegetation")->placed_positions(10);
  ASSERT_EQ(at.size(), 2u);
  EXPECT_EQ(at[0].x, -6.0);
  EXPECT_EQ(at[0].z, 0.0);
  EXPECT_NEAR(at[0].y, scene->ground_height(-6.0, 0.0), 1e-4);
  EXPECT_EQ(at[1].x, 6.0);
  std::string all;
  for (const std::string& m : logged) all += m + "\n";
  EXPECT_NE(all.find("vegetation.trees.2.species: no species 'oak' in the stand (red, blue)"), std::string::npos) << all;

  const glm::ivec2 size(128, 96);
  const Image with = frame(*scene, size), without = frame(*bare, size);
  const std::vector<std::uint8_t> mask = tree_mask(with, without);
  double red_x = 0.0, blue_x = 0.0;
  int red = 0, blue = 0;
  for (int y = 0; y < size.y; ++y)
    for (int x = 0; x < size.x; ++x) {
      if (!mask[static_cast<std::size_t>(y * size.x + x)]) continue;
      const float r = with.at(x, y, 0), b = with.at(x, y, 2);
      if (r > 1.5f * b) red_x += x, ++red;
      if (b > 1.5f * r) blue_x += x, ++blue;
    }
  ASSERT_GT(red, 20);
  ASSERT_GT(blue, 20);
  std::printf("single trees: red at column %.1f, blue at %.1f\n", red_x / red, blue_x / blue);
  // x = -6 and +6 m at 60 m: columns 64 -+ 6 / (60 tan(15 deg) * 4/3) * 64; the mean column of
  // each tree's bark is its trunk's within a few columns (branches reach out to one side).
  const double offset = 6.0 / (60.0 * std::tan(glm::radians(15.0)) * size.x / size.y) * size.x / 2.0;
  EXPECT_NEAR(red_x / red, size.x / 2.0 - offset, 4.0);
  EXPECT_NEAR(blue_x / blue, size.x / 2.0 + offset, 4.0);
}

// A species file's "lod" and "animation" apply to its trees only: v1 = 10 m turns the tree 80 m
// away into slices while the forest says LOD0 up to 300 m; wind_scale 0 holds it still in a
// gale, where the forest's own scale moves it.
TEST_F(SpeciesFilesGl, ASpeciesFilesLodAndAnimationApplyToItsTrees) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "red.json", R"({"name": "red", "model": {"objt": "../trees/seed.objt"}, "units": 2,
      "lod": {"v1": 10, "v2": 500}, "animation": {"wind_scale": 0}})").ok());
  std::string stand = kOneTree;
  stand.replace(stand.find(R"("enabled": false)"), 16, R"("v1": 300, "v2": 400, "cache_directory": "")");
  const auto open_windy = [&](const std::string& vegetation) {
    auto scene = open(kSideCamera, vegetation);
    if (scene) {
      EXPECT_TRUE(scene->set_param("wind.strength", "30").ok());
    }
    return scene;
  };
  auto tuned = open_windy(stand);
  ASSERT_TRUE(tuned);
  const glm::ivec2 size(96, 96);
  const auto at = [&](Scene& scene, double t) {
    auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
    render::FrameProfiler profiler;
    const render::Camera camera = scene.make_camera(scene.document().camera, size);
    for (int i = 0; i < 2; ++i) {
      scene.update(camera, t, 0.0f, size);
      scene.render(fb, profiler);
    }
    return render::read_color(fb).value();
  };
  const auto changed = [](const Image& a, const Image& b) {
    int n = 0;
    for (int y = 0; y < a.height(); ++y)
      for (int x = 0; x < a.width(); ++x)
        if (std::abs(a.at(x, y, 0) - b.at(x, y, 0)) + std::abs(a.at(x, y, 1) - b.at(x, y, 1)) > 0.03f) ++n;
    return n;
  };
  const int still = changed(at(*tuned, 2.0), at(*tuned, 3.5));
  EXPECT_EQ(tuned->module_stats()["vegetation"]["instances_per_lod"]["lod1"].get<int>(), 1)
      << "the species' v1 = 10 m, not the forest's 300 m: " << tuned->module_stats()["vegetation"].dump();
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "red.json", kRedSpecies).ok());
  auto plain = open_windy(stand);
  ASSERT_TRUE(plain);
  const int moving = changed(at(*plain, 2.0), at(*plain, 3.5));
  EXPECT_EQ(plain->module_stats()["vegetation"]["instances_per_lod"]["lod0"].get<int>(), 1);
  std::printf("wind_scale 0: %d pixels change in 1.5 s of a 30 m/s wind; the forest's scale: %d\n", still, moving);
  EXPECT_EQ(still, 0);
  EXPECT_GT(moving, 10);
}

// A generated broadleaf from a species file, 80 m away (kSideCamera), alone.
constexpr const char* kLeafyTree = R"({"area_min": [-1, -1], "area_max": [1, 1], "layout": "grid", "trees_per_hectare": 1,
    "scale_min": 1, "scale_max": 1, "leaf_texture_size": 32, "forest": {"lod": {"enabled": false}},
    "species_files": {"0": {"file": "species/leafy.json"}}})";
std::string sliced(std::string stand) {
  return stand.replace(stand.find(R"("enabled": false)"), 16, R"("v1": 30, "v2": 200, "cache_directory": "")");
}

// Leaf images (issue #16): pure blue leaves from a species file's "leaf.color" are blue on the
// screen at LOD0 and in the baked slices (LOD1 forced by v1 = 30 m); the procedural leaves of the
// same tree are not.
TEST_F(SpeciesFilesGl, ALeafImageColoursTheLeavesAtLod0AndInSlices) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  write_leaf_png("blue_leaf.png", {0.0f, 0.0f, 1.0f});
  const std::string model = R"("model": {"preset": "broadleaf", "seed": 2, "parameters": {"trunk_length": 5}})";
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "leafy.json", R"({"name": "leafy", )" + model + "}").ok());
  auto plain = open(kSideCamera, kLeafyTree);
  ASSERT_TRUE(plain);
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "leafy.json", R"({"name": "leafy", "leaf": {"color": "blue_leaf.png"}, )" + model + "}").ok());
  auto near = open(kSideCamera, kLeafyTree);
  ASSERT_TRUE(near);
  auto far = open(kSideCamera, sliced(kLeafyTree));
  ASSERT_TRUE(far);
  auto bare = open(kSideCamera, "");
  ASSERT_TRUE(bare);
  const glm::ivec2 size(128, 128);
  const Image without = frame(*bare, size);
  const Image p = frame(*plain, size), n = frame(*near, size), f = frame(*far, size);
  EXPECT_EQ(far->module_stats()["vegetation"]["instances_per_lod"]["lod1"].get<int>(), 1) << far->module_stats()["vegetation"].dump();
  EXPECT_EQ(near->module_stats()["vegetation"]["instances_per_lod"]["lod0"].get<int>(), 1) << near->module_stats()["vegetation"].dump();
  const std::vector<std::uint8_t> mp = tree_mask(p, without), mn = tree_mask(n, without), mf = tree_mask(f, without);
  const int plain_blue = dominant(p, mp, 2), near_blue = dominant(n, mn, 2), far_blue = dominant(f, mf, 2);
  std::printf("blue leaf pixels: procedural %d of %d, leaf image LOD0 %d of %d, LOD1 %d of %d\n", plain_blue, count(mp), near_blue,
              count(mn), far_blue, count(mf));
  ASSERT_GT(count(mn), 200) << "the crown is drawn";
  EXPECT_LT(plain_blue, count(mp) / 50) << "procedural leaves are green";
  EXPECT_GT(near_blue, count(mn) / 2) << "LOD0 leaves show the image's blue";
  EXPECT_GT(far_blue, count(mf) / 2) << "the slices show it too";
}

// The slices bake the leaf image's colour deviation (c_v, eq. 3.34), not only its mean: leaves
// half red, half blue (mean purple) seen from 25 m show red and blue pixels at LOD0 and LOD1.
TEST_F(SpeciesFilesGl, TwoColouredLeavesStayTwoColouredInSlices) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  write_png("two_leaf.png", 32, 32, 4, [&](int x, int y) {
    const float u = (x + 0.5f) / 32.0f - 0.5f, v = (y + 0.5f) / 32.0f - 0.5f;
    if (u * u + v * v >= 0.2f) return glm::vec4(0.0f);
    return x < 16 ? glm::vec4(1.0f, 0.0f, 0.0f, 1.0f) : glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  });
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "leafy.json", R"({"name": "leafy", "leaf": {"color": "two_leaf.png"},
      "model": {"preset": "broadleaf", "seed": 2, "parameters": {"trunk_length": 5}}})").ok());
  const std::string camera = R"({"position": [0, 6, 22], "yaw_deg": 0, "pitch_deg": 0, "fov_deg": 50})";
  std::string stand = kLeafyTree;
  stand.replace(stand.find(R"("leaf_texture_size": 32)"), 23, R"("leaf_texture_size": 64)");
  std::string far_stand = stand;
  far_stand.replace(far_stand.find(R"("enabled": false)"), 16, R"("v1": 5, "v2": 200, "slice_resolution": 512, "cache_directory": "")");
  auto near = open(camera, stand);
  ASSERT_TRUE(near);
  auto far = open(camera, far_stand);
  ASSERT_TRUE(far);
  auto bare = open(camera, "");
  ASSERT_TRUE(bare);
  const glm::ivec2 size(256, 256);
  const Image without = frame(*bare, size);
  const Image n = frame(*near, size), f = frame(*far, size);
  EXPECT_EQ(far->module_stats()["vegetation"]["instances_per_lod"]["lod1"].get<int>(), 1) << far->module_stats()["vegetation"].dump();
  const std::vector<std::uint8_t> mn = tree_mask(n, without), mf = tree_mask(f, without);
  std::printf("two-coloured leaves: LOD0 %d red %d blue of %d, LOD1 %d red %d blue of %d\n", dominant(n, mn, 0), dominant(n, mn, 2),
              count(mn), dominant(f, mf, 0), dominant(f, mf, 2), count(mf));
  // A bake of the mean colour alone (purple) would give neither; procedural leaves neither.
  ASSERT_GT(count(mn), 1000);
  EXPECT_GT(dominant(n, mn, 0), count(mn) / 5);
  EXPECT_GT(dominant(n, mn, 2), count(mn) / 5);
  EXPECT_GT(dominant(f, mf, 0), count(mf) / 10) << "red leaf halves in the slices";
  EXPECT_GT(dominant(f, mf, 2), count(mf) / 10) << "blue leaf halves in the slices";
}

// A bark image colours the trunk, over the file's bark_color (which then warns).
TEST_F(SpeciesFilesGl, ABarkImageColoursTheTrunk) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  write_png("green_bark.png", 8, 8, 3, [](int, int) { return glm::vec4(0.05f, 0.8f, 0.05f, 1.0f); });
  std::string red = kRedSpecies;
  red.insert(red.rfind('}'), R"(, "bark": {"color": "green_bark.png"})");
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "red.json", red).ok());
  std::vector<std::string> logged;
  set_log_sink([&](LogLevel level, std::string_view message) {
    if (level == LogLevel::kWarn) logged.emplace_back(message);
  });
  auto scene = open(kSideCamera, kOneTree);
  set_log_sink(nullptr);
  ASSERT_TRUE(scene);
  auto bare = open(kSideCamera, "");
  ASSERT_TRUE(bare);
  std::string all;
  for (const std::string& m : logged) all += m + "\n";
  EXPECT_NE(all.find("vegetation.species_files.0.file: red.json: bark_color: ignored, bark.color gives the bark"), std::string::npos) << all;
  const glm::ivec2 size(128, 128);
  const Image with = frame(*scene, size);
  const std::vector<std::uint8_t> mask = tree_mask(with, frame(*bare, size));
  const int green = dominant(with, mask, 1), reds = dominant(with, mask, 0);
  std::printf("bark image: %d green, %d red of %d tree pixels\n", green, reds, count(mask));
  ASSERT_GT(count(mask), 40);
  EXPECT_GT(green, count(mask) / 2) << "the image's green bark";
  EXPECT_EQ(reds, 0) << "not bark_color's red";
}

// A season image (seed §4.6, one column, top = season 1) sets the leaves' colour by the scene's
// season: the lower half blue, the upper half red. The tree's season coordinate is
// environment.season + 79/365 + 0.2 leafSpecificNumber - 0.04 (per tree), so season 0.42 reads
// only red rows and 0.9 (wrapping) only blue ones.
TEST_F(SpeciesFilesGl, ASeasonImageChangesTheLeafColourWithTheSeason) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  write_leaf_png("grey_leaf.png", glm::vec3(0.5f));
  write_png("season.png", 1, 8, 3, [](int, int y) { return y < 4 ? glm::vec4(0.9f, 0.0f, 0.0f, 1.0f) : glm::vec4(0.0f, 0.0f, 0.9f, 1.0f); });
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "leafy.json", R"({"name": "leafy", "leaf": {"color": "grey_leaf.png"},
      "season": "season.png", "model": {"preset": "broadleaf", "seed": 2, "parameters": {"trunk_length": 5}}})").ok());
  auto autumn = open(kSideCamera, kLeafyTree, R"(, "environment": {"season": 0.42})");
  ASSERT_TRUE(autumn);
  auto spring = open(kSideCamera, kLeafyTree, R"(, "environment": {"season": 0.9})");
  ASSERT_TRUE(spring);
  auto bare = open(kSideCamera, "");
  ASSERT_TRUE(bare);
  const glm::ivec2 size(128, 128);
  const Image without = frame(*bare, size);
  const Image a = frame(*autumn, size), b = frame(*spring, size);
  const std::vector<std::uint8_t> ma = tree_mask(a, without), mb = tree_mask(b, without);
  const int a_red = dominant(a, ma, 0), a_blue = dominant(a, ma, 2), b_red = dominant(b, mb, 0), b_blue = dominant(b, mb, 2);
  std::printf("season image: season 0.42 %d red %d blue of %d; season 0.9 %d red %d blue of %d\n", a_red, a_blue, count(ma), b_red,
              b_blue, count(mb));
  ASSERT_GT(count(ma), 200);
  EXPECT_GT(a_red, count(ma) / 2);
  EXPECT_EQ(a_blue, 0);
  EXPECT_GT(b_blue, count(mb) / 2);
  EXPECT_EQ(b_red, 0) << "the trunk is brown, not red enough to count";
}

// The shipped example (scenes/species/grove.json, not a golden scene): every species file loads
// (painted_birch.json with its image set),
// without a warning beyond the seed example's own left-handed frames, and the trees are drawn.
TEST_F(SpeciesFilesGl, TheShippedExampleOpens) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  std::vector<std::string> logged;
  set_log_sink([&](LogLevel level, std::string_view message) {
    if (level == LogLevel::kWarn) logged.emplace_back(message);
  });
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(fs::path(SYLVA_SCENES_DIR) / "species" / "grove.json", warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  auto scene = Scene::create(std::move(*doc));
  set_log_sink(nullptr);
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  for (const std::string& m : logged) EXPECT_NE(m.find("left-handed"), std::string::npos) << m;
  const nlohmann::json per = (*scene)->module_stats()["vegetation"]["trees_per_species"];
  ASSERT_EQ(per.size(), 4u) << per.dump();
  EXPECT_GT(per["sapling"].get<int>(), 0) << per.dump();
  EXPECT_GT(per["painted birch"].get<int>(), 0) << "leaf, bark and season images (scenes/species/images)" << per.dump();
  EXPECT_GT(per["slender conifer"].get<int>(), 0) << per.dump();
  EXPECT_EQ(per["seed example"].get<int>(), 1) << "the single tree" << per.dump();
  const glm::ivec2 size(96, 54);
  (void)frame(**scene, size);
  EXPECT_GT((*scene)->module_stats()["vegetation"]["trees_drawn"].get<int>(), 5);
}

TEST_F(SpeciesFilesGl, AFailingSpeciesFileIsLeftOutWithAWarning) {
  if (!find_module("vegetation")) GTEST_SKIP() << "vegetation is built out";
  std::vector<std::string> logged;
  set_log_sink([&](LogLevel level, std::string_view message) {
    if (level == LogLevel::kWarn) logged.emplace_back(message);
  });
  ASSERT_TRUE(write_file_atomic(dir_ / "species" / "broken.json", R"({"model": {"objt": "../trees/oak.objt"}})").ok());
  const std::string stand = R"({"area_min": [-1, -1], "area_max": [1, 1], "layout": "grid", "trees_per_hectare": 1,
      "leaf_texture_size": 32, "forest": {"lod": {"enabled": false}},
      "species_files": {"0": {"file": "species/red.json"}, "1": {"file": "species/broken.json"}}})";
  auto scene = open(kSideCamera, stand);
  auto none = [&] {
    std::vector<std::string> warnings;
    EXPECT_TRUE(write_file_atomic(dir_ / "only_broken.json", R"({"ground": {"resolution": 33, "size": 64, "generator": "flat"},
        "vegetation": {"leaf_texture_size": 32, "species_files": {"0": {"file": "species/broken.json"}}}})")
                    .ok());
    auto doc = SceneDocument::load(dir_ / "only_broken.json", warnings);
    EXPECT_TRUE(doc.ok());
    return Scene::create(std::move(*doc));
  }();
  set_log_sink(nullptr);
  ASSERT_TRUE(scene);
  const nlohmann::json per = scene->module_stats()["vegetation"]["trees_per_species"];
  EXPECT_EQ(per.size(), 1u) << per.dump();
  EXPECT_TRUE(per.contains("red")) << per.dump();
  std::string all;
  for (const std::string& m : logged) all += m + "\n";
  EXPECT_NE(all.find("vegetation.species_files.1.file: broken.json: model.objt: no such file ../trees/oak.objt"), std::string::npos)
      << all;
  // The editor's and --set's path: a slot set by its parameter path rebuilds the stand.
  ASSERT_TRUE(scene->set_param("vegetation.species_files.1.file", "species/blue.json").ok());
  const nlohmann::json after = scene->module_stats()["vegetation"]["triangles_per_tree"];
  EXPECT_EQ(after.size(), 2u) << after.dump();
  EXPECT_TRUE(after.contains("blue")) << after.dump();
  ASSERT_FALSE(none.ok()) << "no species left";
  EXPECT_NE(none.error().message.find("no species left"), std::string::npos) << none.error().message;
}

}  // namespace
