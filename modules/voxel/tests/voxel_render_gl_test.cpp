// GL tests of the voxel renderer: the three meshers rasterise to the same depth; chunks 1e6
// blocks from the origin render exactly like at the origin; point lights and culling work; a
// generated world renders (screenshots saved for inspection).

#include <sylva/core/image_metrics.hpp>
#include <sylva/render/point_lights.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/shadow_maps.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/voxel/world_builder.hpp>
#include <sylva/voxel/voxel_renderer.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <span>

#include <glm/gtc/matrix_transform.hpp>
#include <sylva/render/readback.hpp>

#include "support/test_chunks.hpp"
#include "support/voxel_gl_scene.hpp"

namespace sylva::voxel {
namespace {

using VoxelRenderGl = render::GlTest;

// A 2x1x2-chunk world with terrain-like, random and alpha-cut content across chunk borders.
World make_test_world(std::int64_t offset_blocks) {
  const BlockPalette& pal = BlockPalette::standard();
  World w(pal);
  const BlockId stone = pal.id("stone"), grass = pal.id("grass"), leaves = pal.id("oak_leaves"),
                dirt = pal.id("dirt"), lantern = pal.id("lantern");
  for (int z = 0; z < 64; ++z) {
    for (int x = 0; x < 64; ++x) {
      const int h = 6 + static_cast<int>(4.0 * std::sin(x * 0.2) + 3.0 * std::cos(z * 0.15));
      for (int y = 0; y <= h; ++y) {
        (void)w.set({offset_blocks + x, y, offset_blocks + z}, y == h ? grass : y > h - 3 ? dirt : stone);
      }
      if ((x * 7 + z * 3) % 23 == 0) (void)w.set({offset_blocks + x, h + 1, offset_blocks + z}, leaves);
      if (x > 20 && x < 30 && z > 20 && z < 30 && ((x + z) % 3 == 0)) {
        for (int y = h + 1; y < h + 5; ++y) (void)w.set({offset_blocks + x, y, offset_blocks + z}, stone);
      }
    }
  }
  (void)w.set({offset_blocks + 40, 20, offset_blocks + 40}, lantern);
  return w;
}

void remesh_all(World& w, MesherKind kind) {
  for (const auto& c : w.chunk_coords()) w.mark_dirty(c);
  auto mesher = make_mesher(kind);
  (void)w.remesh(*mesher);
}

struct View {
  glm::dvec3 eye;
  glm::dvec3 target;
};
const View kViews[] = {
    {{-10.0, 25.0, -10.0}, {32.0, 5.0, 32.0}},
    {{70.0, 12.0, 20.0}, {30.0, 8.0, 30.0}},
    {{32.0, 60.0, 33.0}, {32.0, 0.0, 32.0}},
    {{5.0, 9.0, 50.0}, {40.0, 9.0, 10.0}},  // grazing, close to the ground
};

TEST_F(VoxelRenderGl, ThreeMeshersRasteriseTheSameDepth) {
  World world = make_test_world(0);
  auto scene = testing::VoxelGlScene::create();
  std::vector<std::vector<Image>> depth(3), color(3);
  for (auto kind : {MesherKind::kCulled, MesherKind::kGreedy, MesherKind::kBitmask}) {
    remesh_all(world, kind);
    auto renderer = VoxelRenderer::create(world, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    for (const View& v : kViews) {
      scene.camera.set_position(v.eye);
      scene.camera.look_at(v.target);
      scene.render(**renderer);
      depth[static_cast<int>(kind)].push_back(scene.depth());
      color[static_cast<int>(kind)].push_back(scene.color());
    }
  }
  testing::save_png(color[2][0], "voxel_meshers_view0");
  for (std::size_t v = 0; v < std::size(kViews); ++v) {
    const Image& ref = depth[0][v];
    std::size_t covered = 0;
    for (float d : ref.data()) covered += d > 0.0f;
    EXPECT_GT(covered, ref.pixel_count() / 4) << "view " << v << " shows the world";
    for (int k = 1; k < 3; ++k) {
      const Image& other = depth[static_cast<std::size_t>(k)][v];
      std::size_t differ = 0;
      float worst = 0.0f;
      for (std::size_t i = 0; i < ref.data().size(); ++i) {
        const float a = ref.data()[i], b = other.data()[i];
        const float rel = std::abs(a - b) / std::max(std::abs(a), 1e-6f);
        if (rel > 1e-4f) ++differ;
        else worst = std::max(worst, rel);
      }
      // Merged quads meet unit quads at T-junctions; rasterisation may differ at a handful of
      // edge pixels, never over surfaces.
      EXPECT_LE(differ, ref.pixel_count() / 1000) << "view " << v << " mesher " << k << ": " << differ << " pixels";
      std::size_t color_differ = 0;
      const Image& c0 = color[0][v];
      const Image& ck = color[static_cast<std::size_t>(k)][v];
      for (std::size_t i = 0; i < c0.data().size(); ++i) color_differ += std::abs(c0.data()[i] - ck.data()[i]) > 3.0f / 255.0f;
      EXPECT_LE(color_differ, c0.data().size() / 200) << "view " << v << " mesher " << k << ": shading matches too";
    }
  }
}

TEST_F(VoxelRenderGl, ChunksAtPlusMinusOneMillionBlocksRenderLikeAtTheOrigin) {
  // Invariant: camera-relative rendering; the same blocks seen from the same relative camera give
  // the same picture at the origin and +-1e6 blocks away (no jitter from float positions).
  auto scene = testing::VoxelGlScene::create();
  std::vector<Image> images;
  for (std::int64_t offset : {std::int64_t{0}, std::int64_t{1'000'000}, std::int64_t{-1'000'000}}) {
    World world = make_test_world(offset);
    remesh_all(world, MesherKind::kBitmask);
    auto renderer = VoxelRenderer::create(world, nullptr);
    ASSERT_TRUE(renderer.ok()) << renderer.error().message;
    const glm::dvec3 o(static_cast<double>(offset), 0.0, static_cast<double>(offset));
    // Several sub-block camera steps: each must match its origin twin exactly.
    for (double step : {0.0, 0.013, 0.37}) {
      scene.camera.set_position(o + glm::dvec3(-10.0 + step, 25.0, -10.0 + step * 0.5));
      scene.camera.look_at(o + glm::dvec3(32.0, 5.0, 32.0));
      scene.render(**renderer);
      images.push_back(scene.color());
    }
  }
  testing::save_png(images[4], "voxel_far_from_origin");
  for (std::size_t i = 3; i < images.size(); ++i) {
    const Image& ref = images[i % 3];
    std::size_t differ = 0;
    for (std::size_t k = 0; k < ref.data().size(); ++k) differ += std::abs(ref.data()[k] - images[i].data()[k]) > 1.5f / 255.0f;
    EXPECT_LE(differ, ref.data().size() / 2000) << "image " << i << " differs in " << differ << " channels";
  }
}

TEST_F(VoxelRenderGl, PointLightBrightensWithSeedAttenuation) {
  const BlockPalette& pal = BlockPalette::standard();
  World world(pal);
  for (int z = -20; z < 20; ++z)
    for (int x = -20; x < 20; ++x) (void)world.set({x, 0, z}, pal.id("stone"));
  remesh_all(world, MesherKind::kGreedy);
  auto scene = testing::VoxelGlScene::create(128, 128);
  scene.lighting.sun_intensity = 0.0f;
  scene.lighting.ambient = glm::vec3(0.02f);
  scene.camera.set_position({0.5, 30.0, 0.6});
  scene.camera.look_at({0.5, 0.0, 0.5});
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  scene.render(**renderer);
  const Image dark = scene.color();
  (void)world.set({0, 3, 0}, pal.id("lantern"));
  remesh_all(world, MesherKind::kGreedy);
  scene.render(**renderer);
  EXPECT_EQ((*renderer)->frame_stats().point_lights, 1u);
  const Image lit = scene.color();
  testing::save_png(lit, "voxel_point_light");
  auto lum = [](const Image& im, int x, int y) { return im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2); };
  // Floor pixels at increasing distance from the lamp along the image x axis.
  const int cy = 64;
  const float near_px = lum(lit, 64 + 12, cy), mid_px = lum(lit, 64 + 30, cy), far_px = lum(lit, 64 + 55, cy);
  EXPECT_GT(near_px, mid_px);
  EXPECT_GT(mid_px, far_px);
  EXPECT_GT(near_px, lum(dark, 64 + 12, cy) + 0.2f);
}

// The host's point lights (render core, UBO 3, e.g. the scene's) light voxel faces with the
// same attenuation; with nothing bound there the renderer binds an empty block (no lights) and
// restores the host's binding afterwards.
TEST_F(VoxelRenderGl, HostPointLightsFromTheRenderCoreLightTheFloor) {
  const BlockPalette& pal = BlockPalette::standard();
  World world(pal);
  for (int z = -20; z < 20; ++z)
    for (int x = -20; x < 20; ++x) (void)world.set({x, 0, z}, pal.id("stone"));
  remesh_all(world, MesherKind::kGreedy);
  auto scene = testing::VoxelGlScene::create(96, 96);
  scene.lighting.sun_intensity = 0.0f;
  scene.lighting.ambient = glm::vec3(0.02f);
  scene.camera.set_position({0.5, 30.0, 0.6});
  scene.camera.look_at({0.5, 0.0, 0.5});
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  glBindBufferBase(GL_UNIFORM_BUFFER, render::kPointLightBinding, 0);
  scene.render(**renderer);
  const Image dark = scene.color();
  render::PointLightUniforms lights = render::PointLightUniforms::create();
  render::PointLight lamp;
  lamp.position = {0.5, 3.0, 0.5};
  lamp.color = {1.0f, 0.8f, 0.6f};
  lamp.intensity = 2.0f;
  lamp.range = 30.0f;
  ASSERT_TRUE(lights.update(std::span<const render::PointLight>(&lamp, 1), scene.camera.position()).ok());
  lights.bind();
  scene.render(**renderer);
  const Image lit = scene.color();
  GLint bound = 0;
  glGetIntegeri_v(GL_UNIFORM_BUFFER_BINDING, render::kPointLightBinding, &bound);
  EXPECT_NE(bound, 0) << "the host's block stays bound";
  auto lum = [](const Image& im, int x, int y) { return im.at(x, y, 0) + im.at(x, y, 1) + im.at(x, y, 2); };
  const float centre = lum(lit, 48, 48), edge = lum(lit, 48 + 40, 48);
  std::printf("host point light: centre %.3f (dark %.3f), edge %.3f\n", centre, lum(dark, 48, 48), edge);
  EXPECT_GT(centre, lum(dark, 48, 48) + 0.3f);
  EXPECT_GT(centre, edge);
  glBindBufferBase(GL_UNIFORM_BUFFER, render::kPointLightBinding, 0);
}

// Specular maps (seed §2.3.2): seen at the sun's mirror angle, snow (specular 0.6 with its map)
// shows a highlight that vanishes with specular_scale 0; dirt (no specular: "a missing map means
// no gloss") looks the same either way.
TEST_F(VoxelRenderGl, SpecularMapsGiveHighlightsOnlyToGlossyBlocks) {
  const BlockPalette& pal = BlockPalette::standard();
  ASSERT_EQ(pal[pal.id("dirt")].specular, 0.0f);
  ASSERT_GT(pal[pal.id("snow")].specular, 0.0f);
  World world(pal);
  for (int z = -12; z < 12; ++z)
    for (int x = -12; x < 12; ++x) (void)world.set({x, 0, z}, pal.id(x < 0 ? "snow" : "dirt"));
  remesh_all(world, MesherKind::kBitmask);
  auto scene = testing::VoxelGlScene::create(128, 96);
  scene.lighting.sun_direction = glm::normalize(glm::vec3(0.0f, 0.5f, 1.0f));
  scene.lighting.sun_intensity = 0.5f;  // keep white snow below saturation
  scene.lighting.ambient = glm::vec3(0.05f);
  // The mirror direction of the sun about the floor's normal points at the camera.
  scene.camera.set_position({0.0, 11.0, -20.0});
  scene.camera.look_at({0.0, 1.0, 0.0});
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  scene.render(**renderer);
  const Image glossy = scene.color();
  (*renderer)->settings().specular_scale = 0.0f;
  scene.render(**renderer);
  const Image matte = scene.color();
  auto mean_at = [&scene](const Image& im, double wx) {
    // Mean brightness of a 5 x 5 pixel patch around the projection of floor point (wx, 1, 0).
    const glm::vec4 clip = scene.camera.view_projection() * glm::vec4(scene.camera.to_relative({wx, 1.0, 0.0}), 1.0f);
    const int px = static_cast<int>((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(im.width()));
    const int py = static_cast<int>((0.5f - clip.y / clip.w * 0.5f) * static_cast<float>(im.height()));
    double sum = 0.0;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
        for (int c = 0; c < 3; ++c) sum += im.at(std::clamp(px + dx, 0, im.width() - 1), std::clamp(py + dy, 0, im.height() - 1), c);
    return sum / 75.0;
  };
  const double snow_gloss = mean_at(glossy, -3.0), snow_matte = mean_at(matte, -3.0);
  const double dirt_gloss = mean_at(glossy, 3.0), dirt_matte = mean_at(matte, 3.0);
  std::printf("snow %.4f -> %.4f without specular, dirt %.4f -> %.4f\n", snow_gloss, snow_matte, dirt_gloss, dirt_matte);
  EXPECT_GT(snow_gloss, snow_matte + 0.05);
  EXPECT_NEAR(dirt_gloss, dirt_matte, 1e-3);
}

TEST_F(VoxelRenderGl, FrustumCullingSkipsChunksBehindTheCamera) {
  World world = make_test_world(0);
  remesh_all(world, MesherKind::kBitmask);
  auto scene = testing::VoxelGlScene::create();
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok());
  scene.camera.set_position({32.0, 20.0, -40.0});
  scene.camera.look_at({32.0, 20.0, -100.0});  // looking away
  scene.render(**renderer);
  EXPECT_EQ((*renderer)->frame_stats().chunks_drawn, 0u);
  EXPECT_EQ(scene.last_stats.draw_calls, 0u);
  scene.camera.look_at({32.0, 5.0, 32.0});
  scene.render(**renderer);
  EXPECT_GT((*renderer)->frame_stats().chunks_drawn, 0u);
  EXPECT_GT(scene.last_stats.triangles, 0u);
}

TEST_F(VoxelRenderGl, ShadowHookIsPluggableAndDepthPassDraws) {
  // The Lighting issue's cascades plug in through set_shadow_receiver; here a hook that puts
  // everything in shadow must darken sunlit faces, and draw_depth must fill a depth-only target.
  World world = make_test_world(0);
  remesh_all(world, MesherKind::kBitmask);
  auto scene = testing::VoxelGlScene::create();
  scene.camera.set_position({-10.0, 25.0, -10.0});
  scene.camera.look_at({32.0, 5.0, 32.0});
  auto renderer = VoxelRenderer::create(world, nullptr);
  ASSERT_TRUE(renderer.ok());
  scene.render(**renderer);
  const Image lit = scene.color();
  int bound = 0;
  ShadowReceiver hook;
  hook.glsl_source = "uniform float u_test_shadow;\nfloat voxel_shadow(vec3 rel_pos, vec3 normal) { return u_test_shadow; }\n";
  hook.bind = [&bound](GLuint program) {
    ++bound;
    glProgramUniform1f(program, glGetUniformLocation(program, "u_test_shadow"), 0.0f);
  };
  ASSERT_TRUE((*renderer)->set_shadow_receiver(hook).ok());
  scene.render(**renderer);
  const Image shadowed = scene.color();
  EXPECT_GT(bound, 0);
  // Over the pixels showing geometry (not the clear colour).
  double sum_lit = 0.0, sum_shadowed = 0.0;
  for (int y = 0; y < lit.height(); ++y) {
    for (int x = 0; x < lit.width(); ++x) {
      if (std::abs(lit.at(x, y, 2) - scene.clear_color.b) < 0.02f) continue;
      for (int c = 0; c < 3; ++c) {
        sum_lit += lit.at(x, y, c);
        sum_shadowed += shadowed.at(x, y, c);
      }
    }
  }
  EXPECT_LT(sum_shadowed, sum_lit * 0.7);
  // A broken hook reports the compile error instead of crashing.
  ShadowReceiver broken;
  broken.glsl_source = "float voxel_shadow(vec3 p, vec3 n) { return undefined_thing; }\n";
  const Status st = (*renderer)->set_shadow_receiver(broken);
  EXPECT_FALSE(st.ok());
  (void)take_errors();
  ASSERT_TRUE((*renderer)->set_shadow_receiver({}).ok());
  // Depth-only pass from above with an orthographic light-like matrix.
  render::FramebufferDesc desc;
  desc.width = desc.height = 128;
  desc.color_formats.clear();
  auto depth_fb = render::Framebuffer::create(desc);
  ASSERT_TRUE(depth_fb.ok()) << depth_fb.error().message;
  depth_fb->bind();
  depth_fb->clear(glm::vec4(0.0f), 0.0f);
  const glm::mat4 ortho = glm::ortho(-40.0f, 40.0f, -40.0f, 40.0f, -100.0f, 100.0f);
  const glm::mat4 view = glm::lookAt(glm::vec3(0.0f), glm::vec3(0.3f, -1.0f, 0.2f), glm::vec3(0.0f, 0.0f, 1.0f));
  render::PassStats stats;
  glDepthFunc(GL_ALWAYS);
  (*renderer)->draw_depth(ortho * view, glm::dvec3(32.0, 10.0, 32.0), stats);
  glDepthFunc(GL_GREATER);
  EXPECT_GT(stats.draw_calls, 0u);
  auto depth = render::read_depth(*depth_fb);
  ASSERT_TRUE(depth.ok());
  std::size_t written = 0;
  for (float d : depth->data()) written += d != 0.0f;
  EXPECT_GT(written, depth->pixel_count() / 2);
}

// The generated chunks of seed 3 (the shipped spawn's) within 2 chunks of the origin, meshed,
// with a renderer of the default settings.
struct GeneratedWorld {
  World world;
  std::shared_ptr<const WorldGenerator> generator;
  std::unique_ptr<VoxelRenderer> renderer;
};

// Null (with a test failure recorded) when the generator or the renderer cannot be created.
std::unique_ptr<GeneratedWorld> generate_seed3() {
  WorldGenSettings gs;
  gs.seed = 3;
  gs.variants_per_species = 4;
  auto gen = WorldGenerator::create(gs);
  EXPECT_TRUE(gen.ok()) << gen.error().message;
  if (!gen.ok()) return nullptr;
  auto g = std::make_unique<GeneratedWorld>();
  g->generator = *gen;
  WorkerPool pool(2);
  std::int64_t y0, y1;
  chunk_y_range(gs, y0, y1);
  const auto coords = chunk_box({0, 0, 0}, 2, y0, y1);
  populate(g->world, *g->generator, coords, pool);
  remesh_parallel(g->world, pool, MesherKind::kBitmask);
  auto renderer = VoxelRenderer::create(g->world, g->generator);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  if (!renderer.ok()) return nullptr;
  g->renderer = std::move(*renderer);
  return g;
}

// A hazy view over the generated world (ground, plants, tufts), 100-150 blocks away.
void look_over_generated_world(testing::VoxelGlScene& scene) {
  scene.lighting.fog_density = 0.004f;
  scene.camera.set_position({-60.0, 70.0, -60.0});
  scene.camera.look_at({16.0, 20.0, 16.0});
}

// The overview at 256 x 144 that the shader-variant tests draw.
testing::VoxelGlScene overview_256x144() {
  auto scene = testing::VoxelGlScene::create(256, 144);
  look_over_generated_world(scene);
  return scene;
}

TEST_F(VoxelRenderGl, GeneratedWorldWithPlantsRenders) {
  const auto g = generate_seed3();
  ASSERT_TRUE(g);
  VoxelRenderer& renderer = *g->renderer;
  const World& world = g->world;
  const WorldGenerator* gen = g->generator.get();
  auto scene = testing::VoxelGlScene::create(320, 180);
  look_over_generated_world(scene);
  scene.render(renderer);
  const Image img = scene.color();
  testing::save_png(img, "voxel_generated_world");
  EXPECT_GT(renderer.frame_stats().plant_triangles, 0u);
  // Not blank: plenty of pixels differ from the clear colour.
  std::size_t drawn = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) drawn += std::abs(img.at(x, y, 2) - scene.clear_color.b) > 0.05f;
  EXPECT_GT(drawn, img.pixel_count() / 3);
  // A close view of the first tree found, for a person to look at the L-system plants.
  for (const auto& c : world.chunk_coords()) {
    const auto* plants = world.plants(c);
    if (!plants || plants->empty()) continue;
    const PlantInstance* tree = nullptr;
    for (const auto& p : *plants) {
      const std::string& name = gen->species().species.at(p.species).name;
      if (name != "forked_bush" && name != "berry_bush") tree = &p;
    }
    if (!tree) continue;
    const glm::dvec3 base(static_cast<double>(tree->ground.x), static_cast<double>(tree->ground.y),
                          static_cast<double>(tree->ground.z));
    scene.lighting.fog_density = 0.0f;
    scene.camera.set_position(base + glm::dvec3(-11.0, 12.0, -11.0));
    scene.camera.look_at(base + glm::dvec3(0.0, 7.0, 0.0));
    scene.render(renderer);
    const Image unshadowed = scene.color();
    testing::save_png(unshadowed, std::string("voxel_tree_") + gen->species().species.at(tree->species).name);
    // The same view in the render core's cascaded shadows: the tree shades the ground and itself.
    scene.lighting.sun_direction = glm::normalize(glm::vec3(0.6f, 0.5f, 0.3f));
    scene.render(renderer);
    const Image sunlit = scene.color();
    render::ShadowSettings ss;
    ss.cascade_count = 1;
    ss.resolution = 1024;
    ss.max_distance = 50.0f;
    auto maps = render::ShadowMaps::create(ss);
    ASSERT_TRUE(maps.ok());
    maps->add_caster(&renderer.shadow_caster());
    render::apply_reversed_z_state();
    ASSERT_TRUE(maps->render(scene.camera, scene.lighting.sun_direction, nullptr, nullptr).ok());
    maps->remove_caster(&renderer.shadow_caster());
    maps->bind();
    scene.render(renderer);
    const Image shadowed = scene.color();
    testing::save_png(shadowed, std::string("voxel_tree_shadowed_") + gen->species().species.at(tree->species).name);
    double a = 0.0, b = 0.0;
    for (int y = 0; y < shadowed.height(); ++y)
      for (int x = 0; x < shadowed.width(); ++x) {
        a += shadowed.at(x, y, 1);
        b += sunlit.at(x, y, 1);
      }
    EXPECT_LT(a, 0.97 * b) << "shadows darken the view";
    glBindBufferBase(GL_UNIFORM_BUFFER, render::kShadowUniformBinding, 0);
    break;
  }
}

// voxel.render.aerial_perspective: per_vertex (the default; extinction per metre interpolated from
// the vertices, distance, exponential and sky per pixel) draws blocks, plants and tufts within
// 2/255 of per_pixel (apply_fog) but through its own programs; off draws no air.
TEST_F(VoxelRenderGl, AerialPerspectivePerVertexMatchesPerPixelAndOffDrawsNoAir) {
  const auto g = generate_seed3();
  ASSERT_TRUE(g);
  VoxelRenderer& r = *g->renderer;
  EXPECT_EQ(r.settings().aerial_perspective, AerialPerspective::kPerVertex) << "the default";
  auto scene = overview_256x144();
  // Haze thinning with height: the extinction per metre then depends on the ray's direction, so
  // interpolating it is not exact (with uniform haze it is nearly constant).
  scene.lighting.fog_height_falloff = 0.03f;
  r.settings().aerial_perspective = AerialPerspective::kPerPixel;
  scene.render(r);
  const Image per_pixel = scene.color();
  r.settings().aerial_perspective = AerialPerspective::kPerVertex;
  scene.render(r);
  const Image per_vertex = scene.color();
  EXPECT_GT(r.frame_stats().plant_triangles, 0u);
  EXPECT_GT(r.frame_stats().tufts_drawn, 0u);
  r.settings().aerial_perspective = AerialPerspective::kOff;
  scene.render(r);
  const Image off = scene.color();
  testing::save_png(per_vertex, "voxel_air_per_vertex");
  testing::save_png(off, "voxel_air_off");
  float max_vertex = 0.0f;
  std::size_t vertex_differs = 0, off_differs = 0, drawn = 0;
  for (int y = 0; y < per_pixel.height(); ++y)
    for (int x = 0; x < per_pixel.width(); ++x) {
      float dv = 0.0f, doff = 0.0f, dclear = 0.0f;
      for (int c = 0; c < 3; ++c) {
        dv = std::max(dv, std::fabs(per_vertex.at(x, y, c) - per_pixel.at(x, y, c)));
        doff = std::max(doff, std::fabs(off.at(x, y, c) - per_pixel.at(x, y, c)));
        dclear = std::max(dclear, std::fabs(per_pixel.at(x, y, c) - scene.clear_color[c]));
      }
      drawn += dclear > 2.0f / 255.0f;
      max_vertex = std::max(max_vertex, dv);
      vertex_differs += dv > 0.0f;
      off_differs += doff > 8.0f / 255.0f;
    }
  ASSERT_GT(drawn, per_pixel.pixel_count() / 2);
  EXPECT_LE(max_vertex, 2.0f / 255.0f + 1e-6f) << "per-vertex air against per-pixel";
  std::printf("per_vertex vs per_pixel: %zu of %zu drawn pixels differ, max %.2f/255; off: %zu by > 8/255\n",
              vertex_differs, drawn, max_vertex * 255.0f, off_differs);
  EXPECT_GT(vertex_differs, 0u) << "per_vertex drew the per-pixel programs";
  EXPECT_GT(off_differs, drawn / 4) << "off still draws the air";
}

// Without point lights (no emissive block lit, no host block bound) the colour passes run the
// shaders without the point-light loops (llvmpipe runs a loop body once per pixel even for zero
// lights; issue #18); a host block switches to the shaders with them. The same picture when
// that block's one light shines with intensity 0.
TEST_F(VoxelRenderGl, ShadersWithoutPointLightLoopsDrawTheSamePictureWhenNoLightShines) {
  const auto g = generate_seed3();
  ASSERT_TRUE(g);
  VoxelRenderer& r = *g->renderer;
  auto scene = overview_256x144();
  glBindBufferBase(GL_UNIFORM_BUFFER, render::kPointLightBinding, 0);
  scene.render(r);
  const Image without_loops = scene.color();
  EXPECT_EQ(r.frame_stats().point_lights, 0u);
  EXPECT_EQ(r.frame_stats().point_light_shaders, 0u) << "no light: the shaders without loops";
  EXPECT_GT(r.frame_stats().plant_triangles, 0u);
  EXPECT_GT(r.frame_stats().tufts_drawn, 0u);
  render::PointLightUniforms lights = render::PointLightUniforms::create();
  render::PointLight dark_lamp;
  dark_lamp.position = glm::dvec3(scene.camera.position()) + glm::dvec3(0.0, -2.0, 0.0);
  dark_lamp.intensity = 0.0f;
  ASSERT_TRUE(lights.update(std::span<const render::PointLight>(&dark_lamp, 1), scene.camera.position()).ok());
  lights.bind();
  scene.render(r);
  const Image with_loops = scene.color();
  EXPECT_EQ(r.frame_stats().point_light_shaders, 1u) << "a host block: the shaders with loops";
  glBindBufferBase(GL_UNIFORM_BUFFER, render::kPointLightBinding, 0);
  const DifferenceCount d = count_exceeding(without_loops, with_loops, 0.0f).value();
  std::printf("point-light loops: %zu of %zu pixels differ, max %.2f/255\n", d.pixels, d.total, d.max_difference * 255.0f);
  EXPECT_EQ(d.pixels, 0u);
  scene.render(r);
  EXPECT_EQ(r.frame_stats().point_light_shaders, 0u) << "back to the shaders without loops";
}

// The shadow look-up runs only where it can change a pixel: with the render core's hook, a frame
// without a shadow pass (the scene's when its shadows are off: its block says "disabled") selects
// the shaders without it (llvmpipe runs the look-up under a mask otherwise; issue #18), a frame
// whose shadow pass ran the ones with it, known on the CPU without a read-back (the block's flag
// is read only in frames without a pass). The same picture as the look-up through a custom hook
// of the same text.
TEST_F(VoxelRenderGl, ShadowLookupLeftOutWhileTheHostsShadowsAreDisabled) {
  const auto g = generate_seed3();
  ASSERT_TRUE(g);
  VoxelRenderer& r = *g->renderer;
  auto scene = overview_256x144();
  render::ShadowSettings ss;
  ss.cascade_count = 1;
  ss.resolution = 256;
  auto maps = render::ShadowMaps::create(ss);
  ASSERT_TRUE(maps.ok()) << maps.error().describe();
  // The host's frame: update, then its shadow pass (casters drawn only while enabled), then the
  // colour passes with the maps' block bound.
  const auto shadow_pass = [&](const render::FrameContext& frame) {
    maps->add_caster(&r.shadow_caster());
    ASSERT_TRUE(maps->render(scene.camera, scene.lighting.sun_direction, &frame, nullptr).ok());
    maps->remove_caster(&r.shadow_caster());
    maps->bind();
  };
  scene.render(r, 0.0, shadow_pass);
  EXPECT_EQ(r.frame_stats().shadow_lookup_shaders, 1u) << "enabled cascades: the look-up";
  EXPECT_EQ(r.frame_stats().shadow_flag_reads, 0u) << "the shadow pass ran: nothing read back";
  const Image with_shadows = scene.color();
  scene.render(r);
  EXPECT_EQ(r.frame_stats().shadow_lookup_shaders, 1u) << "maps kept from an earlier frame, still enabled";
  EXPECT_EQ(r.frame_stats().shadow_flag_reads, 0u) << "a ShadowMaps' block: its flag is known on the CPU";

  // The scene's path with its shadows off: the maps upload "disabled" (cascade count 0, the
  // resolution and PCF radius still set), call no caster, and stay bound.
  maps->settings().enabled = false;
  scene.render(r, 0.0, shadow_pass);
  const Image without_lookup = scene.color();
  EXPECT_EQ(r.frame_stats().shadow_lookup_shaders, 0u) << "a disabled block: no look-up";
  EXPECT_EQ(r.frame_stats().shadow_flag_reads, 0u);
  {
    // A host's own block (not a ShadowMaps'): only its bytes can tell, so they are read back.
    const render::Buffer own = render::make_disabled_shadow_block();
    own.bind_base(GL_UNIFORM_BUFFER, render::kShadowUniformBinding);
    scene.render(r);
    EXPECT_EQ(r.frame_stats().shadow_lookup_shaders, 0u) << "its flag says disabled";
    EXPECT_GT(r.frame_stats().shadow_flag_reads, 0u);
    maps->bind();
  }
  EXPECT_GT(r.frame_stats().plant_triangles, 0u);
  ShadowReceiver same_hook;
  same_hook.glsl_source = render::shader_source("voxel/shadow_hook_default.glsl").value();
  ASSERT_TRUE(r.set_shadow_receiver(same_hook).ok());
  scene.render(r, 0.0, shadow_pass);
  const Image with_lookup = scene.color();
  EXPECT_EQ(r.frame_stats().shadow_lookup_shaders, 1u) << "a custom hook is called in every frame";
  same_hook.lit_when_core_shadows_disabled = true;  // what the scene's hook says of itself
  ASSERT_TRUE(r.set_shadow_receiver(same_hook).ok());
  scene.render(r, 0.0, shadow_pass);
  EXPECT_EQ(r.frame_stats().shadow_lookup_shaders, 0u) << "a hook lit where the core's shadows are disabled";
  ASSERT_TRUE(r.set_shadow_receiver({}).ok());
  glBindBufferBase(GL_UNIFORM_BUFFER, render::kShadowUniformBinding, 0);
  const DifferenceCount d = count_exceeding(without_lookup, with_lookup, 0.0f).value();
  std::printf("shadow look-up left out: %zu of %zu pixels differ, max %.2f/255\n", d.pixels, d.total,
              d.max_difference * 255.0f);
  EXPECT_EQ(d.pixels, 0u);
  EXPECT_GT(count_exceeding(with_shadows, without_lookup, 2.0f / 255.0f).value().pixels, 100u)
      << "the enabled frame did sample shadows";
}

// Chunks wholly nearer than the fade's start draw with the shaders without the fade (its sky
// look-up would run for every pixel on llvmpipe; issue #18), the others with it: with a view
// distance ending mid-view both kinds are drawn, without one none fades. The pictures of both
// settings stay within 1/255 of themselves drawn a second time (deterministic split).
TEST_F(VoxelRenderGl, OnlyChunksReachingPastTheFadesStartDrawTheFade) {
  const auto g = generate_seed3();
  ASSERT_TRUE(g);
  VoxelRenderer& r = *g->renderer;
  auto scene = testing::VoxelGlScene::create(256, 144);
  scene.camera.set_position({16.0, 60.0, 16.0});  // inside the 5 x 5 chunk world
  scene.camera.look_at({70.0, 25.0, 70.0});
  r.settings().view_distance = 0.0f;
  scene.render(r);
  EXPECT_GT(r.frame_stats().chunks_drawn, 0u);
  EXPECT_EQ(r.frame_stats().chunks_faded, 0u) << "no view distance: nothing fades";
  r.settings().view_distance = 60.0f;  // the fade from 42 to 60 blocks, across the view
  scene.render(r);
  const Image split = scene.color();
  const std::size_t drawn = r.frame_stats().chunks_drawn, faded = r.frame_stats().chunks_faded;
  std::printf("fade 42-60 blocks: %zu of %zu drawn chunks fade\n", faded, drawn);
  EXPECT_GT(faded, 0u);
  EXPECT_LT(faded, drawn) << "the chunks under the camera lie nearer than the fade's start";
  r.settings().fade_share = 1.0f;  // the fade from 0: every chunk reaches past its start
  scene.render(r);
  EXPECT_EQ(r.frame_stats().chunks_faded, r.frame_stats().chunks_drawn);
  r.settings().fade_share = 0.3f;
  scene.render(r);
  EXPECT_EQ(count_exceeding(split, scene.color(), 0.0f).value().pixels, 0u);

  // Straight down onto the chunk column under the eye: with the fade from 52 blocks it lies
  // nearer (drawn without the fade), from 23 blocks every chunk reaches past the start (with the
  // fade), but the middle of the picture (< 16 blocks away) lies nearer in both: no change.
  scene.camera.set_position({16.0, 60.0, 16.0});
  scene.camera.look_at({16.0, 0.0, 16.001});
  r.settings().view_distance = 52.0f / 0.7f;
  scene.render(r);
  const Image unfaded_middle = scene.color();
  const std::size_t unfaded_from_52 = r.frame_stats().chunks_drawn - r.frame_stats().chunks_faded;
  r.settings().view_distance = 23.0f / 0.7f;
  scene.render(r);
  const Image faded_middle = scene.color();
  EXPECT_GE(unfaded_from_52, 3u) << "the column under the eye and its neighbours lie nearer";
  EXPECT_EQ(r.frame_stats().chunks_faded, r.frame_stats().chunks_drawn) << "from 23 blocks all reach past";
  std::size_t middle = 0, differ = 0;
  for (int y = 0; y < scene.target.size().y; ++y)
    for (int x = 0; x < scene.target.size().x; ++x) {
      if ((x - 128) * (x - 128) + (y - 72) * (y - 72) > 40 * 40) continue;
      ++middle;
      for (int c = 0; c < 3; ++c) differ += unfaded_middle.at(x, y, c) != faded_middle.at(x, y, c) ? 1 : 0;
    }
  std::printf("straight down: %zu chunks without the fade -> none, %zu channel values differ in the middle %zu pixels\n",
              unfaded_from_52, differ, middle);
  EXPECT_EQ(differ, 0u);
}

}  // namespace
}  // namespace sylva::voxel
