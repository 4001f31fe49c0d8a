// Full crowns (issue 19): each species preset, seen from the side at 30 m as in the player's
// default view (60 degree lens over 720 rows, 4x MSAA with alpha-to-coverage), covers most of the
// convex hull of its crown silhouette with leaves, and the image-based levels (seed 000 §2.6-2.11)
// keep the crown's covered share and mean colour of LOD0 within the bounds the vegetation README
// states, each level seen at the distance it is used from.
#include <sylva/vegetation/forest.hpp>
#include <sylva/vegetation/tree_renderer.hpp>

#include <sylva/render/testing.hpp>

#include "support/crown_metrics.hpp"
#include "support/gl_scene.hpp"
#include "support/lod_scene.hpp"
#include "support/models.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sylva::vegetation {
namespace {

using CrownGl = render::GlTest;

constexpr SpeciesPreset kPresets[] = {SpeciesPreset::kBroadleaf, SpeciesPreset::kConifer, SpeciesPreset::kBirch,
                                      SpeciesPreset::kShrub};
const char* name_of(SpeciesPreset p) {
  switch (p) {
    case SpeciesPreset::kBroadleaf: return "broadleaf";
    case SpeciesPreset::kConifer: return "conifer";
    case SpeciesPreset::kBirch: return "birch";
    case SpeciesPreset::kShrub: return "shrub";
  }
  return "?";
}

// The player's default view: 720 rows over a 60 degree field of view.
double pixels_per_metre(double distance) { return 720.0 / (2.0 * distance * std::tan(0.5 * 1.0471976)); }

// A square scene just large enough for the tree, from the side (horizontal view) at `distance`
// from the centre of its bounds, with the default view's pixel density.
testing::GlScene side_view(const TreeMesh& mesh, double distance, int samples) {
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  const glm::vec3 e = mesh.bounds_max - mesh.bounds_min;
  const double extent = 1.15 * std::max({e.x, e.y, e.z});
  const int size = std::max(32, static_cast<int>(std::ceil(extent * pixels_per_metre(distance))));
  auto scene = testing::GlScene::create(size, size, samples);
  scene.camera.perspective().fov_y = static_cast<float>(2.0 * std::atan(0.5 * extent / distance));
  scene.camera.set_aspect(size, size);
  scene.camera.set_position(glm::dvec3(c.x, c.y, c.z + distance));
  scene.camera.look_at(glm::dvec3(c));
  return scene;
}

struct Shot {
  Image over_black;
  Image coverage;
};

template <class Draw>
Shot shoot(testing::GlScene& scene, Draw&& draw) {
  Image pictures[2];
  for (int i = 0; i < 2; ++i) {
    scene.clear_color = i == 0 ? glm::vec4(0, 0, 0, 1) : glm::vec4(1, 1, 1, 1);
    pictures[i] = draw();
  }
  return {pictures[0], testing::coverage_from_backgrounds(pictures[0], pictures[1])};
}

TEST_F(CrownGl, CrownHullOfASquareAndOfATriangle) {
  // The metric itself: a filled square is fully closed; a half-filled checkerboard in it half.
  Image square(20, 20, 1);
  Image picture(20, 20, 3);
  for (int y = 5; y < 15; ++y)
    for (int x = 5; x < 15; ++x) {
      square.at(x, y) = ((x + y) % 2 == 0 || x == 5 || x == 14 || y == 5 || y == 14) ? 1.0f : 0.0f;
      picture.at(x, y, 1) = square.at(x, y) * 0.5f;
    }
  const testing::CrownStats s = testing::crown_stats(square, picture);
  EXPECT_EQ(s.hull_pixels, 100.0);
  EXPECT_NEAR(s.closure, (36.0 + 32.0) / 100.0, 1e-9);
  EXPECT_NEAR(s.mean_color.y, 0.5, 1e-6);
  // Three points span a triangle: the hull contains its interior, not the bounding box.
  Image tri(21, 21, 1);
  tri.at(0, 0) = 1.0f;
  tri.at(20, 0) = 1.0f;
  tri.at(0, 20) = 1.0f;
  const Image hull = testing::convex_hull_mask(tri);
  double n = 0.0;
  for (float v : hull.data()) n += v;
  EXPECT_EQ(n, 21.0 * 22.0 / 2.0);
  EXPECT_EQ(hull.at(20, 20), 0.0f);
}

TEST_F(CrownGl, PresetCrownsAreClosedFromTheSideAtThirtyMetres) {
  Result<TreeRenderer> renderer = TreeRenderer::create();
  ASSERT_TRUE(renderer.ok()) << renderer.error().describe();
  for (SpeciesPreset preset : kPresets) {
    const TreeMesh& mesh = testing::preset_mesh(preset);
    testing::TreeOnGpu tree = testing::upload_tree(mesh, preset, {}, 128);
    auto scene = side_view(mesh, 30.0, 4);
    renderer->set_frame(rest_animation(), WindGpuParams{});
    testing::set_instances(tree, {make_instance_gpu(TreeInstance{}, scene.camera.position(), glm::vec3(0.0f))});
    TreeDrawParams params;
    params.view_proj = scene.camera.view_projection();
    params.draw_bark = false;  // leaves only: the crown's leaf cover, not its branches
    const Shot shot = shoot(scene, [&] {
      scene.begin();
      render::PassStats stats;
      EXPECT_TRUE(renderer->draw(render::Pass::kOpaque, tree.asset, tree.instances, 0, 1, params, stats).ok());
      return scene.read();
    });
    const testing::CrownStats st = testing::crown_stats(shot.coverage, shot.over_black);
    std::printf("%-9s at 30 m: %d px square, crown hull %.0f px, leaf-covered %.0f px, closure %.3f\n", name_of(preset),
                scene.target.width(), st.hull_pixels, st.covered, st.closure);
    RecordProperty(std::string("closure_") + name_of(preset), std::to_string(st.closure));
    testing::save_png(shot.over_black, fmt::format("crown30_{}", name_of(preset)));
    ASSERT_GT(st.hull_pixels, 500.0) << name_of(preset);
    // The bound for the two forest species; birch (an open, airy crown) and the shrub are
    // held to what they reach today minus a margin (README).
    const double bound = preset == SpeciesPreset::kBroadleaf || preset == SpeciesPreset::kConifer ? 0.7 : 0.5;
    EXPECT_GE(st.closure, bound) << name_of(preset);
  }
}

TEST_F(CrownGl, SlicesKeepTheCrownsCoverageAndColour) {
  const LodSettings defaults;
  // The sun behind the tree (the render default, back light) and behind the camera (front light).
  const glm::vec3 suns[2] = {render::Lighting{}.sun_direction, glm::normalize(glm::vec3(-0.4f, 0.6f, 0.5f))};
  for (SpeciesPreset preset : kPresets) {
    Forest forest = testing::make_lod_forest(128, preset, 128);
    const WindField calm(WindSettings{.strength = 0.0f, .gust_amplitude = 0.0f, .turbulence_amplitude = 0.0f});
    testing::CrownStats st[3];
    for (int shot_index = 0; shot_index < 4; ++shot_index) {
      const int level = 1 + shot_index % 2;
      const char* light = shot_index < 2 ? "back" : "front";
      // Each level and its LOD0 reference from the distance the level starts at.
      const double d = level == 1 ? defaults.v1 : defaults.v2;
      auto scene = side_view(forest.mesh(0), d, 4);
      scene.lighting.sun_direction = suns[shot_index / 2];
      for (int l : {0, level}) {
        testing::force_level(forest, l);
        const Shot shot = shoot(scene, [&] { return testing::render_forest(forest, scene, calm, 1.0); });
        st[l] = testing::crown_stats(shot.coverage, shot.over_black);
        testing::save_png(shot.over_black, fmt::format("crown_{}_lod{}_at{}_{}", name_of(preset), l, static_cast<int>(d), light));
      }
      const double ratio = st[level].closure / std::max(st[0].closure, 1e-9);
      const glm::dvec3 c0 = st[0].mean_color;
      const glm::dvec3 ck = st[level].mean_color;
      const double lum0 = 0.2126 * c0.r + 0.7152 * c0.g + 0.0722 * c0.b;
      const double lumk = 0.2126 * ck.r + 0.7152 * ck.g + 0.0722 * ck.b;
      const double dc = std::max({std::abs(ck.r - c0.r), std::abs(ck.g - c0.g), std::abs(ck.b - c0.b)});
      std::printf("%-9s %-5s LOD%d at %3.0f m: closure %.3f vs LOD0 %.3f (ratio %.3f); mean colour (%.3f %.3f %.3f) vs "
                  "(%.3f %.3f %.3f), largest channel difference %.3f, luminance ratio %.3f\n",
                  name_of(preset), light, level, d, st[level].closure, st[0].closure, ratio, ck.r, ck.g, ck.b, c0.r, c0.g, c0.b,
                  dc, lumk / std::max(lum0, 1e-9));
      // The README's bounds: closure within 10 %, mean colour within 0.1 per channel (linear)
      // and luminance within -35 % / +20 % (the slices' reduced leaf model: the back-lit conifer
      // at LOD2 is the darkest, README "Full crowns").
      EXPECT_GT(ratio, 0.9) << name_of(preset) << " " << light << " LOD" << level;
      EXPECT_LT(ratio, 1.1) << name_of(preset) << " " << light << " LOD" << level;
      EXPECT_LT(dc, 0.1) << name_of(preset) << " " << light << " LOD" << level;
      EXPECT_GT(lumk / lum0, 0.65) << name_of(preset) << " " << light << " LOD" << level;
      EXPECT_LT(lumk / lum0, 1.2) << name_of(preset) << " " << light << " LOD" << level;
    }
  }
}

}  // namespace
}  // namespace sylva::vegetation
