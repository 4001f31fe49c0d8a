// Stability of the image-based levels on the GPU. Invariants named per test: a forest with LOD
// renders finite pixels for extreme thresholds (v1 = v2, 0, huge; screen size 0 and huge), for
// hurricane wind and huge times, far from the world origin (no jitter between two frames of a
// still camera), and the transition fades dither the shadow pass (a fade of 0 casts nothing,
// 1/2 about half, 1 everything).
#include <sylva/vegetation/forest.hpp>

#include <sylva/core/image_metrics.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"
#include "support/lod_scene.hpp"
#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sylva::vegetation {
namespace {

using LodForestStability = render::GlTest;

std::size_t non_finite(const Image& img) {
  std::size_t n = 0;
  for (float v : img.data()) n += std::isfinite(v) ? 0u : 1u;
  return n;
}

// Invariant: finite pixels, at least one tree drawn, per-LOD counts consistent, for every extreme
// threshold setting, hurricane wind and t = 1e7 s.
TEST_F(LodForestStability, ExtremeThresholdsWindAndTimeRenderFinitePictures) {
  Forest forest = testing::make_lod_forest(32);
  std::vector<TreeInstance> trees;
  for (int i = 0; i < 12; ++i) {
    TreeInstance t;
    t.position = {(i % 4) * 9.0 - 13.0, 0.0, -(i / 4) * 30.0 - 10.0};
    t.yaw = 0.4f * static_cast<float>(i);
    t.scale = i == 5 ? 1.0e-3f : (i == 6 ? 50.0f : 1.0f);
    trees.push_back(t);
  }
  ASSERT_TRUE(forest.set_instances(0, trees).ok());
  auto scene = testing::GlScene::create(64, 48);
  render::FramebufferDesc desc;
  desc.width = 64;
  desc.height = 48;
  desc.color_formats = {GL_RGBA32F};
  scene.target = render::Framebuffer::create(desc).value();
  scene.camera.set_position({0.0, 6.0, 12.0});
  scene.camera.look_at({0.0, 5.0, -40.0});
  const WindField hurricane(WindSettings{.strength = 80.0f, .gust_amplitude = 40.0f, .turbulence_amplitude = 20.0f});
  struct Case {
    const char* name;
    LodCriterion criterion;
    float v1, v2, s1, s2, band, hysteresis;
  };
  const Case cases[] = {{"v1=v2", LodCriterion::kDistance, 30.0f, 30.0f, 70.0f, 28.0f, 0.15f, 0.05f},
                        {"zero", LodCriterion::kDistance, 0.0f, 0.0f, 70.0f, 28.0f, 0.0f, 0.0f},
                        {"huge", LodCriterion::kDistance, 1.0e7f, 1.0e7f, 70.0f, 28.0f, 4.0f, 1.0f},
                        {"v2<v1", LodCriterion::kHorizontalDistance, 50.0f, 5.0f, 70.0f, 28.0f, 0.15f, 0.05f},
                        {"screen 0", LodCriterion::kScreenSize, 0.0f, 0.0f, 0.0f, 0.0f, 0.15f, 0.05f},
                        {"screen huge", LodCriterion::kScreenSize, 0.0f, 0.0f, 1.0e5f, 1.0e5f, 0.15f, 0.05f}};
  for (const Case& c : cases) {
    LodSettings& l = forest.settings().lod;
    l.criterion = c.criterion;
    l.v1 = c.v1;
    l.v2 = c.v2;
    l.s1 = c.s1;
    l.s2 = c.s2;
    l.band = c.band;
    l.hysteresis = c.hysteresis;
    for (double t : {0.0, 3.5, 1.0e7}) {
      const Image pic = testing::render_forest(forest, scene, hurricane, t);
      EXPECT_EQ(non_finite(pic), 0u) << c.name << " t=" << t;
      const ForestStats& st = forest.stats();
      EXPECT_GT(st.visible, 0u) << c.name;
      EXPECT_EQ(st.lod[0] + st.lod[1] + st.lod[2], st.visible + st.transitions) << c.name;
      for (float v : forest.lod_state(0)) EXPECT_TRUE(std::isnan(v) || (v >= 0.0f && v <= 2.0f)) << c.name;
    }
  }
}

// Invariant: 1e6 m from the origin the slices render like at the origin, and a still camera gives
// identical frames (no jitter).
TEST_F(LodForestStability, FarFromTheOriginSlicesDoNotJitter) {
  auto run = [](const glm::dvec3& offset) {
    Forest forest = testing::make_lod_forest(32);
    TreeInstance t;
    t.position = offset;
    EXPECT_TRUE(forest.set_instances(0, {t}).ok());
    testing::force_level(forest, 1);
    auto scene = testing::GlScene::create(64, 64);
    scene.camera.perspective().fov_y = 0.3f;
    scene.camera.set_position(offset + glm::dvec3(0.0, 6.0, 50.0));
    scene.camera.look_at(offset + glm::dvec3(0.0, 6.0, 0.0));
    const WindField wind(WindSettings{.strength = 5.0f});
    Image a = testing::render_forest(forest, scene, wind, 2.0);
    Image b = testing::render_forest(forest, scene, wind, 2.0);
    return std::make_pair(a, b);
  };
  const auto [near_a, near_b] = run(glm::dvec3(0.0));
  const auto [far_a, far_b] = run(glm::dvec3(1.0e6, 0.0, -1.0e6));
  EXPECT_EQ(count_exceeding(near_a, near_b, 0.0f)->pixels, 0u);
  EXPECT_EQ(count_exceeding(far_a, far_b, 0.0f)->pixels, 0u);
  const double diff = share_exceeding(near_a, far_a, 0.1f).value();
  std::printf("1e6 m from the origin: %.2f %% of pixels differ from the same view at the origin\n", 100.0 * diff);
  EXPECT_LT(diff, 0.02);
}

// Invariant: the transition fade dithers the shadow pass of both LOD0 and the slices.
TEST_F(LodForestStability, TransitionFadesDitherShadows) {
  Forest forest = testing::make_lod_forest(32);
  SliceRenderer slices = SliceRenderer::create().value();
  TreeRenderer trees = TreeRenderer::create().value();
  const AnimationGpu rest = rest_animation();
  trees.set_frame(rest, WindGpuParams{});
  slices.set_frame(rest, WindGpuParams{}, 0.0, LodSettings{});
  const TreeMesh& mesh = forest.mesh(0);
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  // Orthographic view from +z over the tree (reversed Z: nearer larger).
  glm::mat4 m(1.0f);
  m[0][0] = 1.0f / 7.0f;
  m[3][0] = -c.x / 7.0f;
  m[1][1] = 1.0f / 7.0f;
  m[3][1] = -c.y / 7.0f;
  m[2][2] = 0.5f / 20.0f;
  m[3][2] = 0.5f;
  render::FramebufferDesc desc;
  desc.width = 96;
  desc.height = 96;
  desc.color_formats = {};
  render::Framebuffer fb = render::Framebuffer::create(desc).value();
  for (int level = 0; level < 2; ++level) {
    std::size_t texels[3] = {0, 0, 0};
    const float fades[3] = {0.0f, 0.5f, 1.0f};
    for (int k = 0; k < 3; ++k) {
      InstanceGpu g = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), glm::vec3(0.0f));
      g.lod.x = fades[k];
      const render::Buffer inst = render::Buffer::immutable(sizeof(InstanceGpu), &g);
      render::apply_reversed_z_state();
      fb.bind();
      fb.clear(glm::vec4(0.0f), 0.0f);
      render::PassStats stats;
      if (level == 0) {
        TreeDrawParams p;
        p.view_proj = m;
        ASSERT_TRUE(trees.draw(render::Pass::kShadow, forest.asset(0), inst, 0, 1, p, stats).ok());
      } else {
        SliceDrawParams p;
        p.view_proj = m;
        p.view_direction = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
        ASSERT_TRUE(slices.draw(render::Pass::kShadow, forest.asset(0), *forest.slices(0), 1, inst, 0, 1, p, stats).ok());
      }
      const Image depth = render::read_depth(fb).value();
      for (float z : depth.data()) texels[k] += z > 0.0f ? 1u : 0u;
    }
    std::printf("%s shadow texels at fade 0 / 0.5 / 1: %zu / %zu / %zu\n", level == 0 ? "LOD0" : "LOD1", texels[0], texels[1],
                texels[2]);
    EXPECT_EQ(texels[0], 0u);
    EXPECT_GT(texels[2], 500u);
    EXPECT_GT(texels[1], texels[2] / 4);
    EXPECT_LT(texels[1], texels[2] * 9 / 10);  // overlapping layers each pass with 1/2
  }
}

}  // namespace
}  // namespace sylva::vegetation
