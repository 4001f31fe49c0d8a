// The general-model terrain (seed 002 §4) reached through a scene file's "model_terrain" section:
// the shipped scenes/model_terrain.json (an OBJ with an overhanging cliff) builds its model tree
// and draws it, covering every pixel where it must be seen, with segments, triangles and GPU bytes
// in the stats; the seed's reduce per pass is reachable from the file; missing and broken meshes
// are clear errors naming the file (and line).
#include <sylva/core/atomic_file.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gpu_memory.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/frame_stats.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include "render_once.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include <unistd.h>

namespace fs = std::filesystem;
using namespace sylva;
using namespace sylva::scene;

namespace {

using ModelTerrainGl = render::GlTest;

const fs::path kScene = fs::path(SYLVA_SCENES_DIR) / "model_terrain.json";

// The shipped scene, less the modules in `drop`.
std::unique_ptr<Scene> shipped(std::initializer_list<const char*> drop) {
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(kScene, warnings);
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  if (!doc.ok()) return nullptr;
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  for (const char* m : drop) doc->remove_module(m);
  doc->render.shadows.enabled = false;  // speed; the shipped scene's shadows run in shipped_scenes
  auto scene = Scene::create(std::move(*doc));
  EXPECT_TRUE(scene.ok()) << scene.error().message;
  return scene.ok() ? std::move(*scene) : nullptr;
}

Image frame(Scene& scene, const render::Camera& camera, glm::ivec2 size) {
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
  render::FrameProfiler profiler;
  scene.update(camera, 0.0, 0.0f, size);
  scene.render(fb, profiler);
  return render::read_color(fb).value();
}

std::size_t differing_pixels(const Image& a, const Image& b) {
  std::size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > 1.5f / 255.0f) {
          ++n;
          break;
        }
  return n;
}

TEST_F(ModelTerrainGl, ShippedSceneDrawsTheModelWhereItMustBeSeen) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  auto with = shipped({"ground"});
  auto without = shipped({"ground", "model_terrain"});
  ASSERT_TRUE(with && without);
  const glm::ivec2 size(128, 72);
  // Straight down from 150 m over the 400 m square (heights 0..~75 m): every pixel's ray runs
  // from above the sheet to below it inside the square, so the model must cover the whole frame
  // (any sheet with the square as its outline is crossed, at any mix of segment levels).
  render::Camera down = with->make_camera(with->document().camera, size);
  down.set_position({10.0, 150.0, -5.0});
  down.set_yaw_pitch(0.3f, -1.55f);
  const Image model = frame(*with, down, size), sky = frame(*without, down, size);
  EXPECT_EQ(differing_pixels(model, sky), model.pixel_count()) << "every pixel shows the model, none the sky";
  const nlohmann::json s = with->module_stats()["model_terrain"];
  EXPECT_GT(s["segments_drawn"].get<std::uint64_t>(), 0u);
  EXPECT_GT(s["triangles"].get<std::uint64_t>(), 0u);
  EXPECT_EQ(s["mesh_triangles"].get<std::uint64_t>(), 32768u) << "128 x 128 quads (scripts/make-model-terrain-mesh)";
  EXPECT_EQ(s["tree_levels"].get<int>(), 5);
  EXPECT_LE(s["max_projected_error_px"].get<double>(), 1.0) << "render.lod.max_pixel_error of the file";
  EXPECT_GT(s["gpu_bytes"].get<std::uint64_t>(), 32768u * 3u * 4u) << "at least the leaves' indices";
  EXPECT_GE(render::gpu_memory_usage()["model_terrain"].bytes[static_cast<int>(render::GpuMemoryKind::kBuffer)],
            s["gpu_bytes"].get<std::uint64_t>()) << "tracked under the module's name";

  // The file's own view: the cliff stands in the frame; a coarser tau draws fewer triangles.
  const render::Camera view = with->make_camera(with->document().camera, size);
  const Image a = frame(*with, view, size), b = frame(*without, view, size);
  EXPECT_GT(differing_pixels(a, b), a.pixel_count() / 4);
  const std::uint64_t fine = with->module_stats()["model_terrain"]["triangles"].get<std::uint64_t>();
  ASSERT_TRUE(with->set_param("model_terrain.render.lod.max_pixel_error", "8").ok());
  (void)frame(*with, view, size);
  const nlohmann::json coarse = with->module_stats()["model_terrain"];
  EXPECT_LT(coarse["triangles"].get<std::uint64_t>(), fine);
  EXPECT_GT(coarse["segments_drawn"].get<std::uint64_t>(), 0u);
  std::printf("model_terrain: from above %s segments, %s triangles, %s GPU bytes; the file's view at tau 1: %llu "
              "triangles, at tau 8: %s\n", s["segments_drawn"].dump().c_str(), s["triangles"].dump().c_str(),
              s["gpu_bytes"].dump().c_str(), static_cast<unsigned long long>(fine), coarse["triangles"].dump().c_str());
}

// Shadows: the model casts into the scene's cascades (the shadow pass draws its segments) and
// what it casts darkens the picture (onto itself and the ground) against cast_shadows = false.
TEST_F(ModelTerrainGl, CastsShadowsIntoTheScene) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  std::vector<std::string> warnings;
  auto doc = SceneDocument::load(kScene, warnings);
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  ASSERT_TRUE(doc->render.shadows.enabled);
  auto scene = Scene::create(std::move(*doc));
  ASSERT_TRUE(scene.ok()) << scene.error().message;
  const glm::ivec2 size(160, 90);
  // A sun behind the cliff (azimuth 90, 30 degrees up) lays its shadow toward the file's camera.
  ASSERT_TRUE((*scene)->set_param("sun.azimuth_deg", "90").ok());
  ASSERT_TRUE((*scene)->set_param("sun.elevation_deg", "30").ok());
  const render::Camera down = (*scene)->make_camera((*scene)->document().camera, size);
  const auto shot = [&](std::uint64_t& shadow_triangles) {
    auto fb = render::Framebuffer::create({.width = size.x, .height = size.y}).value();
    render::FrameProfiler profiler;
    for (int i = 0; i < 2; ++i) {
      (*scene)->update(down, 0.0, 0.0f, size);
      (*scene)->render(fb, profiler);
    }
    auto stats = profiler.flush();
    shadow_triangles = stats ? split_frame_stats(*stats).modules["model_terrain"]["shadow"].triangles : 0;
    return render::read_color(fb).value();
  };
  std::uint64_t cast = 0, none = 0;
  const Image lit = shot(cast);
  ASSERT_TRUE((*scene)->set_param("model_terrain.render.cast_shadows", "false").ok());
  const Image unshadowed = shot(none);
  EXPECT_GT(cast, 0u) << "the shadow pass draws the model";
  EXPECT_EQ(none, 0u);
  std::size_t darker = 0;
  for (int y = 0; y < lit.height(); ++y)
    for (int x = 0; x < lit.width(); ++x) {
      const float a = lit.at(x, y, 0) + lit.at(x, y, 1) + lit.at(x, y, 2);
      const float b = unshadowed.at(x, y, 0) + unshadowed.at(x, y, 1) + unshadowed.at(x, y, 2);
      if (a < 0.9f * b) ++darker;  // the sun term is lost, the sky light stays
    }
  EXPECT_GT(darker, lit.pixel_count() / 20) << "the model's shadow shows";
  std::printf("shadows: %llu triangles in the shadow pass, %zu of %zu pixels darker\n",
              static_cast<unsigned long long>(cast), darker, lit.pixel_count());
}

// Tab. 4.6-4.11's axis from a file: tree.reduce_per_pass (seed -reduce) and tree.levels.
TEST_F(ModelTerrainGl, ReducePerPassIsSetFromTheSceneFile) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  std::uint64_t previous = 0;
  for (const char* reduce : {"0.25", "0.75"}) {
    std::vector<std::string> warnings;
    auto doc = SceneDocument::load(kScene, warnings);
    ASSERT_TRUE(doc.ok()) << doc.error().message;
    ASSERT_TRUE(doc->params().set("model_terrain.tree.levels", "3").ok());
    ASSERT_TRUE(doc->params().set("model_terrain.tree.reduce_per_pass", reduce).ok());
    doc->remove_module("ground");
    auto scene = Scene::create(std::move(*doc));
    ASSERT_TRUE(scene.ok()) << scene.error().message;
    sylva::scene::testing::render_once(**scene);
    const nlohmann::json s = (*scene)->module_stats()["model_terrain"];
    const std::uint64_t root = s["tree_triangles"]["level0"].get<std::uint64_t>();
    EXPECT_EQ(s["tree_triangles"]["level2"].get<std::uint64_t>(), 32768u) << "leaves are the original";
    if (previous != 0) {
      EXPECT_LT(root, previous / 2) << "removing 75 % per pass keeps far fewer than 25 %";
    }
    std::printf("reduce_per_pass %s, 3 levels: %s\n", reduce, s["tree_triangles"].dump().c_str());
    previous = root;
  }
}

TEST_F(ModelTerrainGl, MissingOrBrokenMeshIsAClearError) {
  if (!find_module("model_terrain")) GTEST_SKIP() << "terrain is built out";
  const fs::path dir = fs::temp_directory_path() / ("sylva_model_terrain_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const auto scene_with = [&](const std::string& file) {
    std::vector<std::string> warnings;
    EXPECT_TRUE(write_file_atomic(dir / "s.json", R"({"model_terrain": {"file": ")" + file + R"("}})").ok());
    auto doc = SceneDocument::load(dir / "s.json", warnings);
    EXPECT_TRUE(doc.ok()) << doc.error().message;
    return Scene::create(std::move(*doc));
  };
  auto missing = scene_with("nowhere.obj");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("nowhere.obj"), std::string::npos) << missing.error().message;
  EXPECT_NE(missing.error().message.find("model_terrain.file"), std::string::npos) << missing.error().message;

  ASSERT_TRUE(write_file_atomic(dir / "broken.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 x\n").ok());
  auto broken = scene_with("broken.obj");
  ASSERT_FALSE(broken.ok());
  EXPECT_NE(broken.error().message.find("broken.obj:4"), std::string::npos) << broken.error().message;
  std::printf("errors: %s | %s\n", missing.error().message.c_str(), broken.error().message.c_str());

  auto none = scene_with("");
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.error().message.find("model_terrain.file"), std::string::npos) << none.error().message;
  fs::remove_all(dir);
}

}  // namespace
