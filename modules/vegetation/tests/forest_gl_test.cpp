// Forest drawable: per-instance frustum culling (never drops a visible tree, drops the ones behind
// the camera), instanced drawing, placement on a height field, animated seasons, the depth pass.
#include <sylva/vegetation/forest.hpp>

#include <sylva/core/image_metrics.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/vegetation/placement.hpp>

#include "support/gl_scene.hpp"
#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sylva::vegetation {
namespace {

using ForestGl = render::GlTest;

std::vector<TreeInstance> grid(int n, double spacing) {
  std::vector<TreeInstance> out;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      TreeInstance t;
      t.position = {(i - n / 2) * spacing, 0.0, (j - n / 2) * spacing};
      t.yaw = 0.37f * static_cast<float>(i * 7 + j);
      t.scale = 0.9f + 0.02f * static_cast<float>((i + j) % 10);
      t.time_offset = static_cast<float>(i + 3 * j);
      out.push_back(t);
    }
  return out;
}

// LOD0 behaviour (Trees I): the image-based levels are off here; slices_gl_test covers them.
Forest make_forest() {
  ForestSettings settings;
  settings.lod.enabled = false;
  Result<Forest> f = Forest::create(settings);
  EXPECT_TRUE(f.ok()) << f.error().describe();
  Forest forest = std::move(f).value();
  forest.settings().receive_shadows = false;  // these tests bind no shadow maps
  Result<TreeTextureSet> tex = make_texture_set(SpeciesPreset::kBroadleaf, 1, 64, 64);
  EXPECT_TRUE(tex.ok());
  Result<int> s = forest.add_species(testing::preset_tree(SpeciesPreset::kBroadleaf), *tex);
  EXPECT_TRUE(s.ok());
  return forest;
}

TEST_F(ForestGl, CullingKeepsEveryVisibleTreeAndDropsTheOthers) {
  Forest forest = make_forest();
  ASSERT_TRUE(forest.set_instances(0, grid(12, 14.0)).ok());
  auto scene = testing::GlScene::create(128, 96);
  scene.clear_color = {0.6f, 0.75f, 0.95f, 1.0f};
  scene.camera.set_position({0.0, 5.0, 10.0});
  scene.camera.look_at({0.0, 5.0, -50.0});
  const WindField wind;
  const double time = 2.0;
  render::FrameContext frame{scene.camera, time, 0.016f, wind, scene.lighting, {128, 96}, 1};
  Image images[2];
  std::size_t visible[2] = {0, 0};
  for (int culled = 0; culled < 2; ++culled) {
    forest.settings().frustum_culling = culled == 1;
    forest.update(frame);
    visible[culled] = forest.stats().visible;
    scene.begin(time);
    render::PassStats stats;
    forest.draw(render::Pass::kOpaque, frame, stats);
    EXPECT_EQ(stats.draw_calls, 2u);  // one instanced draw for bark, one for leaves
    EXPECT_EQ(stats.instances, visible[culled]);
    images[culled] = scene.read();
  }
  testing::save_png(images[1], "forest_culled");
  EXPECT_EQ(visible[0], 144u);
  EXPECT_LT(visible[1], visible[0] / 2);  // the camera looks at one side of the grid
  EXPECT_GT(visible[1], 10u);
  // Culling never removes a visible tree: the pictures are identical.
  Result<DifferenceCount> diff = count_exceeding(images[0], images[1], 0.0f);
  ASSERT_TRUE(diff.ok());
  EXPECT_EQ(diff->pixels, 0u);
  // Trees behind the camera (z > 10 + radius) are culled; trees straight ahead are kept.
  const std::vector<TreeInstance>& all = forest.instances(0);
  for (std::uint32_t i : forest.visible(0)) EXPECT_LT(all[i].position.z, 10.0 + 12.0) << i;
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (std::fabs(all[i].position.x) < 1.0 && all[i].position.z < -5.0 && all[i].position.z > -80.0) {
      bool kept = false;
      for (std::uint32_t v : forest.visible(0)) kept = kept || v == i;
      EXPECT_TRUE(kept) << "tree straight ahead at z " << all[i].position.z;
    }
  }
}

TEST_F(ForestGl, PlacedOnAHeightFieldAndAnimated) {
  Forest forest = make_forest();
  HeightField ground(65, 65, 2.0, {-64.0, -64.0});
  for (int j = 0; j < 65; ++j)
    for (int i = 0; i < 65; ++i) ground.sample(i, j) = 4.0f * std::sin(0.08f * static_cast<float>(i)) + 0.05f * static_cast<float>(j);
  ground.update_range();
  PlacementSettings ps;
  ps.min_distance = 12.0f;
  Result<std::vector<TreeInstance>> trees = place_poisson_disk(ground, ps);
  ASSERT_TRUE(trees.ok());
  ASSERT_TRUE(forest.set_instances(0, *trees).ok());
  auto scene = testing::GlScene::create(160, 96, 4);
  scene.clear_color = {0.6f, 0.75f, 0.95f, 1.0f};
  scene.camera.set_position({0.0, 14.0, 70.0});
  scene.camera.look_at({0.0, 4.0, 0.0});
  const WindField wind(WindSettings{.strength = 10.0f, .gust_amplitude = 5.0f});
  Image frames[2];
  for (int k = 0; k < 2; ++k) {
    const double time = 5.0 + 0.7 * k;
    render::FrameContext frame{scene.camera, time, 0.7f, wind, scene.lighting, {160, 96}, static_cast<std::uint64_t>(k)};
    forest.update(frame);
    scene.begin(time);
    render::PassStats stats;
    forest.draw(render::Pass::kOpaque, frame, stats);
    EXPECT_GT(stats.triangles, 1000u);
    frames[k] = scene.read();
  }
  testing::save_png(frames[0], "forest_on_ground");
  EXPECT_GT(forest.stats().visible, 10u);
  // The wind moves the crowns between the two frames.
  Result<double> moved = share_exceeding(frames[0], frames[1], 0.08f);
  ASSERT_TRUE(moved.ok());
  EXPECT_GT(*moved, 0.002);
}

TEST_F(ForestGl, SeasonsAnimateWithTime) {
  Forest forest = make_forest();
  ASSERT_TRUE(forest.set_instances(0, grid(1, 0.0)).ok());
  forest.settings().shading.season = 0.5f;
  forest.settings().season_speed = 0.125f;  // an eighth of a year per second
  auto scene = testing::GlScene::create(64, 64);
  scene.camera.set_position({0.0, 6.0, 22.0});
  scene.camera.look_at({0.0, 6.0, 0.0});
  const WindField wind;
  render::FrameContext summer{scene.camera, 0.0, 0.0f, wind, scene.lighting, {64, 64}, 0};
  forest.update(summer);
  EXPECT_FLOAT_EQ(forest.current_season(), 0.5f);
  render::FrameContext winter{scene.camera, 4.4, 0.0f, wind, scene.lighting, {64, 64}, 1};  // season 1.05 -> 0.05
  forest.update(winter);
  EXPECT_NEAR(forest.current_season(), 0.05f, 1e-5f);
  // After 12500 years the season is still exact (wrapped in double).
  render::FrameContext far{scene.camera, 1.0e5 + 4.4, 0.0f, wind, scene.lighting, {64, 64}, 2};
  forest.update(far);
  EXPECT_NEAR(forest.current_season(), 0.05f, 1e-4f);
}

TEST_F(ForestGl, DepthPassCullsForItsOwnFrustum) {
  Forest forest = make_forest();
  ASSERT_TRUE(forest.set_instances(0, grid(6, 15.0)).ok());
  auto scene = testing::GlScene::create(96, 96);
  scene.camera.set_position({0.0, 5.0, 60.0});
  scene.camera.look_at({0.0, 5.0, 0.0});
  const WindField wind;
  render::FrameContext frame{scene.camera, 1.0, 0.0f, wind, scene.lighting, {96, 96}, 0};
  forest.update(frame);
  // A caster's camera from the same origin (matrices are camera-relative), looking down at the
  // grid at another angle: it draws the trees in its own frustum.
  render::Camera light;
  light.set_position({0.0, 5.0, 60.0});
  light.look_at({10.0, -30.0, -10.0});
  light.set_aspect(96, 96);
  scene.begin(1.0);
  render::PassStats stats;
  ASSERT_TRUE(forest.draw_depth(light.view_projection(), stats).ok());
  EXPECT_GT(stats.instances, 0u);
  EXPECT_EQ(stats.draw_calls, 2u);
  const Image depth = render::read_depth(scene.target).value();
  std::size_t written = 0;
  for (float d : depth.data()) written += d > 0.0f ? 1u : 0u;
  EXPECT_GT(written, 50u);
  // Looking away from the grid: nothing to draw, although the view camera sees trees.
  light.look_at({0.0, 5.0, 200.0});
  render::PassStats away;
  ASSERT_TRUE(forest.draw_depth(light.view_projection(), away).ok());
  EXPECT_EQ(away.instances, 0u);
  EXPECT_GT(forest.stats().visible, 0u);
}

TEST_F(ForestGl, BadInstancesAreRejected) {
  Forest forest = make_forest();
  std::vector<TreeInstance> bad(2);
  bad[1].scale = 0.0f;
  const Status s = forest.set_instances(0, bad);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("instance 1"), std::string::npos);
  EXPECT_FALSE(forest.set_instances(3, {}).ok());
}

}  // namespace
}  // namespace sylva::vegetation
