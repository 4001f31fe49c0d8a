// Forest stability on the GPU. Invariants named per test: no jitter far from the world origin
// (camera-relative instances), hurricane wind and huge times render finite, bounded pictures, an
// empty forest and frames with dt = 0 or 1 s are harmless.
#include <sylva/vegetation/forest.hpp>

#include <sylva/core/image_metrics.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"
#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::vegetation {
namespace {

// LOD0 behaviour (Trees I); the image-based levels have their own tests.
ForestSettings lod0_only() {
  ForestSettings s;
  s.lod.enabled = false;
  return s;
}

using ForestStability = render::GlTest;

Forest small_forest(const glm::dvec3& offset) {
  Forest forest = Forest::create(lod0_only()).value();
  forest.settings().receive_shadows = false;  // no shadow maps bound here
  const Result<TreeTextureSet> tex = make_texture_set(SpeciesPreset::kShrub, 1, 64, 64);
  EXPECT_TRUE(forest.add_species(testing::preset_tree(SpeciesPreset::kShrub), *tex).ok());
  std::vector<TreeInstance> trees;
  for (int i = 0; i < 9; ++i) {
    TreeInstance t;
    t.position = offset + glm::dvec3((i % 3) * 4.0 - 4.0, 0.0, -(i / 3) * 4.0);
    t.yaw = 0.5f * static_cast<float>(i);
    trees.push_back(t);
  }
  EXPECT_TRUE(forest.set_instances(0, trees).ok());
  return forest;
}

Image render(Forest& forest, testing::GlScene& scene, const WindField& wind, double time, float dt) {
  render::FrameContext frame{scene.camera, time, dt, wind, scene.lighting, scene.target.size(), 0};
  forest.update(frame);
  scene.begin(time);
  render::PassStats stats;
  forest.draw(render::Pass::kOpaque, frame, stats);
  return scene.read();
}

bool finite_image(const Image& img) { return find_non_finite(img).count == 0; }

// Invariant: a forest 1e6 m from the origin renders like the same forest at the origin (vertex
// positions are camera-relative, so they do not jitter or shift).
TEST_F(ForestStability, FarFromTheOriginLooksTheSame) {
  const WindField calm(WindSettings{.strength = 0.0f, .gust_amplitude = 0.0f, .turbulence_amplitude = 0.0f});
  Image pictures[2];
  const glm::dvec3 offsets[2] = {glm::dvec3(0.0), glm::dvec3(1.0e6, 250.0, -3.0e6)};
  for (int k = 0; k < 2; ++k) {
    Forest forest = small_forest(offsets[k]);
    auto scene = testing::GlScene::create(96, 64);
    scene.camera.set_position(offsets[k] + glm::dvec3(0.0, 2.0, 8.0));
    scene.camera.look_at(offsets[k] + glm::dvec3(0.0, 1.0, -4.0));
    pictures[k] = render(forest, scene, calm, 10.0, 0.016f);
  }
  const DifferenceCount diff = count_exceeding(pictures[0], pictures[1], 2.0f / 255.0f).value();
  EXPECT_LT(diff.share, 0.002) << diff.pixels << " pixels differ";
}

// Invariant: hurricane wind (x100) at long and huge times gives finite pictures with the trees in
// them (the bend saturates, nothing explodes), for dt = 0 and dt = 1 s.
TEST_F(ForestStability, HurricaneAndHugeTimesRenderFinitePictures) {
  Forest forest = small_forest(glm::dvec3(0.0));
  forest.settings().animation.wind_scale = 100.0f;
  const WindField hurricane(WindSettings{.strength = 100.0f, .gust_amplitude = 100.0f, .turbulence_amplitude = 100.0f,
                                         .turbulence_scale = 0.05f});
  auto scene = testing::GlScene::create(96, 64, 0, GL_RGBA32F);  // float: NaN stays NaN
  scene.camera.set_position({0.0, 2.0, 9.0});
  scene.camera.look_at({0.0, 1.0, -4.0});
  for (double t : {0.0, 1.0, 2.0, 1.0e7, 1.0e9}) {
    for (float dt : {0.0f, 1.0f}) {
      const Image img = render(forest, scene, hurricane, t, dt);
      ASSERT_TRUE(finite_image(img)) << "t " << t;
      const Image mask = mask_from_background(img, scene.clear_color, 0.02f).value();
      double covered = 0.0;
      for (float v : mask.data()) covered += v;
      EXPECT_GT(covered, 100.0) << "t " << t;
    }
  }
}

// Invariant: an empty forest, a species without instances and a forest drawn before its first
// update do nothing and raise no GL error.
TEST_F(ForestStability, EmptyForestsAreHarmless) {
  Forest forest = Forest::create(lod0_only()).value();
  forest.settings().receive_shadows = false;
  auto scene = testing::GlScene::create(32, 32);
  const WindField wind;
  render::FrameContext frame{scene.camera, 0.0, 0.0f, wind, scene.lighting, {32, 32}, 0};
  render::PassStats stats;
  forest.draw(render::Pass::kOpaque, frame, stats);
  forest.update(frame);
  forest.draw(render::Pass::kOpaque, frame, stats);
  forest.draw(render::Pass::kShadow, frame, stats);
  forest.draw(render::Pass::kTransparent, frame, stats);
  EXPECT_EQ(stats.draw_calls, 0u);
  Forest one = small_forest(glm::dvec3(0.0));
  ASSERT_TRUE(one.set_instances(0, {}).ok());
  one.update(frame);
  one.draw(render::Pass::kOpaque, frame, stats);
  EXPECT_EQ(stats.draw_calls, 0u);
  EXPECT_TRUE(one.draw_depth(scene.camera.view_projection(), stats).ok());
}

}  // namespace
}  // namespace sylva::vegetation
