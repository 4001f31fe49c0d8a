// The backward transform of the slices (seed 000 §2.7, shaders/lib/slices.glsl): with zero wind a
// slice renders its baked image exactly; with wind the slices sway (coherently with LOD0), never
// produce NaN and never put a pixel outside the animated LOD0 tree's bounding box.
#include <sylva/vegetation/forest.hpp>

#include <sylva/core/image_metrics.hpp>
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

using BackwardTransformGl = render::GlTest;

// Orthographic camera-relative matrix looking along -z at the LOD2 slice 0 (normal +z) whose rest
// rectangle fills the viewport exactly, one texel per pixel (reversed Z: nearer is larger).
glm::mat4 slice_view(const SliceLayout& l) {
  glm::mat4 m(1.0f);
  m[0][0] = 1.0f / l.radius;
  m[3][0] = -l.center.x / l.radius;
  m[1][1] = 1.0f / l.half_height;
  m[3][1] = -l.center.y / l.half_height;
  const float zr = 4.0f * l.radius;
  m[2][2] = 0.5f / zr;  // depth = (z - (c - zr)) / 2zr: nearer (larger z) is larger
  m[3][2] = 0.5f - 0.5f * l.center.z / zr;
  return m;
}

Image render_slice(SliceRenderer& r, const Forest& forest, const render::Buffer& inst, const SliceDrawParams& p, int res,
                   const glm::vec4& clear) {
  render::FramebufferDesc desc;
  desc.width = res;
  desc.height = res;
  desc.color_formats = {GL_RGBA32F};
  render::Framebuffer fb = render::Framebuffer::create(desc).value();
  render::apply_reversed_z_state();
  glDisable(GL_MULTISAMPLE);
  fb.bind();
  fb.clear(clear, 0.0f);
  render::PassStats stats;
  EXPECT_TRUE(r.draw(render::Pass::kOpaque, forest.asset(0), *forest.slices(0), 2, inst, 0, 1, p, stats).ok());
  return render::read_color(fb).value();
}

// LOD2 slice 0 of a 64-texel test forest drawn face-on, one texel per pixel, under a sun without
// fog, alpha-tested, over magenta: the stage of the slice tests below.
struct SliceStage {
  Forest forest = testing::make_lod_forest(64);
  SliceRenderer renderer = SliceRenderer::create().value();
  render::LightingUniforms lighting = render::LightingUniforms::create();
  int res = forest.baked(0)->lod[1].images.resolution;
  SliceDrawParams params;
  glm::vec4 clear{1.0f, 0.0f, 1.0f, 1.0f};

  SliceStage() {
    render::Lighting light;
    light.fog_density = 0.0f;
    lighting.update(light, 0.0, 0.0);
    lighting.bind();
    params.view_proj = slice_view(forest.slices(0)->layout(2));
    params.view_direction = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
    params.shading.alpha_mode = AlphaMode::kAlphaTest;
  }
  Image draw(const render::Buffer& inst, const SliceDrawParams& p) { return render_slice(renderer, forest, inst, p, res, clear); }
};

TEST_F(BackwardTransformGl, ZeroWindRendersTheBakedSliceExactly) {
  SliceStage stage;
  const Forest& forest = stage.forest;
  const int res = stage.res;
  // Calm wind: the instance's wind is zero, so the transform is the identity.
  InstanceGpu g = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), glm::vec3(0.0f));
  const render::Buffer inst = render::Buffer::immutable(sizeof(InstanceGpu), &g);
  AnimationSettings anim;
  stage.renderer.set_frame(make_animation_gpu(anim, 5.0), WindGpuParams{}, 5.0, LodSettings{});
  const Image animated = stage.draw(inst, stage.params);
  // The same picture from the static program (no transform compiled in) at another time.
  SliceDrawParams ps = stage.params;
  ps.level = AnimationLevel::kStatic;
  stage.renderer.set_frame(make_animation_gpu(anim, 123.0), WindGpuParams{}, 123.0, LodSettings{});
  const Image still = stage.draw(inst, ps);
  testing::save_png(animated, "slice_zero_wind");
  ASSERT_EQ(animated.data().size(), still.data().size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < animated.data().size(); ++i) differ += animated.data()[i] != still.data()[i] ? 1u : 0u;
  EXPECT_EQ(differ, 0u) << "zero wind must not move a single pixel";
  // Coverage is exactly the baked alpha of slice 0, texel for texel (rows bottom-up in both).
  const SliceImages& im = forest.baked(0)->lod[1].images;
  std::size_t covered = 0, mismatched = 0;
  for (int y = 0; y < res; ++y)
    for (int x = 0; x < res; ++x) {
      const bool baked = im.color[static_cast<std::size_t>(y * res + x) * 4 + 3] >= 128;
      const int row = res - 1 - y;  // Image rows are top-down
      const bool drawn = !(animated.at(x, row, 0) == 1.0f && animated.at(x, row, 1) == 0.0f && animated.at(x, row, 2) == 1.0f);
      covered += baked ? 1u : 0u;
      mismatched += baked != drawn ? 1u : 0u;
    }
  std::printf("slice 0: %zu covered texels, %zu pixels differ from the baked coverage\n", covered, mismatched);
  EXPECT_GT(covered, 200u);
  EXPECT_EQ(mismatched, 0u);
}

// Seed 000 Tab. 5.5's animation levels reach the image-based LODs: under a storm, the slice drawn
// with each level of vegetation.forest.animation_level (static, + trunk, + main branches, +
// leaves) differs from the one before it, and the static program does not move at all.
TEST_F(BackwardTransformGl, EachAnimationLevelAddsMotionToTheSlices) {
  SliceStage stage;
  const WindField storm(WindSettings{.direction_deg = 30.0f, .strength = 28.0f, .gust_amplitude = 10.0f, .turbulence_amplitude = 4.0f});
  const double t = 3.7;
  AnimationSettings anim;
  const InstanceGpu g = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), storm, t, anim);
  const render::Buffer inst = render::Buffer::immutable(sizeof(InstanceGpu), &g);
  stage.renderer.set_frame(make_animation_gpu(anim, t), storm.frame(t, glm::dvec3(0.0)).gpu, t, LodSettings{});
  const int res = stage.res;
  std::vector<Image> pictures;
  for (AnimationLevel level : {AnimationLevel::kStatic, AnimationLevel::kTrunk, AnimationLevel::kBranches, AnimationLevel::kLeaves}) {
    SliceDrawParams p = stage.params;
    p.level = level;
    pictures.push_back(stage.draw(inst, p));
  }
  const auto differing = [](const Image& a, const Image& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.data().size(); i += 4) {
      bool d = false;
      for (std::size_t c = 0; c < 3; ++c) d = d || std::abs(a.data()[i + c] - b.data()[i + c]) > 1e-3f;
      n += d ? 1u : 0u;
    }
    return n;
  };
  const std::size_t trunk = differing(pictures[1], pictures[0]), branches = differing(pictures[2], pictures[1]),
                    leaves = differing(pictures[3], pictures[2]);
  const std::size_t whole = differing(pictures[3], pictures[0]);
  std::printf("slice pixels changed by + trunk %zu, + main branches %zu, + leaves %zu; full against static %zu of %d\n",
              trunk, branches, leaves, whole, res * res);
  EXPECT_GT(trunk, 50u) << "the trunk's bend moves the slice";
  EXPECT_GT(branches, 50u) << "the level-1 branches add their own sway";
  EXPECT_GT(leaves, 50u) << "the leaves add their displacement";
  EXPECT_GE(whole, trunk);
}

// Screen rectangle [min, max] in pixels of the camera-relative box corners.
glm::vec4 screen_box(const render::Camera& cam, glm::vec3 lo, glm::vec3 hi, int w, int h) {
  glm::vec4 out(1e9f, 1e9f, -1e9f, -1e9f);
  const glm::mat4 vp = cam.view_projection();
  for (int k = 0; k < 8; ++k) {
    const glm::vec3 p((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
    const glm::vec4 c = vp * glm::vec4(cam.to_relative(glm::dvec3(p)), 1.0f);
    const float x = (c.x / c.w * 0.5f + 0.5f) * static_cast<float>(w);
    const float y = (0.5f - c.y / c.w * 0.5f) * static_cast<float>(h);  // image rows top-down
    out = glm::vec4(std::min(out.x, x), std::min(out.y, y), std::max(out.z, x), std::max(out.w, y));
  }
  return out;
}

TEST_F(BackwardTransformGl, WindSwaysSlicesWithinTheAnimatedLod0BoundsWithoutNaN) {
  Forest forest = testing::make_lod_forest(64);
  auto scene = testing::GlScene::create(112, 112);
  render::FramebufferDesc desc;
  desc.width = 112;
  desc.height = 112;
  desc.color_formats = {GL_RGBA32F};
  scene.target = render::Framebuffer::create(desc).value();
  scene.clear_color = {1.0f, 0.0f, 1.0f, 1.0f};
  const TreeMesh& mesh = forest.mesh(0);
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  scene.camera.perspective().fov_y = 0.3f;
  const WindField calm(WindSettings{.strength = 0.0f, .gust_amplitude = 0.0f, .turbulence_amplitude = 0.0f});
  const WindField storm(WindSettings{.direction_deg = 30.0f, .strength = 28.0f, .gust_amplitude = 10.0f, .turbulence_amplitude = 4.0f});
  std::size_t outside_total = 0, nan_total = 0;
  double moved_max = 0.0;
  for (int lod = 1; lod <= 2; ++lod) {
    testing::force_level(forest, lod);
    for (float az : {0.4f, 2.1f}) {
      const double d = 55.0;
      scene.camera.set_position(glm::dvec3(c.x + d * std::sin(az), c.y + 4.0, c.z + d * std::cos(az)));
      scene.camera.look_at(glm::dvec3(c));
      const Image still = testing::render_forest(forest, scene, calm, 3.0);
      for (double t : {1.0, 3.7, 9.2}) {
        const Image pic = testing::render_forest(forest, scene, storm, t);
        // The animated LOD0 tree at the same time: CPU reference deformation of every vertex.
        const AnimationGpu anim = make_animation_gpu(forest.settings().animation, t);
        const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), storm, t, forest.settings().animation);
        const WindGpuParams wind = storm.frame(t, glm::dvec3(0.0)).gpu;
        glm::vec3 lo(1e9f), hi(-1e9f);
        for (const BranchVertex& v : mesh.branch_vertices) {
          const glm::vec3 p = deform_branch_vertex(mesh.data, anim, inst, v).position;
          lo = glm::min(lo, p);
          hi = glm::max(hi, p);
        }
        for (const LeafVertex& v : mesh.leaf_vertices) {
          const glm::vec3 p = deform_leaf_vertex(mesh.data, anim, inst, wind, v).position;
          lo = glm::min(lo, p);
          hi = glm::max(hi, p);
        }
        const glm::vec4 box = screen_box(scene.camera, lo, hi, pic.width(), pic.height());
        std::size_t outside = 0, nan = 0, drawn = 0;
        for (int y = 0; y < pic.height(); ++y)
          for (int x = 0; x < pic.width(); ++x) {
            bool bad = false;
            for (int ch = 0; ch < 4; ++ch) bad = bad || !std::isfinite(pic.at(x, y, ch));
            nan += bad ? 1u : 0u;
            const bool fg = !(pic.at(x, y, 0) == 1.0f && pic.at(x, y, 1) == 0.0f && pic.at(x, y, 2) == 1.0f);
            if (!fg) continue;
            ++drawn;
            // One pixel of tolerance for rasterisation at the box edge.
            if (x + 1.0f < box.x || x > box.z + 1.0f || y + 1.0f < box.y || y > box.w + 1.0f) ++outside;
          }
        const Result<double> moved = share_exceeding(still, pic, 0.1f);
        moved_max = std::max(moved_max, *moved);
        std::printf("LOD%d az %.1f t %.1f: %zu px drawn, %zu outside the animated LOD0 box, %zu NaN, %.1f %% changed\n", lod, az, t,
                    drawn, outside, nan, 100.0 * *moved);
        EXPECT_GT(drawn, 300u);
        outside_total += outside;
        nan_total += nan;
        if (t == 3.7) testing::save_png(pic, fmt::format("slices_wind_lod{}_az{}", lod, static_cast<int>(az * 10)));
      }
    }
  }
  EXPECT_EQ(nan_total, 0u);
  EXPECT_EQ(outside_total, 0u);
  EXPECT_GT(moved_max, 0.02) << "the slices must sway in the wind";
}

}  // namespace
}  // namespace sylva::vegetation
