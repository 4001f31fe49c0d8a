// The vertex shaders against the CPU reference of the animation (positions and normals captured
// from the very programs that draw), the same deformation in the colour and the depth pass, and
// the rest pose on the GPU.
#include <sylva/vegetation/tree_renderer.hpp>

#include <sylva/core/wind.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"
#include "support/models.hpp"

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sylva::vegetation {
namespace {

using TreeAnimationGl = render::GlTest;

struct FrameSetup {
  AnimationGpu anim;
  WindGpuParams wind;
  InstanceGpu instance;
};

FrameSetup make_setup(double time, const glm::vec3& wind_world, bool transport, float time_offset) {
  AnimationSettings s;
  s.frame_transport = transport;
  TreeInstance ti;
  ti.position = {20.0, 1.0, -30.0};
  ti.yaw = 0.7f;
  ti.scale = 1.1f;
  ti.time_offset = time_offset;
  const glm::dvec3 camera(15.0, 3.0, -10.0);
  WindField field(WindSettings{.strength = 9.0f, .turbulence_amplitude = 2.0f});
  return {make_animation_gpu(s, time), field.frame(time, camera).gpu, make_instance_gpu(ti, camera, wind_world)};
}

struct Diff {
  float position = 0.0f;
  float normal = 0.0f;
};

Diff compare(const std::vector<glm::vec4>& gpu, const std::vector<glm::vec3>& cpu_pos, const std::vector<glm::vec3>& cpu_n) {
  Diff d;
  for (std::size_t i = 0; i < cpu_pos.size(); ++i) {
    d.position = std::max(d.position, glm::length(glm::vec3(gpu[2 * i]) - cpu_pos[i]));
    d.normal = std::max(d.normal, glm::length(glm::vec3(gpu[2 * i + 1]) - cpu_n[i]));
  }
  return d;
}

TEST_F(TreeAnimationGl, VertexShadersMatchTheCpuReference) {
  Result<TreeRenderer> renderer = TreeRenderer::create();
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  for (SpeciesPreset preset : {SpeciesPreset::kBroadleaf, SpeciesPreset::kConifer}) {
    testing::TreeOnGpu tree = testing::upload_tree(testing::preset_mesh(preset), preset);
    const float size = glm::length(tree.mesh.bounds_max - tree.mesh.bounds_min);
    for (bool transport : {true, false}) {
      for (const glm::vec3& w : {glm::vec3(0.0f), glm::vec3(6.0f, 0.0f, 3.0f), glm::vec3(-60.0f, 5.0f, 40.0f)}) {
        const FrameSetup st = make_setup(1234.567, w, transport, 13.0f);
        testing::set_instances(tree, {st.instance});
        renderer->set_frame(st.anim, st.wind);
        auto scene = testing::GlScene::create(64, 64);
        scene.begin();
        TreeDrawParams params;
        params.view_proj = scene.camera.view_projection();
        Result<std::vector<glm::vec4>> bark = renderer->capture(render::Pass::kOpaque, tree.asset, tree.instances, 0, params, false);
        Result<std::vector<glm::vec4>> leaves = renderer->capture(render::Pass::kOpaque, tree.asset, tree.instances, 0, params, true);
        ASSERT_TRUE(bark.ok() && leaves.ok());
        std::vector<glm::vec3> bp, bn, lp, ln;
        for (const BranchVertex& v : tree.mesh.branch_vertices) {
          const DeformedVertex d = deform_branch_vertex(tree.mesh.data, st.anim, st.instance, v);
          bp.push_back(d.position);
          bn.push_back(d.normal);
        }
        for (const LeafVertex& v : tree.mesh.leaf_vertices) {
          const DeformedVertex d = deform_leaf_vertex(tree.mesh.data, st.anim, st.instance, st.wind, v);
          lp.push_back(d.position);
          ln.push_back(d.normal);
        }
        const Diff db = compare(*bark, bp, bn);
        const Diff dl = compare(*leaves, lp, ln);
        std::printf("preset %d transport %d wind %.0f: max |GPU - CPU| bark %.3g m / normal %.3g, leaves %.3g m / normal %.3g\n",
                    static_cast<int>(preset), transport ? 1 : 0, static_cast<double>(glm::length(w)),
                    static_cast<double>(db.position), static_cast<double>(db.normal), static_cast<double>(dl.position),
                    static_cast<double>(dl.normal));
        EXPECT_LT(db.position, 2e-6f * size + 1e-5f);
        EXPECT_LT(dl.position, 2e-6f * size + 1e-5f);
        EXPECT_LT(db.normal, 1e-4f);
        EXPECT_LT(dl.normal, 1e-4f);
        if (w == glm::vec3(0.0f)) {
          // Rest pose on the GPU: the stored rest positions.
          float rest = 0.0f;
          for (std::size_t i = 0; i < tree.mesh.branch_vertices.size(); ++i)
            rest = std::max(rest, glm::length(glm::vec3((*bark)[2 * i]) - tree.mesh.branch_vertices[i].position));
          for (std::size_t i = 0; i < tree.mesh.leaf_vertices.size(); ++i)
            rest = std::max(rest, glm::length(glm::vec3((*leaves)[2 * i]) - tree.mesh.leaf_vertices[i].position));
          EXPECT_LT(rest, 2e-6f * size + 1e-5f);
        }
      }
    }
  }
}

// The trunk-only level (seed table 5.5: "+ trunk") moves everything above the trunk rigidly; it
// equals the CPU chain with every other level and the leaves switched off.
TEST_F(TreeAnimationGl, TrunkOnlyLevelMatchesTheChainWithUpperLevelsOff) {
  Result<TreeRenderer> renderer = TreeRenderer::create();
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  testing::TreeOnGpu tree = testing::upload_tree(testing::preset_mesh(SpeciesPreset::kBroadleaf), SpeciesPreset::kBroadleaf);
  AnimationSettings s;
  s.level1.enabled = s.level2.enabled = s.level3.enabled = false;
  s.leaves_enabled = false;
  const AnimationGpu anim = make_animation_gpu(s, 21.0);
  const InstanceGpu inst = make_instance_gpu(TreeInstance{}, glm::dvec3(0.0), glm::vec3(30.0f, 0.0f, 12.0f));
  const WindGpuParams wind = WindField().frame(21.0).gpu;
  testing::set_instances(tree, {inst});
  // The GPU gets the full settings: the trunk-only program ignores the other levels itself.
  renderer->set_frame(make_animation_gpu(AnimationSettings{}, 21.0), wind);
  auto scene = testing::GlScene::create(32, 32);
  scene.begin();
  TreeDrawParams params;
  params.view_proj = scene.camera.view_projection();
  params.level = AnimationLevel::kTrunk;
  Result<std::vector<glm::vec4>> bark = renderer->capture(render::Pass::kOpaque, tree.asset, tree.instances, 0, params, false);
  Result<std::vector<glm::vec4>> leaves = renderer->capture(render::Pass::kOpaque, tree.asset, tree.instances, 0, params, true);
  ASSERT_TRUE(bark.ok() && leaves.ok());
  float worst = 0.0f;
  float moved = 0.0f;
  for (std::size_t i = 0; i < tree.mesh.branch_vertices.size(); ++i) {
    const BranchVertex& v = tree.mesh.branch_vertices[i];
    const glm::vec3 cpu = deform_branch_vertex(tree.mesh.data, anim, inst, v).position;
    worst = std::max(worst, glm::length(glm::vec3((*bark)[2 * i]) - cpu));
    moved = std::max(moved, glm::length(cpu - v.position));
  }
  for (std::size_t i = 0; i < tree.mesh.leaf_vertices.size(); ++i) {
    const LeafVertex& v = tree.mesh.leaf_vertices[i];
    worst = std::max(worst, glm::length(glm::vec3((*leaves)[2 * i]) - deform_leaf_vertex(tree.mesh.data, anim, inst, wind, v).position));
  }
  EXPECT_GT(moved, 0.05f);
  EXPECT_LT(worst, 2e-5f);
  std::printf("trunk-only level: max |GPU rigid - CPU chain| %.3g m (largest displacement %.3g m)\n",
              static_cast<double>(worst), static_cast<double>(moved));
}

TEST_F(TreeAnimationGl, DepthPassDeformsExactlyLikeTheColourPass) {
  Result<TreeRenderer> renderer = TreeRenderer::create();
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  testing::TreeOnGpu tree = testing::upload_tree(testing::preset_mesh(SpeciesPreset::kBirch), SpeciesPreset::kBirch);
  auto scene = testing::GlScene::create(128, 128);
  const glm::vec3 c = 0.5f * (tree.mesh.bounds_min + tree.mesh.bounds_max);
  scene.camera.set_position(glm::dvec3(c.x + 3.0f, c.y, c.z + 16.0f));
  scene.camera.look_at(glm::dvec3(c));
  AnimationSettings anim;
  TreeInstance ti;
  ti.time_offset = 3.0f;
  const WindField wind(WindSettings{.strength = 14.0f});
  renderer->set_frame(make_animation_gpu(anim, 77.0), wind.frame(77.0, scene.camera.position()).gpu);
  testing::set_instances(tree, {make_instance_gpu(ti, scene.camera.position(), wind, 77.0, anim)});
  TreeDrawParams params;
  params.view_proj = scene.camera.view_projection();
  params.shading.alpha_mode = AlphaMode::kAlphaTest;
  for (bool leaves : {false, true}) {
    scene.begin();
    Result<std::vector<glm::vec4>> colour = renderer->capture(render::Pass::kOpaque, tree.asset, tree.instances, 0, params, leaves);
    Result<std::vector<glm::vec4>> depth = renderer->capture(render::Pass::kShadow, tree.asset, tree.instances, 0, params, leaves);
    ASSERT_TRUE(colour.ok() && depth.ok());
    float worst = 0.0f;
    for (std::size_t i = 0; i < colour->size(); i += 2) worst = std::max(worst, glm::length(glm::vec3((*colour)[i] - (*depth)[i])));
    EXPECT_EQ(worst, 0.0f) << (leaves ? "leaves" : "bark");
  }
  // The depth buffers of the two passes agree pixel for pixel.
  render::PassStats stats;
  scene.begin();
  ASSERT_TRUE(renderer->draw(render::Pass::kOpaque, tree.asset, tree.instances, 0, 1, params, stats).ok());
  const Image colour_depth = render::read_depth(scene.target).value();
  testing::save_png(scene.read(), "depth_vs_colour_colour");
  scene.begin();
  ASSERT_TRUE(renderer->draw(render::Pass::kShadow, tree.asset, tree.instances, 0, 1, params, stats).ok());
  const Image shadow_depth = render::read_depth(scene.target).value();
  std::size_t covered = 0;
  float worst = 0.0f;
  for (std::size_t i = 0; i < colour_depth.data().size(); ++i) {
    covered += colour_depth.data()[i] > 0.0f ? 1u : 0u;
    worst = std::max(worst, std::fabs(colour_depth.data()[i] - shadow_depth.data()[i]));
  }
  EXPECT_GT(covered, 500u);
  EXPECT_EQ(worst, 0.0f);
  EXPECT_EQ(stats.draw_calls, 4u);
}

}  // namespace
}  // namespace sylva::vegetation
