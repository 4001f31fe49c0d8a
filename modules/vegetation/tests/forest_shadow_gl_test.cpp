// Trees in the render core's cascaded shadow maps: they cast through a ShadowCaster calling
// Forest::draw_depth (and through draw(kShadow) inside ShadowMaps::render, the scene's hook, with
// the same result), and their crowns receive the shadows in the opaque pass.
#include <sylva/vegetation/forest.hpp>

#include <sylva/core/wind.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"
#include "support/models.hpp"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdio>

namespace sylva::vegetation {
namespace {

// LOD0 behaviour (Trees I); the image-based levels have their own tests.
ForestSettings lod0_only() {
  ForestSettings s;
  s.lod.enabled = false;
  return s;
}

using ForestShadowGl = render::GlTest;

std::vector<float> read_depth_array(const render::ShadowMaps& maps) {
  const render::Texture& t = maps.depth_array();
  std::vector<float> out(static_cast<std::size_t>(t.width()) * static_cast<std::size_t>(t.height()) *
                         static_cast<std::size_t>(t.layers()));
  glGetTextureImage(t.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
  return out;
}

TEST_F(ForestShadowGl, TreesCastIntoTheCascades) {
  Forest forest = Forest::create(lod0_only()).value();
  const Result<TreeTextureSet> tex = make_texture_set(SpeciesPreset::kBroadleaf, 1, 64, 64);
  ASSERT_TRUE(forest.add_species(testing::preset_tree(SpeciesPreset::kBroadleaf), *tex).ok());
  TreeInstance a;
  TreeInstance b;
  b.position = {6.0, 0.0, -7.0};
  ASSERT_TRUE(forest.set_instances(0, {a, b}).ok());

  auto scene = testing::GlScene::create(128, 96);
  scene.clear_color = {0.6f, 0.75f, 0.95f, 1.0f};
  scene.lighting.sun_direction = glm::normalize(glm::vec3(0.5f, 0.7f, -0.4f));
  scene.camera.set_position({2.0, 6.0, 22.0});
  scene.camera.look_at({2.0, 5.0, -3.0});
  const WindField wind;
  render::FrameContext frame{scene.camera, 1.0, 0.016f, wind, scene.lighting, {128, 96}, 0};
  forest.update(frame);

  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.resolution = 512;
  ss.max_distance = 60.0f;
  Result<render::ShadowMaps> maps = render::ShadowMaps::create(ss);
  ASSERT_TRUE(maps.ok()) << maps.error().describe();
  render::CallbackShadowCaster caster([&](const render::ShadowCasterContext& c) {
    EXPECT_TRUE(forest.draw_depth(c.relative_view_projection, c.light_frustum, *c.stats).ok());
  });
  maps->add_caster(&caster);
  render::PassStats shadow_stats;
  ASSERT_TRUE(maps->render(scene.camera, scene.lighting.sun_direction, &frame, &shadow_stats).ok());
  const std::vector<float> cast = read_depth_array(*maps);
  std::size_t texels = 0;
  for (float d : cast) texels += d > 0.0f ? 1u : 0u;
  EXPECT_GT(texels, 1000u);
  EXPECT_GE(shadow_stats.draw_calls, 4u);  // bark + leaves per cascade

  // The scene's hook: draw(kShadow) inside ShadowMaps::render writes the same depth.
  Result<render::ShadowMaps> maps2 = render::ShadowMaps::create(ss);
  ASSERT_TRUE(maps2.ok());
  render::CallbackShadowCaster hook([&](const render::ShadowCasterContext& c) { forest.draw(render::Pass::kShadow, frame, *c.stats); });
  maps2->add_caster(&hook);
  ASSERT_TRUE(maps2->render(scene.camera, scene.lighting.sun_direction, &frame, nullptr).ok());
  EXPECT_EQ(read_depth_array(*maps2), cast);
  // Outside ShadowMaps::render, draw(kShadow) draws nothing.
  render::PassStats none;
  forest.draw(render::Pass::kShadow, frame, none);
  EXPECT_EQ(none.draw_calls, 0u);

  maps->remove_caster(&caster);
  maps2->remove_caster(&hook);
}

// Leaf A faces the sun; leaf B stands between them. With the maps bound A loses its direct sun
// (ambient stays); without them it is lit. The camera looks at A from the side, clear of B.
TEST_F(ForestShadowGl, LeavesReceiveTheShadowOfOtherLeaves) {
  Forest forest = Forest::create(lod0_only()).value();
  const Result<TreeTextureSet> tex = make_texture_set(SpeciesPreset::kBroadleaf, 1, 64, 64);
  ASSERT_TRUE(forest.add_species(testing::single_leaf(), *tex).ok());
  forest.settings().shading.specular_color = glm::vec3(0.0f);
  TreeInstance a;
  TreeInstance b;
  b.position = {0.0, 0.3, 1.5};
  auto scene = testing::GlScene::create(96, 96);
  scene.clear_color = {0.0f, 0.0f, 0.0f, 1.0f};
  scene.lighting.sun_direction = glm::normalize(glm::vec3(0.0f, 0.25f, 1.0f));
  scene.camera.set_position({3.0, 1.3, 1.0});
  scene.camera.look_at({0.0, 1.2, 0.0});
  const WindField calm(WindSettings{.strength = 0.0f, .gust_amplitude = 0.0f, .turbulence_amplitude = 0.0f});
  render::FrameContext frame{scene.camera, 0.0, 0.0f, calm, scene.lighting, {96, 96}, 0};

  // A's pixels: A alone, unshadowed.
  ASSERT_TRUE(forest.set_instances(0, {a}).ok());
  forest.settings().receive_shadows = false;
  forest.update(frame);
  scene.begin();
  render::PassStats stats;
  forest.draw(render::Pass::kOpaque, frame, stats);
  const Image alone = scene.read();

  ASSERT_TRUE(forest.set_instances(0, {a, b}).ok());
  forest.update(frame);
  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.resolution = 512;
  ss.max_distance = 20.0f;
  Result<render::ShadowMaps> maps = render::ShadowMaps::create(ss);
  ASSERT_TRUE(maps.ok());
  render::CallbackShadowCaster caster([&](const render::ShadowCasterContext& c) {
    EXPECT_TRUE(forest.draw_depth(c.relative_view_projection, c.light_frustum, *c.stats).ok());
  });
  maps->add_caster(&caster);
  ASSERT_TRUE(maps->render(scene.camera, scene.lighting.sun_direction, &frame, nullptr).ok());
  Image shaded[2];
  for (int k = 0; k < 2; ++k) {
    forest.settings().receive_shadows = k == 0;
    scene.begin();
    maps->bind();
    forest.draw(render::Pass::kOpaque, frame, stats);
    shaded[k] = scene.read();
  }
  testing::save_png(shaded[0], "leaf_in_shadow");
  testing::save_png(shaded[1], "leaf_not_in_shadow");
  double with = 0.0;
  double without = 0.0;
  std::size_t pixels = 0;
  for (int y = 0; y < alone.height(); ++y)
    for (int x = 0; x < alone.width(); ++x) {
      if (alone.at(x, y, 0) + alone.at(x, y, 1) + alone.at(x, y, 2) <= 0.0f) continue;
      ++pixels;
      with += shaded[0].at(x, y, 1);
      without += shaded[1].at(x, y, 1);
    }
  ASSERT_GT(pixels, 100u);
  std::printf("leaf A, mean green with shadows %.4f, without %.4f (%zu px)\n", with / pixels, without / pixels, pixels);
  EXPECT_LT(with, 0.6 * without);
  maps->remove_caster(&caster);
}

}  // namespace
}  // namespace sylva::vegetation
