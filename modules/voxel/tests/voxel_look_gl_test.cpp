// How a generated voxel world looks (issue #19): no face of a sunlit world is black (sky and
// bounce light reach the sides turned away from the sun), and the shipped world
// (scenes/voxel_world.json: 10 chunks of view radius, as fogleman/Craft) fades into the sky at
// its edge, with no pixel below the horizon left at the clear colour (the void behind the edge).

#include <sylva/core/image.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/voxel/voxel_renderer.hpp>
#include <sylva/voxel/world_builder.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "support/voxel_gl_scene.hpp"

namespace sylva::voxel {
namespace {

using VoxelLookGl = render::GlTest;

constexpr glm::vec4 kMagenta{1.0f, 0.0f, 1.0f, 1.0f};  // a clear colour no voxel shades to

struct GeneratedWorld {
  std::shared_ptr<const WorldGenerator> generator;
  World world;
};

std::unique_ptr<GeneratedWorld> generate(std::uint64_t seed, int radius_chunks, const ChunkCoord& center) {
  WorldGenSettings s;
  s.seed = seed;
  s.variants_per_species = 4;
  auto g = WorldGenerator::create(s);
  EXPECT_TRUE(g.ok()) << (g.ok() ? "" : g.error().message);
  if (!g.ok()) return nullptr;
  auto w = std::make_unique<GeneratedWorld>();
  w->generator = *g;
  std::int64_t y0 = 0, y1 = 0;
  chunk_y_range(s, y0, y1);
  WorkerPool pool(2);
  populate(w->world, *w->generator, chunk_box(center, radius_chunks, y0, y1), pool);
  remesh_parallel(w->world, pool, MesherKind::kBitmask);
  return w;
}

bool is_clear(const Image& img, int x, int y) {
  return img.at(x, y, 0) == 1.0f && img.at(x, y, 1) == 0.0f && img.at(x, y, 2) == 1.0f;
}

// What the eye sees of a pixel's light: its luminance through the sRGB transfer curve.
float display_luminance(const Image& img, int x, int y) {
  const float l = 0.2126f * img.at(x, y, 0) + 0.7152f * img.at(x, y, 1) + 0.0722f * img.at(x, y, 2);
  return l <= 0.0031308f ? 12.92f * l : 1.055f * std::pow(l, 1.0f / 2.4f) - 0.055f;
}

TEST_F(VoxelLookGl, NoFaceOfASunlitWorldIsBlack) {
  auto w = generate(3, 2, {0, 0, 0});
  ASSERT_TRUE(w);
  auto renderer = VoxelRenderer::create(w->world, w->generator);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(256, 144);
  scene.clear_color = kMagenta;
  // The shipped world's sun (azimuth 140, elevation 40 degrees), no cast shadows bound: the
  // darkest faces are those turned away from the sun, in ambient-occluded corners.
  scene.lighting.sun_direction = render::sun_direction(glm::radians(140.0f), glm::radians(40.0f));
  scene.camera.set_position({16.0, 48.0, 16.0});
  // Four views: one of them looks into the sun, at the sides turned away from it.
  for (float yaw : {0.0f, 90.0f, 180.0f, 270.0f}) {
    scene.camera.set_yaw_pitch(glm::radians(yaw), glm::radians(-25.0f));
    scene.render(**renderer);
    const Image img = scene.color();
    float lo = 1.0f, hi = 0.0f;
    int surface = 0;
    for (int y = 0; y < img.height(); ++y) {
      for (int x = 0; x < img.width(); ++x) {
        if (is_clear(img, x, y)) continue;
        ++surface;
        const float d = display_luminance(img, x, y);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    }
    ASSERT_GT(surface, img.width() * img.height() / 2) << "yaw " << yaw << ": the world fills the view";
    std::printf("yaw %.0f: darkest %.3f, brightest %.3f (display luminance)\n", static_cast<double>(yaw),
                static_cast<double>(lo), static_cast<double>(hi));
    // Floor: 0.15 of the brightest, as displayed. Measured 0.18-0.21 (darkest / brightest per
    // view); with the plain hemisphere ambient (sky_light 1, bounce 0) 0.10-0.13, which fails.
    EXPECT_GE(lo, 0.15f * hi) << "yaw " << yaw << ": darkest " << lo << ", brightest " << hi;
    if (lo < 0.15f * hi) testing::save_png(img, "voxel_look_black_faces_yaw" + std::to_string(static_cast<int>(yaw)));
  }
}

// The shipped scene file, read as the scene module reads its voxel section (not linked here).
struct ShippedWorld {
  nlohmann::json json;
  glm::dvec3 position;
  float yaw = 0, pitch = 0, fov = 60;
};

ShippedWorld read_shipped_world() {
  ShippedWorld s;
  std::ifstream in(std::string(SYLVA_VOXEL_DATA_DIR) + "/../../../scenes/voxel_world.json");
  EXPECT_TRUE(in.good());
  s.json = nlohmann::json::parse(in);
  const auto& cam = s.json.at("camera");
  s.position = {cam.at("position")[0].get<double>(), cam.at("position")[1].get<double>(), cam.at("position")[2].get<double>()};
  s.yaw = cam.value("yaw_deg", 0.0f);
  s.pitch = cam.value("pitch_deg", 0.0f);
  s.fov = cam.value("fov_deg", 60.0f);
  return s;
}

// Pixels below the horizon (view ray pointing down by more than half a pixel) left at the clear
// colour: the void behind the world's edge.
int void_pixels(const testing::VoxelGlScene& scene, const Image& img) {
  const float t = std::tan(0.5f * scene.camera.perspective().fov_y);
  const float s = std::sin(scene.camera.pitch()), c = std::cos(scene.camera.pitch());
  int n = 0;
  for (int y = 0; y < img.height(); ++y) {
    // Ray's world y for this row (row 0 is the top); x does not change it without roll.
    const float ndc = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(img.height());
    const float ray_y = s + ndc * t * c;
    if (ray_y > -t / static_cast<float>(img.height()) * 2.0f) continue;
    for (int x = 0; x < img.width(); ++x) n += is_clear(img, x, y) ? 1 : 0;
  }
  return n;
}

TEST_F(VoxelLookGl, ShippedWorldHasAClassicViewDistanceAndNoVoidBelowTheHorizon) {
  const ShippedWorld shipped = read_shipped_world();
  const auto& vox = shipped.json.at("voxel");
  const int radius = vox.at("radius_chunks").get<int>();
  EXPECT_GE(radius, 10) << "fogleman/Craft's default view radius is 10 chunks";
  const glm::dvec2 center(vox.at("center")[0].get<double>(), vox.at("center")[1].get<double>());
  auto w = generate(vox.at("worldgen").at("seed").get<std::uint64_t>(), radius,
                    {static_cast<std::int64_t>(std::floor(center.x / kChunkSize)), 0,
                     static_cast<std::int64_t>(std::floor(center.y / kChunkSize))});
  ASSERT_TRUE(w);
  VoxelRenderSettings settings;
  settings.view_distance = 100000.0f;  // as the scene module: the loaded area's edge
  auto renderer = VoxelRenderer::create(w->world, w->generator, settings);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(240, 136);
  scene.clear_color = kMagenta;
  scene.lighting.sun_direction = render::sun_direction(glm::radians(140.0f), glm::radians(40.0f));
  scene.camera.perspective().fov_y = glm::radians(shipped.fov);
  struct View {
    const char* name;
    glm::dvec3 position;
    float yaw, pitch;
  };
  const View views[] = {
      {"spawn", shipped.position, shipped.yaw, shipped.pitch},
      // High above the spawn, looking at the horizon: past the edge only the skirt is below it.
      {"high", shipped.position + glm::dvec3(0.0, 80.0, 0.0), shipped.yaw + 90.0f, -8.0f},
      {"high_other_way", shipped.position + glm::dvec3(0.0, 80.0, 0.0), shipped.yaw - 90.0f, -3.0f},
  };
  for (const View& v : views) {
    scene.camera.set_position(v.position);
    scene.camera.set_yaw_pitch(glm::radians(v.yaw), glm::radians(v.pitch));
    scene.render(**renderer);
    const Image img = scene.color();
    // The fade ends within the loaded area (its inscribed radius around the camera).
    EXPECT_GT((*renderer)->frame_stats().view_distance, 9.0f * kChunkSize) << v.name;
    EXPECT_LE((*renderer)->frame_stats().view_distance, (radius + 1.0f) * kChunkSize) << v.name;
    const int n = void_pixels(scene, img);
    EXPECT_EQ(n, 0) << v.name << ": pixels below the horizon show the void";
    if (n > 0) testing::save_png(img, std::string("voxel_look_void_") + v.name);
  }
}

TEST_F(VoxelLookGl, PlantCubesDrawnByTheirFacesTowardTheEyeLookTheSame) {
  // Opaque parts always, leaf parts beyond leaf_back_faces_within: 18 instead of 36 vertices.
  auto w = generate(3, 1, {0, 0, 0});
  ASSERT_TRUE(w);
  VoxelRenderSettings all;
  all.leaf_back_faces_within = 1.0e6f;  // every leaf cube with all six faces
  all.plant_far_beyond = 1.0e6f;        // exact plants everywhere (no far shells: voxel_plants_gl)
  all.plant_near_mesh = false;          // instanced cubes (the baked meshes: voxel_plants_gl)
  VoxelRenderSettings near;
  near.plant_far_beyond = 1.0e6f;
  near.plant_near_mesh = false;
  auto full = VoxelRenderer::create(w->world, w->generator, all);
  auto fast = VoxelRenderer::create(w->world, w->generator, near);  // default: within 48 blocks
  ASSERT_TRUE(full.ok() && fast.ok());
  auto scene = testing::VoxelGlScene::create(256, 144);
  scene.camera.set_position({-70.0, 60.0, -70.0});
  scene.camera.look_at({16.0, 25.0, 16.0});
  scene.render(**full);
  const Image a = scene.color();
  const std::uint64_t full_triangles = scene.last_stats.triangles;
  scene.render(**fast);
  const Image b = scene.color();
  const std::uint64_t fast_triangles = scene.last_stats.triangles;
  ASSERT_GT((*fast)->frame_stats().plant_parts_drawn, 1000u);
  EXPECT_LT(static_cast<double>(fast_triangles), 0.75 * static_cast<double>(full_triangles));
  int differ = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x)
      for (int c = 0; c < 3; ++c)
        if (std::abs(a.at(x, y, c) - b.at(x, y, c)) > 2.0f / 255.0f) {
          ++differ;
          break;
        }
  std::printf("%d of %d pixels differ; triangles %llu -> %llu\n", differ, a.width() * a.height(),
              static_cast<unsigned long long>(full_triangles), static_cast<unsigned long long>(fast_triangles));
  // Only far leaf cubes may differ (their back faces seen through holes): measured 2 of 36 864;
  // with the faces turned away instead, 600.
  EXPECT_LE(differ, a.width() * a.height() / 400) << differ << " pixels differ";
}

TEST_F(VoxelLookGl, BadLookSettingsNameTheParameter) {
  World world;
  VoxelRenderSettings s;
  s.bounce = 2.0f;
  auto r = VoxelRenderer::create(world, nullptr, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("voxel.render.bounce"), std::string::npos);
  s = {};
  s.fade_share = 0.0f;
  r = VoxelRenderer::create(world, nullptr, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("voxel.render.fade_share"), std::string::npos);
  s = {};
  s.view_distance = -1.0f;
  r = VoxelRenderer::create(world, nullptr, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("voxel.render.view_distance"), std::string::npos);
  s = {};
  s.sky_light = -1.0f;
  r = VoxelRenderer::create(world, nullptr, s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("voxel.render.sky_light"), std::string::npos);
}

}  // namespace
}  // namespace sylva::voxel
