// Renders every preset at LOD0 (calm and windy) and checks the pictures are plausible: the tree
// covers a reasonable part of the frame, leaves are green in summer, wind moves the crown.
#include <sylva/vegetation/tree_renderer.hpp>

#include <sylva/core/image_metrics.hpp>
#include <sylva/core/wind.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"
#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace sylva::vegetation {
namespace {

using TreeRenderGl = render::GlTest;

// Frames the tree: camera on +z looking at the crown centre from a distance that fits its height.
void frame_tree(testing::GlScene& scene, const TreeMesh& mesh, float distance_factor = 1.0f) {
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  const float h = mesh.bounds_max.y - mesh.bounds_min.y;
  const float d = distance_factor * 1.1f * h / (2.0f * std::tan(0.5f * scene.camera.perspective().fov_y));
  scene.camera.set_position(glm::dvec3(c.x, c.y, c.z + d));
  scene.camera.look_at(glm::dvec3(c));
}

TEST_F(TreeRenderGl, PresetsRenderAsTrees) {
  Result<TreeRenderer> renderer = TreeRenderer::create();
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  const char* names[] = {"broadleaf", "conifer", "birch", "shrub"};
  for (SpeciesPreset preset : {SpeciesPreset::kBroadleaf, SpeciesPreset::kConifer, SpeciesPreset::kBirch, SpeciesPreset::kShrub}) {
    testing::TreeOnGpu tree = testing::upload_tree(testing::preset_mesh(preset), preset);
    auto scene = testing::GlScene::create(192, 192, 4);
    scene.clear_color = {0.55f, 0.7f, 0.9f, 1.0f};
    frame_tree(scene, tree.mesh);
    Image pictures[2];
    for (int windy = 0; windy < 2; ++windy) {
      const double t = 3.0;
      WindField wind(WindSettings{.strength = windy ? 14.0f : 0.0f, .gust_amplitude = windy ? 6.0f : 0.0f,
                                  .turbulence_amplitude = windy ? 2.0f : 0.0f});
      AnimationSettings anim;
      renderer->set_frame(make_animation_gpu(anim, t), wind.frame(t, scene.camera.position()).gpu);
      testing::set_instances(tree, {make_instance_gpu(TreeInstance{}, scene.camera.position(), wind, t, anim)});
      scene.begin(t);
      TreeDrawParams params;
      params.view_proj = scene.camera.view_projection();
      render::PassStats stats;
      ASSERT_TRUE(renderer->draw(render::Pass::kOpaque, tree.asset, tree.instances, 0, 1, params, stats).ok());
      pictures[windy] = scene.read();
      testing::save_png(pictures[windy], fmt::format("preset_{}_{}", names[static_cast<int>(preset)], windy ? "windy" : "calm"));
    }
    Result<Image> mask = mask_from_background(pictures[0], scene.clear_color, 0.02f);
    ASSERT_TRUE(mask.ok());
    double cover = 0.0;
    for (float v : mask->data()) cover += v;
    cover /= static_cast<double>(mask->pixel_count());
    std::printf("%s: covers %.1f %% of the frame\n", names[static_cast<int>(preset)], 100.0 * cover);
    EXPECT_GT(cover, 0.05) << names[static_cast<int>(preset)];
    EXPECT_LT(cover, 0.9) << names[static_cast<int>(preset)];
    Result<double> moved = share_exceeding(pictures[0], pictures[1], 0.1f);
    ASSERT_TRUE(moved.ok());
    EXPECT_GT(*moved, 0.005) << names[static_cast<int>(preset)] << ": wind should move the crown";
  }
}

}  // namespace
}  // namespace sylva::vegetation
