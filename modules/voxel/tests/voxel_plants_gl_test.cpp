// Plants at world scale (issue #18, "Voxel world"): hidden plant faces and parts are skipped
// without changing the picture, far chunks draw plant shells within a bounded image change,
// plants are culled one by one inside chunks the view or a shadow cascade cuts, near and far
// plants baked into meshes draw the instanced picture, and the depth pre-pass the one-pass one.

#include <sylva/core/image_metrics.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/voxel/voxel_renderer.hpp>
#include <sylva/voxel/world_builder.hpp>

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

#include "support/voxel_gl_scene.hpp"

namespace sylva::voxel {
namespace {

using VoxelPlantsGl = render::GlTest;

struct GeneratedWorld {
  std::shared_ptr<const WorldGenerator> generator;
  World world;
};

// Seed 3's spawn (the shipped scene's), 3 x 3 chunk columns: meadow, savanna and birch forest.
std::unique_ptr<GeneratedWorld> make_world() {
  WorldGenSettings gs;
  gs.seed = 3;
  gs.variants_per_species = 4;
  auto gen = WorldGenerator::create(gs);
  if (!gen.ok()) return nullptr;
  auto out = std::make_unique<GeneratedWorld>(GeneratedWorld{std::move(*gen), World(BlockPalette::standard())});
  WorkerPool pool(2);
  std::int64_t y0, y1;
  chunk_y_range(gs, y0, y1);
  populate(out->world, *out->generator, chunk_box({0, 0, 0}, 1, y0, y1), pool);
  remesh_parallel(out->world, pool, MesherKind::kBitmask);
  return out;
}

struct Shot {
  Image image;
  VoxelFrameStats stats;
};

Shot render_view(const GeneratedWorld& w, const VoxelRenderSettings& settings, const glm::dvec3& eye,
                 const glm::dvec3& target) {
  auto renderer = VoxelRenderer::create(w.world, w.generator, settings);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(320, 180);
  scene.camera.set_position(eye);
  scene.camera.look_at(target);
  scene.render(**renderer);
  return {scene.color(), (*renderer)->frame_stats()};
}

// Pixels whose largest channel difference exceeds `tolerance` (core's image metrics).
std::size_t differing_pixels(const Image& a, const Image& b, float tolerance) {
  return count_exceeding(a, b, tolerance).value().pixels;
}

// Baked far shells against instanced ones (320 x 180): the same faces, rasterised from the same
// corner positions up to float rounding of the quaternion turn: 0 pixels on llvmpipe, a handful
// of edge pixels allowed for other rasterisers.
constexpr std::size_t kBakedMeshPixelBudget = 20;

// Exact plants everywhere, instanced (plant.vert): the reference the baked meshes are held to.
VoxelRenderSettings near_only() {
  VoxelRenderSettings s;
  s.plant_far_beyond = 1.0e6f;
  s.plant_near_mesh = false;
  s.depth_prepass = false;  // one pass: coplanar faces resolve by draw order as GL_GREATER does
  return s;
}

TEST_F(VoxelPlantsGl, HiddenPlantFacesAreSkippedWithoutChangingThePicture) {
  auto w = make_world();
  ASSERT_TRUE(w);
  VoxelRenderSettings all = near_only();
  all.plant_hidden_faces = false;
  const glm::dvec3 eye(-12.0, 42.0, -12.0), target(16.0, 22.0, 16.0);
  const Shot before = render_view(*w, all, eye, target);
  const Shot after = render_view(*w, near_only(), eye, target);
  testing::save_png(after.image, "voxel_plants_hidden_faces");
  ASSERT_GT(before.stats.plant_parts_drawn, 1000u);
  // Faces inside trunks and leaves inside logs are gone...
  EXPECT_LT(after.stats.plant_triangles, before.stats.plant_triangles);
  // ...and nothing a camera sees changed (they lie inside the union of the parts).
  EXPECT_EQ(differing_pixels(before.image, after.image, 0.02f), 0u);
}

TEST_F(VoxelPlantsGl, FarChunksDrawPlantShellsCloseToTheExactPlants) {
  auto w = make_world();
  ASSERT_TRUE(w);
  const glm::dvec3 eye(-110.0, 70.0, -110.0), target(16.0, 22.0, 16.0);
  const Shot exact = render_view(*w, near_only(), eye, target);
  VoxelRenderSettings far = near_only();
  far.plant_far_beyond = 96.0f;
  far.plant_far_mesh = false;  // instanced shells: their cubes are counted (baked: the next test)
  const Shot shells = render_view(*w, far, eye, target);
  testing::save_png(shells.image, "voxel_plants_far_shells");
  EXPECT_EQ(exact.stats.plant_far_chunks, 0u);
  EXPECT_GT(shells.stats.plant_far_chunks, 0u);
  EXPECT_LT(shells.stats.plant_parts_drawn, exact.stats.plant_parts_drawn * 3 / 4);
  EXPECT_LT(shells.stats.plant_triangles, exact.stats.plant_triangles * 3 / 4);
  // The picture moves by at most half a block at 130-190 blocks (a few pixels here).
  const std::size_t changed = differing_pixels(exact.image, shells.image, 0.1f);
  EXPECT_GT(changed, 0u);
  EXPECT_LT(changed, exact.image.pixel_count() * 3 / 100);
  // plant_far_cell 2: shells on a grid twice as coarse, fewer cubes again.
  far.plant_far_cell = 2.0f;
  const Shot coarse = render_view(*w, far, eye, target);
  EXPECT_LT(coarse.stats.plant_parts_drawn, shells.stats.plant_parts_drawn * 3 / 4);
  EXPECT_LT(differing_pixels(exact.image, coarse.image, 0.1f), exact.image.pixel_count() * 6 / 100);
  far.plant_far_cell = 0.5f;
  auto refused = VoxelRenderer::create(w->world, w->generator, far);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("voxel.render.plant_far_cell"), std::string::npos) << refused.error().message;
}

TEST_F(VoxelPlantsGl, FarShellsBakedIntoMeshesDrawTheInstancedPicture) {
  auto w = make_world();
  ASSERT_TRUE(w);
  const glm::dvec3 eye(-110.0, 70.0, -110.0), target(16.0, 22.0, 16.0);
  VoxelRenderSettings far = near_only();
  far.plant_far_beyond = 96.0f;
  far.plant_far_mesh = false;
  const Shot instanced = render_view(*w, far, eye, target);
  far.plant_far_mesh = true;
  const Shot baked = render_view(*w, far, eye, target);
  testing::save_png(baked.image, "voxel_plants_far_mesh");
  EXPECT_EQ(baked.stats.plant_far_chunks, instanced.stats.plant_far_chunks);
  ASSERT_GT(baked.stats.plant_far_chunks, 0u);
  EXPECT_EQ(instanced.stats.plant_mesh_triangles, 0u);
  EXPECT_GT(baked.stats.plant_mesh_triangles, 0u);
  // The eye is off the chunks' -x and -z sides: the +x and +z groups of far chunks face away.
  EXPECT_GT(baked.stats.plant_mesh_groups_skipped, 0u);
  // No far instances any more; the baked triangles are those of the faces turned to the eye.
  EXPECT_LT(baked.stats.plant_parts_drawn, instanced.stats.plant_parts_drawn);
  EXPECT_LE(baked.stats.plant_triangles, instanced.stats.plant_triangles);
  const std::size_t changed = differing_pixels(instanced.image, baked.image, 0.02f);
  RecordProperty("pixels_changed", static_cast<int>(changed));
  RecordProperty("triangles_instanced", static_cast<int>(instanced.stats.plant_triangles));
  RecordProperty("triangles_baked", static_cast<int>(baked.stats.plant_triangles));
  RecordProperty("groups_skipped", static_cast<int>(baked.stats.plant_mesh_groups_skipped));
  EXPECT_LE(changed, kBakedMeshPixelBudget);
}

TEST_F(VoxelPlantsGl, NearPlantsBakedIntoMeshesDrawTheInstancedPicture) {
  auto w = make_world();
  ASSERT_TRUE(w);
  // Close to the world's -x -z corner: leaf chunks within 48 blocks (both sides of every leaf
  // cube) and beyond (faces turned to the eye), all exact plants (no far shells).
  const glm::dvec3 eye(-12.0, 42.0, -12.0), target(16.0, 22.0, 16.0);
  const Shot instanced = render_view(*w, near_only(), eye, target);
  VoxelRenderSettings baked_settings = near_only();
  baked_settings.plant_near_mesh = true;
  const Shot baked = render_view(*w, baked_settings, eye, target);
  testing::save_png(baked.image, "voxel_plants_near_mesh");
  ASSERT_GT(instanced.stats.plant_parts_drawn, 1000u);
  EXPECT_EQ(instanced.stats.plant_mesh_triangles, 0u);
  // No plant instances in the colour pass any more: every plant triangle comes from the meshes.
  EXPECT_EQ(baked.stats.plant_parts_drawn, 0u);
  EXPECT_GT(baked.stats.plant_mesh_triangles, 0u);
  EXPECT_EQ(baked.stats.plant_mesh_triangles, baked.stats.plant_triangles);
  EXPECT_EQ(baked.stats.plant_far_chunks, 0u);
  const std::size_t changed = differing_pixels(instanced.image, baked.image, 0.02f);
  RecordProperty("pixels_changed", static_cast<int>(changed));
  RecordProperty("triangles_instanced", static_cast<int>(instanced.stats.plant_triangles));
  RecordProperty("triangles_baked", static_cast<int>(baked.stats.plant_triangles));
  EXPECT_LE(changed, kBakedMeshPixelBudget);
}

TEST_F(VoxelPlantsGl, BakedNearPlantsAreCulledOneByOne) {
  auto w = make_world();
  ASSERT_TRUE(w);
  // As PlantsAreCulledOneByOne...: the frustum cuts the chunks along the world's edge.
  const glm::dvec3 eye(16.0, 40.0, -20.0), target(20.0, 24.0, 40.0);
  VoxelRenderSettings baked = near_only();
  baked.plant_near_mesh = true;
  const Shot culled = render_view(*w, baked, eye, target);
  baked.frustum_culling = false;
  const Shot all = render_view(*w, baked, eye, target);
  EXPECT_GT(culled.stats.plants_culled, 0u);
  EXPECT_EQ(all.stats.plants_culled, 0u);
  EXPECT_GT(culled.stats.plant_mesh_triangles, 0u);
  EXPECT_LT(culled.stats.plant_mesh_triangles, all.stats.plant_mesh_triangles);
  EXPECT_EQ(differing_pixels(culled.image, all.image, 0.0f), 0u);
  // And the same picture as the instanced culled plants.
  const Shot instanced = render_view(*w, near_only(), eye, target);
  EXPECT_LE(differing_pixels(instanced.image, culled.image, 0.02f), kBakedMeshPixelBudget);
}

TEST_F(VoxelPlantsGl, DepthPrePassShadesTheSamePicture) {
  auto w = make_world();
  ASSERT_TRUE(w);
  const glm::dvec3 eye(-12.0, 42.0, -12.0), target(16.0, 22.0, 16.0);
  VoxelRenderSettings one_pass;
  one_pass.depth_prepass = false;
  const Shot before = render_view(*w, one_pass, eye, target);
  EXPECT_FALSE(VoxelRenderSettings{}.depth_prepass) << "off by default (issue #18: it costs more than it saves)";
  VoxelRenderSettings prepass;
  prepass.depth_prepass = true;
  auto renderer = VoxelRenderer::create(w->world, w->generator, prepass);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(320, 180);
  scene.camera.set_position(eye);
  scene.camera.look_at(target);
  scene.render(**renderer);
  const Image after = scene.color();
  const render::PassStats two_passes = scene.last_stats;
  (*renderer)->settings().depth_prepass = false;
  scene.render(**renderer);
  const render::PassStats colour_only = scene.last_stats;
  // The pre-pass draws the same geometry once more (depth only)...
  EXPECT_EQ(two_passes.triangles, 2 * colour_only.triangles);
  EXPECT_EQ(two_passes.draw_calls, 2 * colour_only.draw_calls);
  // ...and the voxel counts are the colour pass's.
  EXPECT_EQ((*renderer)->frame_stats().plant_triangles, before.stats.plant_triangles);
  // Same picture: only pixels where two coplanar faces overlap exactly may swap (the last one
  // drawn wins a GL_EQUAL test, the first one GL_GREATER): leaves touching leaves.
  const std::size_t changed = differing_pixels(before.image, after, 0.02f);
  RecordProperty("pixels_changed", static_cast<int>(changed));
  EXPECT_LE(changed, static_cast<std::size_t>(before.image.width() * before.image.height() / 1000));
}

// Fragments that passed the depth test in one render of `scene` (GL_SAMPLES_PASSED).
std::uint64_t samples_passed(testing::VoxelGlScene& scene, VoxelRenderer& renderer) {
  GLuint query = 0;
  glGenQueries(1, &query);
  glBeginQuery(GL_SAMPLES_PASSED, query);
  scene.render(renderer);
  glEndQuery(GL_SAMPLES_PASSED);
  GLuint64 samples = 0;
  glGetQueryObjectui64v(query, GL_QUERY_RESULT, &samples);
  glDeleteQueries(1, &query);
  return samples;
}

// Without the pre-pass, plants and tufts are drawn before the ground they stand on, so the
// early depth test keeps the fragment shader off the ground behind them (issue #18). The
// pre-pass's depth half passes as many samples as the one-pass render (same geometry, same
// order), its colour half one per covered pixel; so one pass / (two passes - one pass) is the
// fragments shaded per covered pixel: 1.31 here (ground first: 1.57).
TEST_F(VoxelPlantsGl, PlantsDrawnBeforeTheGroundKeepShadingOffItsHiddenPixels) {
  auto w = make_world();
  ASSERT_TRUE(w);
  auto renderer = VoxelRenderer::create(w->world, w->generator, VoxelRenderSettings{});
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(320, 180);
  scene.camera.set_position({-12.0, 42.0, -12.0});
  scene.camera.look_at({16.0, 22.0, 16.0});
  (*renderer)->settings().depth_prepass = true;
  const std::uint64_t two_passes = samples_passed(scene, **renderer);
  (*renderer)->settings().depth_prepass = false;
  const std::uint64_t one_pass = samples_passed(scene, **renderer);
  ASSERT_GT(two_passes, one_pass);
  const std::uint64_t covered = two_passes - one_pass;
  EXPECT_GT(covered, 320u * 180u / 2u) << "the view is mostly ground and plants";
  EXPECT_GT((*renderer)->frame_stats().plant_triangles, 0u);
  const double per_pixel = static_cast<double>(one_pass) / static_cast<double>(covered);
  std::printf("one pass: %llu samples for %llu covered pixels (%.3f per pixel)\n",
              static_cast<unsigned long long>(one_pass), static_cast<unsigned long long>(covered), per_pixel);
  RecordProperty("fragments_per_pixel_x1000", static_cast<int>(per_pixel * 1000.0));
  EXPECT_LT(per_pixel, 1.4) << "the ground shaded under the plants";
}

TEST_F(VoxelPlantsGl, PlantsAreCulledOneByOneInTheViewAndInShadowCascades) {
  auto w = make_world();
  ASSERT_TRUE(w);
  // Looking along the world's edge: the frustum cuts the chunks, so some of their plants lie outside.
  const glm::dvec3 eye(16.0, 40.0, -20.0), target(20.0, 24.0, 40.0);
  const Shot culled = render_view(*w, near_only(), eye, target);
  VoxelRenderSettings off = near_only();
  off.frustum_culling = false;
  const Shot all = render_view(*w, off, eye, target);
  EXPECT_GT(culled.stats.plants_culled, 0u);
  EXPECT_EQ(all.stats.plants_culled, 0u);
  EXPECT_LT(culled.stats.plant_parts_drawn, all.stats.plant_parts_drawn);
  EXPECT_EQ(differing_pixels(culled.image, all.image, 0.0f), 0u);

  // A cascade seeing a 20 x 20 block square of the middle chunk column casts only the plants in it.
  auto renderer = VoxelRenderer::create(w->world, w->generator, near_only());
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(64, 64);
  scene.camera.set_position({16.0, 30.0, 16.0});
  scene.render(**renderer);  // update(): uploads the chunks
  const render::Camera& camera = scene.camera;
  const glm::mat4 ortho = glm::ortho(-10.0f, 10.0f, -10.0f, 10.0f, -200.0f, 200.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f));
  auto cast = [&](bool chunk_culling) {
    (*renderer)->settings().shadow_chunk_culling = chunk_culling;
    const std::size_t culled_before = (*renderer)->frame_stats().plants_culled;
    render::PassStats stats;
    render::ShadowCasterContext context;
    context.relative_view_projection = ortho * view;
    context.light_frustum = render::Frustum::from_matrix(ortho * view, camera.position());
    context.camera = &camera;
    context.stats = &stats;
    (*renderer)->draw_shadow(context);
    return std::pair{stats.instances, (*renderer)->frame_stats().plants_culled - culled_before};
  };
  const auto [cut_instances, cut_culled] = cast(true);
  const auto [all_instances, all_culled] = cast(false);
  EXPECT_GT(cut_culled, 0u);
  EXPECT_EQ(all_culled, 0u);
  EXPECT_GT(cut_instances, 0u);
  EXPECT_LT(cut_instances, all_instances);
}

}  // namespace
}  // namespace sylva::voxel
