// Close trees and the image-based levels (editor report: "a tree close to the camera showed a dark
// triangle and green shards" in a large viewport). Invariants:
//  - a tree within v1 of the camera is drawn at LOD0 only (no slice fragments: the picture equals
//    the LOD-off picture bit for bit), from eye heights below, level with and above the crown;
//  - slices seen from inside or next to their bounds (camera 0.5..4 m from the centre, LOD1 and
//    LOD2 forced) render finite pixels and nothing outside the LOD0 tree's screen bounding box.
// Rendered at 480x270 so the per-pixel cost stays small on llvmpipe; the geometry is the same at
// any viewport size.
#include <sylva/vegetation/forest.hpp>

#include <sylva/core/wind.hpp>
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"
#include "support/lod_scene.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace sylva::vegetation {
namespace {

using LodCloseGl = render::GlTest;

constexpr int kWidth = 480;
constexpr int kHeight = 270;

std::size_t non_finite(const Image& img) {
  std::size_t n = 0;
  for (float v : img.data()) n += std::isfinite(v) ? 0u : 1u;
  return n;
}

struct Box {
  int x0 = kWidth, y0 = kHeight, x1 = -1, y1 = -1;
  bool empty() const { return x1 < x0; }
};

Box bounds(const Image& mask) {
  Box b;
  for (int y = 0; y < mask.height(); ++y)
    for (int x = 0; x < mask.width(); ++x)
      if (mask.at(x, y, 0) > 0.5f) {
        b.x0 = std::min(b.x0, x);
        b.y0 = std::min(b.y0, y);
        b.x1 = std::max(b.x1, x);
        b.y1 = std::max(b.y1, y);
      }
  return b;
}

// Foreground pixels outside `box` grown by `pad` pixels.
std::size_t outside(const Image& mask, const Box& box, int pad) {
  std::size_t n = 0;
  for (int y = 0; y < mask.height(); ++y)
    for (int x = 0; x < mask.width(); ++x)
      if (mask.at(x, y, 0) > 0.5f && (x < box.x0 - pad || x > box.x1 + pad || y < box.y0 - pad || y > box.y1 + pad)) ++n;
  return n;
}

testing::GlScene float_scene() {
  auto scene = testing::GlScene::create(kWidth, kHeight);
  render::FramebufferDesc desc;
  desc.width = kWidth;
  desc.height = kHeight;
  desc.color_formats = {GL_RGBA32F};
  scene.target = render::Framebuffer::create(desc).value();
  return scene;
}

struct Eye {
  const char* name;
  glm::dvec3 position;
};

// Invariant: within v1 a tree is LOD0 only (stats and pixels), whatever the eye height.
TEST_F(LodCloseGl, TreeWithinV1IsDrawnAsLod0Only) {
  Forest forest = testing::make_lod_forest(32);
  auto scene = float_scene();
  const WindField wind(WindSettings{.strength = 6.0f});
  const TreeMesh& mesh = forest.mesh(0);
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  const double h = static_cast<double>(mesh.bounds_max.y - mesh.bounds_min.y);
  const Eye eyes[] = {{"ground 3 m", {0.0, 0.3, 3.0}},
                      {"eye 6 m", {1.5, 1.7, 6.0}},
                      {"crown 4 m", {-2.0, static_cast<double>(c.y), 4.0}},
                      {"above 8 m", {2.0, h + 6.0, 3.0}},
                      {"below the crown 2 m", {0.5, 0.5, 1.5}}};
  for (const Eye& e : eyes) {
    SCOPED_TRACE(e.name);
    scene.camera.set_position(e.position);
    scene.camera.look_at(glm::dvec3(c));
    testing::force_level(forest, -1);  // the default thresholds (v1 = 45 m)
    const Image natural = testing::render_forest(forest, scene, wind, 2.0);
    const ForestStats& st = forest.stats();
    EXPECT_EQ(st.lod[1], 0u);
    EXPECT_EQ(st.lod[2], 0u);
    EXPECT_EQ(st.transitions, 0u);
    testing::force_level(forest, 0);
    const Image lod0 = testing::render_forest(forest, scene, wind, 2.0);
    ASSERT_EQ(natural.data().size(), lod0.data().size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < lod0.data().size(); ++i) differ += natural.data()[i] != lod0.data()[i] ? 1u : 0u;
    EXPECT_EQ(differ, 0u) << "slice fragments in a LOD0-only view";
    EXPECT_GT(testing::share(testing::foreground(lod0, scene.clear_color)), 0.01);
  }
}

// Invariant: with LOD1 or LOD2 forced by the thresholds, a camera inside or right next to the
// slice cluster (within 1.5 bounding radii of the centre) still gets the LOD0 tree: no slice
// fragments, finite pixels, nothing outside the LOD0 tree's screen box (the picture is LOD0's).
// Just beyond that the slices are drawn, finite, and stay within the LOD0 box grown by 8 % of the
// view (the parallax bound and per-fragment direction pick; before the fix whole quads of streaks).
TEST_F(LodCloseGl, CameraInsideOrNearSliceBoundsStaysInsideLod0Box) {
  Forest forest = testing::make_lod_forest(32);
  auto scene = float_scene();
  const WindField wind(WindSettings{.strength = 6.0f});
  const TreeMesh& mesh = forest.mesh(0);
  const glm::vec3 c = 0.5f * (mesh.bounds_min + mesh.bounds_max);
  const double r = 0.5 * static_cast<double>(glm::length(mesh.bounds_max - mesh.bounds_min));
  const double cy = static_cast<double>(c.y);
  struct Case {
    const char* name;
    glm::dvec3 offset;  // from the centre, in bounding radii
  };
  const Case cases[] = {{"inside crown", {0.1, 0.0, 0.05}},     {"inside low", {0.1, -0.6, 0.2}},
                        {"edge of the box", {0.0, 0.0, 0.7}},   {"next to it, low", {0.7, -0.5, 1.0}},
                        {"next to it, above", {0.2, 1.3, 0.3}}, {"outside, 3 radii", {1.2, 0.2, 2.7}},
                        {"outside, 2.5 radii, low", {1.0, -0.4, 2.25}}};
  int index = 0;
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    const glm::dvec3 eye = glm::dvec3(c.x, cy, c.z) + r * k.offset;
    const bool guarded = glm::length(r * k.offset) < 1.5 * r;
    scene.camera.set_position(eye);
    // Look past the centre so the view also holds the far side of the cluster.
    scene.camera.look_at(glm::dvec3(c.x, cy, c.z) - 0.5 * r * glm::dvec3(k.offset.x, 0.0, k.offset.z));
    testing::force_level(forest, 0);
    const Image lod0 = testing::render_forest(forest, scene, wind, 1.0);
    const Box box = bounds(testing::foreground(lod0, scene.clear_color));
    for (int level = 1; level <= 2; ++level) {
      SCOPED_TRACE(level);
      testing::force_level(forest, level);
      const Image img = testing::render_forest(forest, scene, wind, 1.0);
      const ForestStats& st = forest.stats();
      EXPECT_EQ(non_finite(img), 0u);
      const Image mask = testing::foreground(img, scene.clear_color);
      const std::size_t drawn = static_cast<std::size_t>(std::lround(testing::share(mask) * kWidth * kHeight));
      const std::size_t out = box.empty() ? drawn : outside(mask, box, kWidth / 12);
      std::printf("%s (%.2f radii) LOD%d forced: drawn LOD0/1/2 = %zu/%zu/%zu, %zu px outside the LOD0 box\n", k.name,
                  glm::length(k.offset), level, st.lod[0], st.lod[1], st.lod[2], out);
      if (guarded) {
        EXPECT_EQ(st.lod[0], 1u);
        EXPECT_EQ(st.lod[static_cast<std::size_t>(level)], 0u);
        std::size_t differ = 0;
        for (std::size_t i = 0; i < lod0.data().size(); ++i) differ += img.data()[i] != lod0.data()[i] ? 1u : 0u;
        EXPECT_EQ(differ, 0u) << "slice fragments with the camera inside the cluster";
      } else {
        EXPECT_EQ(st.lod[static_cast<std::size_t>(level)], 1u);
        EXPECT_GT(drawn, 100u);
      }
      EXPECT_EQ(out, 0u);
      if (out > 0) testing::save_png(img, "lod_close_" + std::to_string(index) + "_lod" + std::to_string(level));
    }
    ++index;
  }
}

}  // namespace
}  // namespace sylva::vegetation
