// The voxel renderer's settings from a scene file (issue #18, "Voxel world"): `voxel.render.*` in
// the file a user writes reaches the renderer. The baked plant meshes (plant_near_mesh,
// plant_far_mesh) against the instanced cubes: the module's counts show which path drew the
// plants, and the pictures match.
#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/image_metrics.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/scene/module_registry.hpp>
#include <sylva/scene/scene.hpp>

#include "scene_test_files.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace sylva;
using namespace sylva::scene;

namespace {

using VoxelRenderSettingsGl = render::GlTest;

struct Frame {
  Image image;
  nlohmann::json stats;
};

// A 3 x 3 chunk column world (seed 3, the shipped spawn's) seen from 70 blocks above its middle,
// plants past 40 blocks as far shells, with `render` added to the file's voxel.render and `sun`
// as its sun block.
Frame render_file(const scene::testing::TestDir& dir, const std::string& render, const std::string& sun = "{}",
                  bool shadows = false) {
  const std::string text = fmt::format(R"({{"camera": {{"position": [16, 70, 16], "yaw_deg": 45, "pitch_deg": -60, "fov_deg": 60}},
      "render": {{"msaa_samples": 1, "shadows": {{"enabled": {}}}, "tone_map": false}}, "sun": {},
      "voxel": {{"center": [16, 16], "radius_chunks": 1, "threads": 2, "worldgen": {{"seed": 3, "variants_per_species": 4}},
                 "render": {{"plant_far_beyond": 40{}}}}}}})",
                                       shadows ? "true" : "false", sun, render);
  const auto file = dir.path / "scene.json";
  EXPECT_TRUE(write_file_atomic(file, text).ok());
  auto scene = scene::testing::open_scene_file(file);
  if (!scene) return {};
  const glm::ivec2 size(240, 135);
  auto fb = render::Framebuffer::create({.width = size.x, .height = size.y, .color_formats = {GL_RGBA32F}}).value();
  render::FrameProfiler profiler;
  const render::Camera camera = scene->make_camera(scene->document().camera, size);
  scene->update(camera, 0.0, 0.0f, size);
  scene->render(fb, profiler);
  return {render::read_color(fb).value(), scene->module_stats()["voxel"]};
}

// Pixels whose largest channel difference exceeds `tolerance`, and the largest difference
// (core's image metrics; the frames' alpha is 1 everywhere, so only colour counts).
std::size_t differing_pixels(const Image& a, const Image& b, float tolerance) {
  return count_exceeding(a, b, tolerance).value().pixels;
}

float max_difference(const Image& a, const Image& b) { return count_exceeding(a, b, 0.0f).value().max_difference; }

std::size_t count(const nlohmann::json& stats, const char* name) { return stats.at(name).get<std::size_t>(); }

TEST_F(VoxelRenderSettingsGl, PlantMeshSettingsFromTheSceneFileChooseHowPlantsAreDrawn) {
  if (!find_module("voxel")) GTEST_SKIP() << "voxel is built out";
  scene::testing::TestDir dir("sylva_voxel_render_settings");
  const Frame instanced = render_file(dir, R"(, "plant_near_mesh": false, "plant_far_mesh": false)");
  const Frame near_baked = render_file(dir, R"(, "plant_near_mesh": true, "plant_far_mesh": false)");
  const Frame baked = render_file(dir, R"(, "plant_near_mesh": true, "plant_far_mesh": true)");
  ASSERT_FALSE(instanced.stats.is_null() || near_baked.stats.is_null() || baked.stats.is_null());
  // Instanced: every plant is a cube instance, nothing baked; near and far chunks in view.
  EXPECT_GT(count(instanced.stats, "plant_parts_drawn"), 1000u);
  EXPECT_GT(count(instanced.stats, "plant_far_chunks"), 0u);
  EXPECT_EQ(count(instanced.stats, "plant_mesh_triangles"), 0u);
  // Near plants baked: only the far shells stay instanced.
  EXPECT_GT(count(near_baked.stats, "plant_mesh_triangles"), 0u);
  EXPECT_GT(count(near_baked.stats, "plant_parts_drawn"), 0u);
  EXPECT_LT(count(near_baked.stats, "plant_parts_drawn"), count(instanced.stats, "plant_parts_drawn"));
  // Both baked (the defaults): no plant instance left, every plant triangle from a mesh.
  EXPECT_EQ(count(baked.stats, "plant_parts_drawn"), 0u);
  EXPECT_EQ(count(baked.stats, "plant_mesh_triangles"), count(baked.stats, "plant_triangles"));
  EXPECT_GT(count(baked.stats, "plant_mesh_triangles"), count(near_baked.stats, "plant_mesh_triangles"));
  // The same picture (a few edge pixels allowed: corners rounded on the CPU instead of the GPU).
  ASSERT_EQ(instanced.image.width(), baked.image.width());
  EXPECT_LE(differing_pixels(instanced.image, near_baked.image, 0.02f), 10u);
  EXPECT_LE(differing_pixels(instanced.image, baked.image, 0.02f), 10u);
  // Not a blank frame passing by accident: plants and ground cover most of it.
  std::size_t lit = 0;
  for (int y = 0; y < baked.image.height(); ++y)
    for (int x = 0; x < baked.image.width(); ++x) lit += baked.image.at(x, y, 0) + baked.image.at(x, y, 1) > 0.05f;
  EXPECT_GT(lit, static_cast<std::size_t>(baked.image.width() * baked.image.height() / 2));
}

// voxel.render.aerial_perspective from the file: per_pixel, per_vertex (the default, also when the
// file names none) and off draw three different programs' pictures, per_vertex within 2/255 of
// per_pixel. A haze thinning with height makes the extinction per metre depend on the view ray.
TEST_F(VoxelRenderSettingsGl, AerialPerspectiveFromTheSceneFile) {
  if (!find_module("voxel")) GTEST_SKIP() << "voxel is built out";
  scene::testing::TestDir dir("sylva_voxel_render_air");
  const std::string haze = R"({"fog_density": 0.006, "fog_height_falloff": 0.03})";
  const Frame per_pixel = render_file(dir, R"(, "aerial_perspective": "per_pixel")", haze);
  const Frame per_vertex = render_file(dir, R"(, "aerial_perspective": "per_vertex")", haze);
  const Frame unnamed = render_file(dir, "", haze);
  const Frame off = render_file(dir, R"(, "aerial_perspective": "off")", haze);
  ASSERT_GT(per_pixel.image.width(), 0);
  ASSERT_EQ(per_pixel.image.width(), off.image.width());
  EXPECT_LE(max_difference(per_pixel.image, per_vertex.image), 2.0f / 255.0f + 1e-6f);
  EXPECT_GT(differing_pixels(per_pixel.image, per_vertex.image, 0.0f), 0u) << "per_vertex drew per_pixel's programs";
  EXPECT_EQ(differing_pixels(per_vertex.image, unnamed.image, 0.0f), 0u) << "per_vertex is the default";
  EXPECT_GT(differing_pixels(per_pixel.image, off.image, 8.0f / 255.0f), per_pixel.image.pixel_count() / 4)
      << "off still draws the air";
}

// Issue 18: the scene's frames sample the voxel shadows only when its shadows are on, known
// without reading the shadow block back from the GPU (which stalls hardware drivers' pipelines):
// on, its shadow pass ran; off, its render::ShadowMaps block says "disabled" on the CPU.
TEST_F(VoxelRenderSettingsGl, SceneShadowsOnAreKnownWithoutAReadBack) {
  if (!find_module("voxel")) GTEST_SKIP() << "voxel is built out";
  scene::testing::TestDir dir("sylva_voxel_shadow_reads");
  const Frame on = render_file(dir, "", "{}", true);
  const Frame off = render_file(dir, "", "{}", false);
  ASSERT_FALSE(on.stats.is_null() || off.stats.is_null());
  EXPECT_EQ(count(on.stats, "shadow_lookup_shaders"), 1u);
  EXPECT_EQ(count(on.stats, "shadow_flag_reads"), 0u);
  EXPECT_EQ(count(off.stats, "shadow_lookup_shaders"), 0u);
  EXPECT_EQ(count(off.stats, "shadow_flag_reads"), 0u) << "the scene's ShadowMaps block: known on the CPU";
}

}  // namespace
