// Translucent blocks (glass, water, ice; seed 004 §2.2, issue #16): drawn in draw(kTransparent)
// after everything opaque, blended with alpha = texture alpha x opacity, chunks back to front
// and the faces of a chunk back to front, without writing depth, texels below translucent_cutoff
// (the seed's 0.05) discarded.

#include <sylva/render/testing.hpp>
#include <sylva/voxel/block_textures.hpp>
#include <sylva/voxel/mesher.hpp>
#include <sylva/voxel/palette_file.hpp>
#include <sylva/voxel/world.hpp>
#include <sylva/voxel/voxel_renderer.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <tuple>
#include <utility>

#include "support/voxel_gl_scene.hpp"

namespace sylva::voxel {
namespace {

using VoxelTranslucentGl = render::GlTest;

// The standard palette plus translucent slabs: white ("snow") and brown ("dirt") glass at the
// given opacities.
BlockPalette glass_palette(float white_opacity, float brown_opacity) {
  BlockPalette p = builtin_palette().value();
  for (auto [name, texture, opacity] : {std::tuple{"white_glass", TextureId::kSnow, white_opacity},
                                        std::tuple{"brown_glass", TextureId::kDirt, brown_opacity}}) {
    BlockType t;
    t.name = name;
    t.render = RenderClass::kTranslucent;
    t.texture_top = t.texture_side = t.texture_bottom = static_cast<int>(texture);
    t.opacity = opacity;
    EXPECT_TRUE(p.add(t).ok());
  }
  return p;
}

// A 32 x 32 stone floor at y = 0 and 16 x 16 slabs of the named blocks at the given heights
// (y 40 and 70 lie in the chunks above the floor's), meshed; seen straight down from y = 100.
struct Layers {
  const char* block;
  int y;
};
Image render_layers(const BlockPalette& palette, std::initializer_list<Layers> layers, float cutoff = 0.05f,
                    Image* depth = nullptr, VoxelFrameStats* stats = nullptr) {
  World w(palette);
  for (int z = 0; z < 32; ++z)
    for (int x = 0; x < 32; ++x) (void)w.set({x, 0, z}, palette.id("stone"));
  for (const Layers& l : layers) {
    for (int z = 8; z < 24; ++z)
      for (int x = 8; x < 24; ++x) (void)w.set({x, l.y, z}, palette.id(l.block));
  }
  auto mesher = make_mesher(MesherKind::kBitmask);
  (void)w.remesh(*mesher);
  VoxelRenderSettings settings;
  settings.translucent_cutoff = cutoff;
  auto renderer = VoxelRenderer::create(w, nullptr, settings);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(96, 96);
  scene.camera.set_position({16.0, 100.0, 16.01});
  scene.camera.look_at({16.0, 0.0, 16.0});
  scene.render(**renderer);
  if (depth) *depth = scene.depth();
  if (stats) *stats = (*renderer)->frame_stats();
  return scene.color();
}

// Share of the pixels where `a` and `b` differ (the slab's footprint) at which `got` is within
// `tolerance` of `want` in every channel.
struct Match {
  int covered = 0;
  int matching = 0;
};
template <class Want>
Match match(const Image& got, const Image& a, const Image& b, Want want, float tolerance) {
  Match m;
  for (int y = 0; y < got.height(); ++y) {
    for (int x = 0; x < got.width(); ++x) {
      bool differs = false;
      for (int c = 0; c < 3; ++c) differs = differs || std::abs(a.at(x, y, c) - b.at(x, y, c)) > 0.05f;
      if (!differs) continue;
      ++m.covered;
      bool ok = true;
      for (int c = 0; c < 3; ++c) ok = ok && std::abs(got.at(x, y, c) - want(x, y, c)) <= tolerance;
      m.matching += ok ? 1 : 0;
    }
  }
  return m;
}

TEST_F(VoxelTranslucentGl, HalfOpaqueGlassBlendsHalfWithWhatIsBehindAndWritesNoDepth) {
  const BlockPalette solid = glass_palette(1.0f, 1.0f);
  const BlockPalette half = glass_palette(0.5f, 0.5f);
  Image floor_depth, glass_depth;
  const Image floor = render_layers(solid, {}, 0.05f, &floor_depth);
  const Image glass = render_layers(solid, {{"white_glass", 40}});
  VoxelFrameStats stats;
  const Image blended = render_layers(half, {{"white_glass", 40}}, 0.05f, &glass_depth, &stats);
  EXPECT_GT(stats.translucent_quads_drawn, 0u);
  const Match m = match(blended, floor, glass,
                        [&](int x, int y, int c) { return 0.5f * glass.at(x, y, c) + 0.5f * floor.at(x, y, c); }, 0.02f);
  EXPECT_GT(m.covered, 400) << "the slab's footprint, 60 blocks below the camera";
  EXPECT_GE(m.matching, m.covered * 99 / 100) << m.matching << " of " << m.covered;
  std::printf("half glass: %d of %d footprint pixels are the half blend\n", m.matching, m.covered);
  // Depth is the floor's: translucent faces do not hide what is drawn after them.
  int same_depth = 0;
  for (std::size_t i = 0; i < floor_depth.data().size(); ++i) same_depth += floor_depth.data()[i] == glass_depth.data()[i];
  EXPECT_EQ(same_depth, static_cast<int>(floor_depth.data().size()));
}

TEST_F(VoxelTranslucentGl, ChunksBlendBackToFront) {
  // White glass at y 70 (chunk y 2) over brown glass at y 40 (chunk y 1), both half opaque:
  // back to front gives 0.5 white + 0.25 brown + 0.25 floor; front to back would give
  // 0.5 brown + 0.25 white + 0.25 floor.
  const BlockPalette solid = glass_palette(1.0f, 1.0f);
  const Image floor = render_layers(solid, {});
  const Image white = render_layers(solid, {{"white_glass", 70}});
  const Image brown = render_layers(solid, {{"brown_glass", 40}});
  const Image both = render_layers(glass_palette(0.5f, 0.5f), {{"white_glass", 70}, {"brown_glass", 40}});
  const Match right = match(both, floor, white, [&](int x, int y, int c) {
    return 0.5f * white.at(x, y, c) + 0.25f * brown.at(x, y, c) + 0.25f * floor.at(x, y, c);
  }, 0.02f);
  const Match wrong = match(both, floor, white, [&](int x, int y, int c) {
    return 0.5f * brown.at(x, y, c) + 0.25f * white.at(x, y, c) + 0.25f * floor.at(x, y, c);
  }, 0.02f);
  EXPECT_GT(right.covered, 1500) << "the upper slab's footprint, 30 blocks below the camera";
  EXPECT_GE(right.matching, right.covered * 95 / 100) << right.matching << " of " << right.covered;
  EXPECT_LT(wrong.matching, wrong.covered / 10) << wrong.matching << " of " << wrong.covered;
  std::printf("two layers: back to front %d, front to back %d of %d\n", right.matching, wrong.matching, right.covered);
}

// 16 x 16 vertical panes of the named blocks at the given z (Layers::y holds z), all in chunk
// (0, 0, 0), on a stone wall at z = 0 .. 1 behind them; seen along z from `eye`.
Image render_panes(const BlockPalette& palette, std::initializer_list<Layers> panes, glm::dvec3 eye,
                   VoxelFrameStats* stats = nullptr) {
  World w(palette);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) (void)w.set({x, y, eye.z > 0.0 ? 0 : 31}, palette.id("stone"));
  for (const Layers& l : panes) {
    for (int y = 8; y < 24; ++y)
      for (int x = 8; x < 24; ++x) (void)w.set({x, y, l.y}, palette.id(l.block));
  }
  auto mesher = make_mesher(MesherKind::kBitmask);
  (void)w.remesh(*mesher);
  auto renderer = VoxelRenderer::create(w, nullptr, VoxelRenderSettings{});
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  auto scene = testing::VoxelGlScene::create(96, 96);
  scene.camera.set_position(eye);
  scene.camera.look_at({16.0, 16.0, 16.0});
  scene.render(**renderer);
  if (stats) *stats = (*renderer)->frame_stats();
  return scene.color();
}

TEST_F(VoxelTranslucentGl, FacesWithinOneChunkBlendBackToFront) {
  // White glass at z 20 and brown glass at z 12, both half opaque, in one chunk: seen from +z the
  // white pane is in front, from -z the brown one. The mesher emits the faces in one order, so
  // without sorting inside the chunk one of the two views blends front to back.
  const BlockPalette solid = glass_palette(1.0f, 1.0f);
  const BlockPalette half = glass_palette(0.5f, 0.5f);
  for (const glm::dvec3 eye : {glm::dvec3(16.0, 16.0, 60.0), glm::dvec3(16.0, 16.0, -28.0)}) {
    const bool from_front = eye.z > 0.0;
    const Image wall = render_panes(solid, {}, eye);
    const Image white = render_panes(solid, {{"white_glass", 20}}, eye);
    const Image brown = render_panes(solid, {{"brown_glass", 12}}, eye);
    VoxelFrameStats stats;
    const Image both = render_panes(half, {{"white_glass", 20}, {"brown_glass", 12}}, eye, &stats);
    const Image& near = from_front ? white : brown;
    const Image& far = from_front ? brown : white;
    const Match right = match(both, wall, near, [&](int x, int y, int c) {
      return 0.5f * near.at(x, y, c) + 0.25f * far.at(x, y, c) + 0.25f * wall.at(x, y, c);
    }, 0.02f);
    std::printf("one chunk seen from %s z: back to front on %d of %d pixels, %zu chunk sort(s)\n", from_front ? "+" : "-",
                right.matching, right.covered, stats.translucent_sorts);
    EXPECT_GT(right.covered, 500) << "the near pane's footprint";
    EXPECT_GE(right.matching, right.covered * 95 / 100) << (from_front ? "from +z" : "from -z");
    EXPECT_EQ(stats.translucent_sorts, 1u) << "one chunk with translucent faces, sorted at its first frame";
  }
}

TEST_F(VoxelTranslucentGl, TheSeedsAlphaThresholdDiscardsFaintTexels) {
  // Opacity 0.04: alpha 0.04 is below the seed's 0.05, so nothing is drawn; with a cutoff of 0
  // the faint glass tints the floor.
  const BlockPalette faint = glass_palette(0.04f, 0.04f);
  const Image floor = render_layers(faint, {});
  const Image cut = render_layers(faint, {{"white_glass", 40}}, 0.05f);
  const Image kept = render_layers(faint, {{"white_glass", 40}}, 0.0f);
  int cut_differs = 0, kept_differs = 0;
  for (std::size_t i = 0; i < floor.data().size(); ++i) {
    cut_differs += floor.data()[i] != cut.data()[i];
    kept_differs += std::abs(floor.data()[i] - kept.data()[i]) > 0.005f;
  }
  EXPECT_EQ(cut_differs, 0);
  EXPECT_GT(kept_differs, 400);
}

}  // namespace
}  // namespace sylva::voxel
