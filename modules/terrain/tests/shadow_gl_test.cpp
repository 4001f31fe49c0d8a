// Terrain in the render core's cascaded shadow maps (render/README.md "Lighting and shadows"): a
// ridge casts through draw(Pass::kShadow) inside ShadowMaps::render (the scene's hook) and the
// valley floor receives through shadows.glsl. A low sun from the west puts the lee side of a
// 45 m ridge in shadow for about 90 m; further east the floor is lit.
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/terrain/renderer.hpp>

#include "support/gl_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sylva::terrain {
namespace {

using namespace testing;
using TerrainShadowGl = render::GlTest;

constexpr int kW = 192, kH = 128;

// 129 x 129 samples, 2 m apart; a north-south ridge (45 m, centred at x = 60 m) on flat ground.
HeightField ridge_field() {
  HeightField f(129, 129, 2.0);
  for (int j = 0; j < f.rows(); ++j)
    for (int i = 0; i < f.columns(); ++i) {
      const double x = i * 2.0;
      f.sample(i, j) = static_cast<float>(45.0 * std::exp(-((x - 60.0) / 8.0) * ((x - 60.0) / 8.0)));
    }
  f.update_range();
  return f;
}

struct ShadowRun {
  Image image;
  render::PassStats shadow_stats;
};

// One frame as the scene draws it: update, the shadow pass through the caster hook, bind the
// maps, the opaque pass.
ShadowRun render_frame(TerrainRenderer& terrain, GlTarget& target, render::ShadowMaps& maps, const render::Camera& cam) {
  ShadowRun run;
  render::FrameContext ctx{cam, 0.0, 0.0f, target.wind, target.lighting, target.size(), 0};
  terrain.update(ctx);
  render::CallbackShadowCaster hook([&](const render::ShadowCasterContext& c) { terrain.draw(render::Pass::kShadow, ctx, *c.stats); });
  maps.add_caster(&hook);
  EXPECT_TRUE(maps.render(cam, target.lighting.sun_direction, &ctx, &run.shadow_stats).ok());
  maps.remove_caster(&hook);
  target.target.bind();
  render::apply_reversed_z_state();
  target.target.clear(glm::vec4(0.5f, 0.6f, 0.8f, 1.0f), 0.0f);
  target.lighting_ubo.update(target.lighting, cam.position().y, 0.0);
  target.lighting_ubo.bind();
  maps.bind();
  render::PassStats stats;
  terrain.draw(render::Pass::kOpaque, ctx, stats);
  run.image = render::read_color(target.target).value();
  return run;
}

// Mean green of the pixels showing ground points with x in [x0, x1] (z in [70, 186] m).
double mean_green(const Image& im, const render::Camera& cam, double x0, double x1, int* count) {
  const glm::mat4 vp = cam.view_projection();
  double sum = 0.0;
  int n = 0;
  for (double x = x0; x <= x1; x += 2.0)
    for (double z = 70.0; z <= 186.0; z += 2.0) {
      const glm::vec4 clip = vp * glm::vec4(cam.to_relative({x, 0.0, z}), 1.0f);
      if (clip.w <= 0.0f) continue;
      const int px = static_cast<int>((clip.x / clip.w * 0.5f + 0.5f) * kW);
      const int py = static_cast<int>((0.5f - clip.y / clip.w * 0.5f) * kH);
      if (px < 1 || py < 1 || px >= kW - 1 || py >= kH - 1) continue;
      sum += im.at(px, py, 1);
      ++n;
    }
  *count = n;
  return n > 0 ? sum / n : 0.0;
}

// 60 degrees vertical, kW x kH, at `eye` looking at `target` (world metres).
render::Camera camera_looking(const glm::dvec3& eye, const glm::dvec3& target) {
  render::Camera cam;
  cam.perspective().fov_y = glm::radians(60.0f);
  cam.perspective().near_plane = 0.5f;
  cam.perspective().far_plane = 0.0f;
  cam.set_aspect(kW, kH);
  cam.set_position(eye);
  cam.look_at(target);
  return cam;
}

void expect_ridge_shadow(const render::Camera& cam, const char* name) {
  const HeightField field = ridge_field();
  ChunkTreeSettings ts;
  ts.leaf_dimension = 17;
  auto tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(field, ts)).value());
  TerrainRenderSettings rs;
  rs.material.detail_strength = 0.0f;  // a uniform floor: only light changes the colour
  auto created = TerrainRenderer::create(tree, &field, rs);
  ASSERT_TRUE(created.ok()) << created.error().describe();
  TerrainRenderer& terrain = **created;
  GlTarget target = GlTarget::create(kW, kH);
  target.lighting.sun_direction = glm::normalize(glm::vec3(-1.0f, 0.5f, 0.0f));  // low sun in the west
  target.lighting.sun_intensity = 1.0f;
  target.lighting.ambient = glm::vec3(0.15f);
  target.lighting.fog_density = 0.0f;
  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.resolution = 1024;
  ss.max_distance = 400.0f;
  Result<render::ShadowMaps> maps = render::ShadowMaps::create(ss);
  ASSERT_TRUE(maps.ok()) << maps.error().describe();

  const ShadowRun shadowed = render_frame(terrain, target, *maps, cam);
  EXPECT_GT(shadowed.shadow_stats.draw_calls, 0u) << "the terrain drew into the cascades";
  EXPECT_TRUE(terrain.shadows_received());
  EXPECT_EQ(terrain.frame_stats().beyond_shadow_chunks, 0u) << "every chunk lies inside the cascades";
  // The host's shadows off (no caster runs): the terrain draws without the receiving code (issue
  // 18: llvmpipe ran its cascade loop and taps for every pixel anyway), the same picture as
  // receive_shadows off.
  maps->settings().enabled = false;
  const ShadowRun host_off = render_frame(terrain, target, *maps, cam);
  EXPECT_FALSE(terrain.shadows_received());
  maps->settings().enabled = true;
  terrain.settings().receive_shadows = false;
  const ShadowRun unshadowed = render_frame(terrain, target, *maps, cam);
  terrain.settings().receive_shadows = true;
  terrain.settings().cast_shadows = false;
  const ShadowRun no_caster = render_frame(terrain, target, *maps, cam);
  EXPECT_EQ(no_caster.shadow_stats.draw_calls, 0u);
  EXPECT_TRUE(std::ranges::equal(host_off.image.data(), unshadowed.image.data())) << "host shadows off = receive_shadows off";
  save_png(shadowed.image, std::string(name) + "_shadowed");
  save_png(unshadowed.image, std::string(name) + "_unshadowed");

  // Lee side in shadow: x in [100, 140] (the shadow reaches x = 150); lit floor x in [175, 240].
  int n_shadow = 0, n_lit = 0, n = 0;
  const double shade_with = mean_green(shadowed.image, cam, 104.0, 140.0, &n_shadow);
  const double shade_without = mean_green(unshadowed.image, cam, 104.0, 140.0, &n);
  const double shade_no_caster = mean_green(no_caster.image, cam, 104.0, 140.0, &n);
  const double lit_with = mean_green(shadowed.image, cam, 175.0, 240.0, &n_lit);
  const double lit_without = mean_green(unshadowed.image, cam, 175.0, 240.0, &n);
  std::printf("%s: shadow band %.4f (unshadowed %.4f, no caster %.4f, %d px); lit band %.4f (unshadowed %.4f, %d px)\n",
              name, shade_with, shade_without, shade_no_caster, n_shadow, lit_with, lit_without, n_lit);
  ASSERT_GT(n_shadow, 50);
  ASSERT_GT(n_lit, 50);
  EXPECT_LT(shade_with, 0.6 * shade_without) << "the valley behind the ridge is in shadow";
  EXPECT_GT(lit_with, 0.93 * lit_without) << "the open floor stays lit (no acne)";
  EXPECT_GT(shade_no_caster, 0.93 * shade_without) << "the shadow comes from the terrain casting";
}

TEST_F(TerrainShadowGl, RidgeShadowsTheValleyWithALowSun) {
  const render::Camera cam = camera_looking({250.0, 170.0, 128.0}, {120.0, 0.0, 128.0});
  expect_ridge_shadow(cam, "ridge_in_view");
}

// The ridge is behind the camera (outside its frustum) and still casts into view: casters are
// selected without the camera frustum and culled per cascade with the light frustum.
TEST_F(TerrainShadowGl, AnOffScreenRidgeStillCastsIntoView) {
  const render::Camera cam = camera_looking({96.0, 60.0, 128.0}, {176.0, 0.0, 128.0});
  expect_ridge_shadow(cam, "ridge_behind_camera");
}

// Issue 18: chunks outside every cascade's shadow map (by the receiver's normal offset and PCF
// reach) are drawn without the receiving code, since sylva_shadow is 1 on all of their pixels.
// A 4 km field seen over 600 m of cascades: the far chunks go without it, the near ones keep it
// (the lee of a ridge near the camera is still shadowed), and the picture of the far ground
// equals receive_shadows off.
TEST_F(TerrainShadowGl, ChunksBeyondEveryShadowMapSkipTheReceivingCode) {
  HeightField field(257, 257, 16.0);
  for (int j = 0; j < field.rows(); ++j)
    for (int i = 0; i < field.columns(); ++i) {
      const double x = i * 16.0, ridge = (x - 500.0) / 24.0;  // a 60 m ridge 400 m ahead of the camera
      field.sample(i, j) = static_cast<float>(40.0 * std::sin(i * 0.07) * std::cos(j * 0.05) + 0.03 * x +
                                              60.0 * std::exp(-ridge * ridge));
    }
  field.update_range();
  ChunkTreeSettings ts;
  ts.leaf_dimension = 17;
  auto tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(field, ts)).value());
  auto created = TerrainRenderer::create(tree, &field, {});
  ASSERT_TRUE(created.ok()) << created.error().describe();
  TerrainRenderer& terrain = **created;
  GlTarget target = GlTarget::create(kW, kH);
  target.lighting.sun_direction = glm::normalize(glm::vec3(-1.0f, 0.5f, 0.2f));
  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.max_distance = 600.0f;
  Result<render::ShadowMaps> maps = render::ShadowMaps::create(ss);
  ASSERT_TRUE(maps.ok()) << maps.error().describe();
  const render::Camera cam = camera_looking({100.0, 160.0, 2000.0}, {3000.0, 0.0, 2000.0});
  const ShadowRun shadowed = render_frame(terrain, target, *maps, cam);
  ASSERT_TRUE(terrain.shadows_received());
  const TerrainFrameStats stats = terrain.frame_stats();
  std::printf("%u of %u chunks beyond the shadow maps\n", stats.beyond_shadow_chunks, stats.selection.chunks);
  EXPECT_GT(stats.beyond_shadow_chunks, 0u);
  EXPECT_LT(stats.beyond_shadow_chunks, stats.selection.chunks) << "the near chunks keep their shadows";
  terrain.settings().receive_shadows = false;
  const ShadowRun unshadowed = render_frame(terrain, target, *maps, cam);
  // The upper third of the picture is far ground (beyond 600 m) or sky: the same either way.
  for (int y = 0; y < kH / 3; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(shadowed.image.at(x, y, c), unshadowed.image.at(x, y, c)) << x << "," << y;
  save_png(shadowed.image, "beyond_shadow_maps_shadowed");
  save_png(unshadowed.image, "beyond_shadow_maps_unshadowed");
  std::size_t near_shadowed = 0;
  for (int y = kH / 2; y < kH; ++y)
    for (int x = 0; x < kW; ++x) near_shadowed += shadowed.image.at(x, y, 1) < unshadowed.image.at(x, y, 1) - 0.02f;
  EXPECT_GT(near_shadowed, 20u) << "the near ground still receives its shadows";
}

}  // namespace
}  // namespace sylva::terrain
