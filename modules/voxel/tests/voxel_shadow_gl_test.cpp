// Voxel chunks and plants in the render core's cascaded shadow maps (seed 004 §3, Lighting
// issue): a pillar shadows the ground under a low sun exactly where the analytic shadow falls
// (and nowhere else: no acne on the lit ground), alpha-cut leaves cast cut-out shadows (opaque
// stone does not, and neither do leaves without the alpha test), plants cast, and the scene's
// two caster paths (draw(kShadow) and draw_depth) cast each cascade once.

#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/voxel/voxel_renderer.hpp>
#include <sylva/voxel/worldgen.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "support/voxel_gl_scene.hpp"

namespace sylva::voxel {
namespace {

using VoxelShadowGl = render::GlTest;

// Flat stone ground: blocks y = 0, top surface at y = 1, x and z in [-16, 32).
void add_ground(World& w) {
  const BlockId stone = w.palette().id("stone");
  for (int z = -16; z < 32; ++z)
    for (int x = -16; x < 32; ++x) (void)w.set({x, 0, z}, stone);
}

void remesh(World& w) {
  auto mesher = make_mesher(MesherKind::kBitmask);
  (void)w.remesh(*mesher);
}

std::vector<float> read_depth_array(const render::ShadowMaps& maps) {
  const render::Texture& t = maps.depth_array();
  std::vector<float> out(static_cast<std::size_t>(t.width()) * static_cast<std::size_t>(t.height()) *
                         static_cast<std::size_t>(t.layers()));
  glGetTextureImage(t.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(out.size() * sizeof(float)), out.data());
  return out;
}

std::size_t written_texels(const render::ShadowMaps& maps) {
  std::size_t n = 0;
  for (float d : read_depth_array(maps)) n += d > 0.0f ? 1u : 0u;
  return n;
}

// Renders the maps for the scene's camera and sun with the renderer as the only caster.
render::ShadowMaps cast(VoxelRenderer& r, testing::VoxelGlScene& scene, const render::ShadowSettings& ss) {
  Result<render::ShadowMaps> maps = render::ShadowMaps::create(ss);
  EXPECT_TRUE(maps.ok()) << maps.error().describe();
  const render::FrameContext frame{scene.camera, 0.0, 0.0f, scene.wind, scene.lighting, scene.target.size(), 0};
  r.update(frame);
  render::apply_reversed_z_state();
  maps->add_caster(&r.shadow_caster());
  render::PassStats stats;
  EXPECT_TRUE(maps->render(scene.camera, scene.lighting.sun_direction, &frame, &stats).ok());
  maps->remove_caster(&r.shadow_caster());
  EXPECT_GT(stats.draw_calls, 0u);
  return std::move(*maps);
}

// Colour images with and without receiving the maps.
struct ShadowPair {
  Image shadowed;
  Image lit;
};
ShadowPair render_pair(VoxelRenderer& r, testing::VoxelGlScene& scene, const render::ShadowMaps& maps) {
  ShadowPair out;
  maps.bind();
  r.settings().receive_shadows = true;
  scene.render(r);
  out.shadowed = scene.color();
  r.settings().receive_shadows = false;
  scene.render(r);
  out.lit = scene.color();
  r.settings().receive_shadows = true;
  return out;
}

// Brightness ratio shadowed / lit at the pixel showing world point p (-1 when off screen).
double ratio_at(const ShadowPair& img, const render::Camera& camera, const glm::dvec3& p) {
  const glm::vec4 clip = camera.view_projection() * glm::vec4(camera.to_relative(p), 1.0f);
  if (clip.w <= 0.0f) return -1.0;
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  const int x = static_cast<int>(std::floor((ndc.x * 0.5f + 0.5f) * static_cast<float>(img.lit.width())));
  const int y = static_cast<int>(std::floor((0.5f - ndc.y * 0.5f) * static_cast<float>(img.lit.height())));
  if (x < 0 || y < 0 || x >= img.lit.width() || y >= img.lit.height()) return -1.0;
  double a = 0.0, b = 0.0;
  for (int c = 0; c < 3; ++c) {
    a += img.shadowed.at(x, y, c);
    b += img.lit.at(x, y, c);
  }
  return b > 1e-4 ? a / b : -1.0;
}

TEST_F(VoxelShadowGl, PillarShadowsTheGroundUnderALowSun) {
  World world;
  add_ground(world);
  const BlockId stone = world.palette().id("stone");
  // A 2 x 10 x 2 pillar on the ground: x, z in [20, 22), top at y = 11 (10 above the ground).
  for (int y = 1; y <= 10; ++y)
    for (int z = 20; z < 22; ++z)
      for (int x = 20; x < 22; ++x) (void)world.set({x, y, z}, stone);
  remesh(world);
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(256, 160);
  // Sun 25 degrees above the +x horizon: the shadow runs 10 / tan 25 = 21.4 blocks toward -x.
  const double elevation = 25.0 * 3.14159265358979 / 180.0;
  scene.lighting.sun_direction = glm::normalize(glm::vec3(static_cast<float>(std::cos(elevation)),
                                                          static_cast<float>(std::sin(elevation)), 0.0f));
  scene.camera.set_position({10.0, 38.0, 44.0});
  scene.camera.look_at({10.0, 1.0, 21.0});
  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.resolution = 1024;
  ss.max_distance = 100.0f;
  const render::ShadowMaps maps = cast(**renderer, scene, ss);
  const ShadowPair img = render_pair(**renderer, scene, maps);
  testing::save_png(img.shadowed, "voxel_pillar_shadow");

  const double reach = 10.0 / std::tan(elevation);
  int inside = 0, inside_dark = 0, outside = 0, outside_lit = 0;
  for (double x = 21.0 - reach + 2.0; x <= 19.0; x += 0.5) {
    for (double z = 20.3; z <= 21.7; z += 0.35) {
      const double r = ratio_at(img, scene.camera, {x, 1.0, z});
      if (r < 0.0) continue;
      ++inside;
      inside_dark += r < 0.6 ? 1 : 0;
    }
    for (double z : {16.0, 17.5, 24.5, 26.0}) {  // beside the shadow strip
      const double r = ratio_at(img, scene.camera, {x, 1.0, z});
      if (r < 0.0) continue;
      ++outside;
      outside_lit += r > 0.97 ? 1 : 0;
    }
  }
  for (double x = 23.5; x <= 30.0; x += 0.5) {  // sunward of the pillar
    const double r = ratio_at(img, scene.camera, {x, 1.0, 21.0});
    if (r < 0.0) continue;
    ++outside;
    outside_lit += r > 0.97 ? 1 : 0;
  }
  std::printf("pillar: %d/%d inside samples shadowed, %d/%d outside samples lit\n", inside_dark, inside, outside_lit,
              outside);
  ASSERT_GT(inside, 100);
  ASSERT_GT(outside, 80);
  EXPECT_GE(inside_dark, inside * 99 / 100);
  EXPECT_GE(outside_lit, outside * 99 / 100);
}

TEST_F(VoxelShadowGl, AlphaCutLeavesCastCutOutShadowsAndPlantsCast) {
  World world;
  add_ground(world);
  const BlockId leaves = world.palette().id("oak_leaves");
  const BlockId stone = world.palette().id("stone");
  // Two 6 x 1 x 6 slabs at y = 6 under a vertical sun: leaves over z in [0, 6), stone over
  // z in [10, 16); the camera looks under them from the side, below their height.
  for (int z = 0; z < 6; ++z)
    for (int x = 0; x < 6; ++x) {
      (void)world.set({x, 6, z}, leaves);
      (void)world.set({x, 6, z + 10}, stone);
    }
  remesh(world);
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(256, 160);
  scene.lighting.sun_direction = glm::vec3(0.0f, 1.0f, 0.0f);
  scene.camera.set_position({-7.0, 3.0, 8.0});
  scene.camera.look_at({3.0, 1.0, 8.0});
  render::ShadowSettings ss;
  ss.cascade_count = 1;
  ss.resolution = 2048;
  ss.max_distance = 30.0f;
  ss.pcf_radius = 0;  // resolve the leaves' one-texel holes

  struct Counts {
    int samples = 0, dark = 0, lit = 0;
  };
  auto measure = [&](const ShadowPair& img, double z0) {
    Counts c;
    for (double z = z0 + 1.0; z <= z0 + 5.0; z += 0.1)
      for (double x = 1.0; x <= 5.0; x += 0.1) {
        const double r = ratio_at(img, scene.camera, {x, 1.0, z});
        if (r < 0.0) continue;
        ++c.samples;
        c.dark += r < 0.5 ? 1 : 0;
        c.lit += r > 0.85 ? 1 : 0;
      }
    return c;
  };
  const render::ShadowMaps maps = cast(**renderer, scene, ss);
  const ShadowPair img = render_pair(**renderer, scene, maps);
  testing::save_png(img.shadowed, "voxel_leaves_shadow");
  const Counts leaf = measure(img, 0.0), solid = measure(img, 10.0);
  // Without the alpha test (cut-off 0) the same leaves cast a solid shadow.
  (*renderer)->settings().alpha_cutoff = 0.0f;
  const render::ShadowMaps uncut_maps = cast(**renderer, scene, ss);
  const Counts uncut = measure(render_pair(**renderer, scene, uncut_maps), 0.0);
  std::printf("leaves: %d dark %d lit of %d; stone: %d dark of %d; uncut leaves: %d lit of %d\n", leaf.dark, leaf.lit,
              leaf.samples, solid.dark, solid.samples, uncut.lit, uncut.samples);
  ASSERT_GT(leaf.samples, 400);
  ASSERT_GT(solid.samples, 400);
  // Oak leaves have 18 % holes (block_textures.cpp): most of the ground is dark, some lit.
  EXPECT_GT(leaf.dark, leaf.samples / 2);
  EXPECT_GT(leaf.lit, leaf.samples / 20);
  EXPECT_LT(leaf.lit, leaf.samples * 2 / 5);
  EXPECT_GE(solid.dark, solid.samples * 99 / 100);
  EXPECT_LT(uncut.lit, uncut.samples / 100);
  (*renderer)->settings().alpha_cutoff = VoxelRenderSettings{}.alpha_cutoff;

  // Seed 004 R1, the shadow pass's shaders: alpha-testing every caster casts the same cut-out
  // shadow as the split; the empty shader for every caster (early-z) casts the leaves solid.
  (*renderer)->settings().shadow_shaders = ShadowPassShaders::kAlphaTested;
  const render::ShadowMaps tested_maps = cast(**renderer, scene, ss);
  const Counts tested = measure(render_pair(**renderer, scene, tested_maps), 0.0);
  (*renderer)->settings().shadow_shaders = ShadowPassShaders::kEarlyZ;
  const render::ShadowMaps early_maps = cast(**renderer, scene, ss);
  const ShadowPair early_img = render_pair(**renderer, scene, early_maps);
  const Counts early = measure(early_img, 0.0), early_stone = measure(early_img, 10.0);
  (*renderer)->settings().shadow_shaders = ShadowPassShaders::kSplit;
  std::printf("alpha-tested leaves: %d lit of %d; early-z leaves: %d lit of %d\n", tested.lit, tested.samples, early.lit,
              early.samples);
  EXPECT_EQ(tested.lit, leaf.lit);
  EXPECT_EQ(tested.dark, leaf.dark);
  EXPECT_LT(early.lit, early.samples / 100);
  EXPECT_GE(early_stone.dark, early_stone.samples * 99 / 100);

  // Plants cast: one acacia on the ground adds shadow-map texels; cast_shadows off casts nothing.
  WorldGenSettings gs;
  gs.variants_per_species = 1;
  auto gen = WorldGenerator::create(gs);
  ASSERT_TRUE(gen.ok()) << gen.error().message;
  World planted;
  add_ground(planted);
  remesh(planted);
  auto with_plants = VoxelRenderer::create(planted, *gen);
  ASSERT_TRUE(with_plants.ok());
  scene.lighting.sun_direction = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  scene.camera.set_position({-4.0, 12.0, -4.0});
  scene.camera.look_at({8.0, 1.0, 8.0});
  ss.pcf_radius = 1;
  ss.resolution = 512;
  const std::vector<float> bare = read_depth_array(cast(**with_plants, scene, ss));
  planted.set_plants({0, 0, 0}, {PlantInstance{*(*gen)->species().find("acacia"), 0, 0, BlockPos{8, 0, 8}}});
  const std::vector<float> tree = read_depth_array(cast(**with_plants, scene, ss));
  ASSERT_EQ(bare.size(), tree.size());
  std::size_t raised = 0, lowered = 0;  // texels nearer to / farther from the sun with the tree
  for (std::size_t i = 0; i < bare.size(); ++i) {
    raised += tree[i] > bare[i] + 1e-5f ? 1u : 0u;
    lowered += tree[i] < bare[i] - 1e-5f ? 1u : 0u;
  }
  (*with_plants)->settings().cast_shadows = false;
  Result<render::ShadowMaps> off = render::ShadowMaps::create(ss);
  ASSERT_TRUE(off.ok());
  off->add_caster(&(*with_plants)->shadow_caster());
  ASSERT_TRUE(off->render(scene.camera, scene.lighting.sun_direction, nullptr, nullptr).ok());
  off->remove_caster(&(*with_plants)->shadow_caster());
  std::printf("acacia: %zu shadow texels nearer the sun, %zu farther; cast_shadows off: %zu texels written\n", raised,
              lowered, written_texels(*off));
  EXPECT_GT(raised, 200u);
  EXPECT_EQ(lowered, 0u);
  EXPECT_EQ(written_texels(*off), 0u);
}

// Seed 004 §3.7.2 (R2): the shadow pass casts only the chunks inside the cascade's light frustum;
// with the culling off it casts every chunk of the world, far ones too.
TEST_F(VoxelShadowGl, ShadowChunkCullingLeavesOutChunksOutsideTheLightFrustum) {
  World world;
  add_ground(world);
  const BlockId stone = world.palette().id("stone");
  for (int i = 0; i < 4; ++i) (void)world.set({300 + 40 * i, 1, 300}, stone);  // four far chunks
  remesh(world);
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(128, 80);
  scene.lighting.sun_direction = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  scene.camera.set_position({-7.0, 6.0, 8.0});
  scene.camera.look_at({3.0, 1.0, 8.0});
  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.max_distance = 40.0f;
  (void)cast(**renderer, scene, ss);
  const std::size_t culled = (*renderer)->frame_stats().shadow_chunks_cast;
  (*renderer)->settings().shadow_chunk_culling = false;
  (void)cast(**renderer, scene, ss);
  const std::size_t all = (*renderer)->frame_stats().shadow_chunks_cast;
  std::printf("shadow chunks cast: %zu culled, %zu without culling\n", culled, all);
  EXPECT_GT(culled, 0u);
  EXPECT_EQ(all, 2 * world.chunk_coords().size());  // every chunk into both cascades
  EXPECT_LT(culled, all - 2 * 4);                    // the four far chunks were left out of both
}

TEST_F(VoxelShadowGl, SceneHookAndCasterPathsCastEachCascadeOnce) {
  World world;
  add_ground(world);
  const BlockId stone = world.palette().id("stone");
  for (int y = 1; y <= 6; ++y) (void)world.set({4, y, 4}, stone);
  remesh(world);
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok());
  auto scene = testing::VoxelGlScene::create(64, 64);
  scene.camera.set_position({-5.0, 10.0, -5.0});
  scene.camera.look_at({8.0, 1.0, 8.0});
  render::ShadowSettings ss;
  ss.cascade_count = 2;
  ss.resolution = 256;
  ss.max_distance = 60.0f;
  const render::FrameContext frame{scene.camera, 0.0, 0.0f, scene.wind, scene.lighting, scene.target.size(), 0};
  (*renderer)->update(frame);
  render::apply_reversed_z_state();

  Result<render::ShadowMaps> a = render::ShadowMaps::create(ss);
  ASSERT_TRUE(a.ok());
  a->add_caster(&(*renderer)->shadow_caster());
  render::PassStats sa;
  ASSERT_TRUE(a->render(scene.camera, scene.lighting.sun_direction, &frame, &sa).ok());
  a->remove_caster(&(*renderer)->shadow_caster());

  // The scene registers the renderer's kShadow pass and a caster calling draw_depth.
  Result<render::ShadowMaps> b = render::ShadowMaps::create(ss);
  ASSERT_TRUE(b.ok());
  render::CallbackShadowCaster hook([&](const render::ShadowCasterContext& c) {
    (*renderer)->draw(render::Pass::kShadow, frame, *c.stats);
    (*renderer)->draw_depth(c.relative_view_projection, c.camera->position(), *c.stats);
  });
  b->add_caster(&hook);
  render::PassStats sb;
  ASSERT_TRUE(b->render(scene.camera, scene.lighting.sun_direction, &frame, &sb).ok());
  b->remove_caster(&hook);
  EXPECT_EQ(read_depth_array(*b), read_depth_array(*a));
  EXPECT_EQ(sb.draw_calls, sa.draw_calls) << "draw_depth after draw(kShadow) must not cast the cascade again";
  EXPECT_GT(sa.draw_calls, 0u);
  // Outside ShadowMaps::render, draw(kShadow) draws nothing.
  render::PassStats none;
  (*renderer)->draw(render::Pass::kShadow, frame, none);
  EXPECT_EQ(none.draw_calls, 0u);
}

}  // namespace
}  // namespace sylva::voxel
