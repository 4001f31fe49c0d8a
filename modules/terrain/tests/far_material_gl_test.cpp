// The baked far material (issue 18, terrain.render.far_material, src/far_material.hpp): far
// chunks read the layered material's albedo and occlusion from a texture baked per field sample
// instead of computing it per pixel. On a far view of a ridged field crossing the snow line the
// baked picture stays within a small tolerance of the computed one; lowering the snow line
// re-bakes (the picture follows it, within the same tolerance of the computed new picture); a
// height edit re-bakes the edited samples only and the snow it raises shows up baked; the setting
// read as a scene file reads it selects the program.
#include <sylva/core/params_json.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/terrain/height_source.hpp>
#include <sylva/terrain/renderer.hpp>

#include "support/gl_support.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sylva::terrain {
namespace {

using namespace testing;
using FarMaterialGl = render::GlTest;

const glm::vec4 kSky(0.55f, 0.7f, 0.9f, 1.0f);
constexpr int kWidth = 512, kHeight = 288;

struct Ground {
  HeightField field;
  std::shared_ptr<const ChunkTree> tree;
};

// 257^2 samples 10 m apart (2.56 km), ridged, 0-450 m.
Ground make_ground() {
  GeneratedFieldSettings g;
  g.size = 257;
  g.spacing = 10.0;
  g.height_scale = 450.0f;
  g.feature_size = 1200.0f;
  g.noise = FieldNoise::kRidged;
  Ground s{generate_height_field(g).value(), nullptr};
  ChunkTreeSettings ts;
  ts.leaf_dimension = 33;
  s.tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(s.field, ts)).value());
  return s;
}

// 1 km outside the field's corner, 0.9 km up, looking at its middle: every chunk lies beyond the
// detail scales' fades and its samples span < 4 pixels (renderer.cpp kBakedMaxTexelPx) but one.
render::Camera far_camera() {
  render::Camera c;
  c.set_position({-1000.0, 900.0, -1000.0});
  c.set_yaw_pitch(glm::radians(-135.0f), glm::radians(-16.0f));
  c.perspective().fov_y = glm::radians(60.0f);
  c.perspective().near_plane = 1.0f;
  c.perspective().far_plane = 0.0f;
  c.set_aspect(kWidth, kHeight);
  return c;
}

TerrainRenderSettings settings_with_snow(float snow_line_m) {
  TerrainRenderSettings rs;
  rs.receive_shadows = false;
  rs.material.snow_line_m = snow_line_m;
  rs.material.tree_line_m = 150.0f;
  rs.material.rock_line_m = 300.0f;
  return rs;
}

// Per 8x8 block wholly on the terrain in both pictures: the largest channel difference of the
// block means. Blocks, not pixels: where a field sample covers less than a pixel the computed
// material samples its inputs once per pixel and aliases (snow speckles), the bake's mips average
// them; the blocks compare what both draw on average.
struct Difference {
  float max = 0.0f;
  double mean = 0.0;
  std::size_t blocks = 0, over_8 = 0;  // terrain blocks; blocks more than 8/255 apart
};

Difference compare(const Image& a, const Image& b) {
  constexpr int kBlock = 8;
  Difference d;
  for (int by = 0; by + kBlock <= a.height(); by += kBlock)
    for (int bx = 0; bx + kBlock <= a.width(); bx += kBlock) {
      glm::vec3 sa(0.0f), sb(0.0f);
      bool terrain = true;
      for (int y = by; y < by + kBlock && terrain; ++y)
        for (int x = bx; x < bx + kBlock && terrain; ++x) {
          terrain = !is_color(a, x, y, kSky) && !is_color(b, x, y, kSky);
          for (int c = 0; c < 3; ++c) sa[c] += a.at(x, y, c), sb[c] += b.at(x, y, c);
        }
      if (!terrain) continue;
      ++d.blocks;
      const glm::vec3 diff = glm::abs(sa - sb) / float(kBlock * kBlock);
      const float m = std::max({diff.x, diff.y, diff.z});
      d.max = std::max(d.max, m);
      d.mean += m;
      d.over_8 += m > 8.0f / 255.0f;
    }
  d.mean /= std::max<std::size_t>(d.blocks, 1);
  return d;
}

// Renders with far_material baked and computed; the bake must have drawn every chunk.
struct Pair {
  Image baked, computed;
};
Pair render_both(TerrainRenderer& t, GlTarget& target) {
  const render::Camera cam = far_camera();
  Pair p;
  t.settings().far_material = FarMaterial::kBaked;
  p.baked = target.render(t, cam, kSky);
  EXPECT_GE(t.frame_stats().far_baked_chunks * 4, t.frame_stats().selection.chunks * 3) << "most chunks are far";
  t.settings().far_material = FarMaterial::kComputed;
  p.computed = target.render(t, cam, kSky);
  EXPECT_EQ(t.frame_stats().far_baked_chunks, 0u);
  t.settings().far_material = FarMaterial::kBaked;
  return p;
}

// The tolerance (measured 4.8-6.3/255 mean, 21-23/255 max): the bake interpolates the material
// where the computed one interpolates its inputs, and takes the field's height where the drawn
// surface is within tau pixels of it, so on this rough ridged field (10 m samples, 24 m curvature
// radius) layer borders move by part of a sample.
void expect_close(const Pair& p, const char* what) {
  const Difference d = compare(p.baked, p.computed);
  ASSERT_GT(d.blocks, std::size_t{kWidth * kHeight} / 64 / 20) << what;
  std::printf("%s: %zu blocks, block means max %.1f/255, mean %.2f/255, %zu over 8/255\n", what, d.blocks,
              d.max * 255.0f, d.mean * 255.0, d.over_8);
  EXPECT_LE(d.mean, 8.0 / 255.0) << what;
  EXPECT_LE(d.max, 32.0 / 255.0) << what;
}

std::size_t brighter(const Image& a, const Image& b) {  // pixels of b brighter than a by > 0.1
  std::size_t n = 0;
  for (int y = 0; y < a.height(); ++y)
    for (int x = 0; x < a.width(); ++x) n += b.at(x, y, 1) - a.at(x, y, 1) > 0.1f;
  return n;
}

TEST_F(FarMaterialGl, BakedFarViewMatchesTheComputedMaterialAndFollowsTheSnowLine) {
  Ground g = make_ground();
  auto r = TerrainRenderer::create(g.tree, &g.field, settings_with_snow(350.0f));
  ASSERT_TRUE(r.ok()) << r.error().describe();
  TerrainRenderer& t = **r;
  EXPECT_EQ(t.settings().far_material, FarMaterial::kComputed) << "the default";
  GlTarget target = GlTarget::create(kWidth, kHeight);
  const Pair high = render_both(t, target);
  save_png(high.baked, "far_material_baked");
  save_png(high.computed, "far_material_computed");
  expect_close(high, "snow line 350 m");
  EXPECT_EQ(t.far_material_texels_baked(), 257 * 257) << "one full bake";

  // A lower snow line: the bake is redone from the new uniforms and shows the new snow.
  t.settings().material.snow_line_m = 150.0f;
  const Pair low = render_both(t, target);
  save_png(low.baked, "far_material_baked_low_snow");
  expect_close(low, "snow line 150 m");
  EXPECT_GT(brighter(high.baked, low.baked), std::size_t{kWidth * kHeight} / 100) << "the baked snow follows the snow line";
  EXPECT_EQ(t.far_material_texels_baked(), 2 * 257 * 257);
}

TEST_F(FarMaterialGl, AHeightEditRebakesTheEditedSamplesOnly) {
  Ground g = make_ground();
  auto r = TerrainRenderer::create(g.tree, &g.field, settings_with_snow(350.0f));
  ASSERT_TRUE(r.ok()) << r.error().describe();
  TerrainRenderer& t = **r;
  t.settings().far_material = FarMaterial::kBaked;
  GlTarget target = GlTarget::create(kWidth, kHeight);
  const Image before = target.render(t, far_camera(), kSky);
  ASSERT_EQ(t.far_material_texels_baked(), 257 * 257);

  // A 300 m round hill (raised cosine, 30 samples in radius) centred on sample (130, 130): snow on
  // its top. The editor's brush calls the same apply_height_edit through Scene::map_changed.
  for (int z = 100; z < 160; ++z)
    for (int x = 100; x < 160; ++x) {
      const double r = std::hypot(x - 130.0, z - 130.0) / 30.0;
      if (r < 1.0) g.field.sample(x, z) += static_cast<float>(150.0 * (1.0 + std::cos(r * 3.14159265358979)));
    }
  ASSERT_TRUE(t.apply_height_edit(g.field, 100, 100, 160, 160).ok());
  const Pair after = render_both(t, target);
  save_png(after.baked, "far_material_baked_edit");
  expect_close(after, "after the edit");
  EXPECT_GT(brighter(before, after.baked), 40u) << "the raised snow shows in the bake";
  const std::int64_t rebaked = t.far_material_texels_baked() - 257 * 257;
  EXPECT_GE(rebaked, 60 * 60);
  EXPECT_LT(rebaked, 257 * 257 / 4) << "only the edited samples (and their curvature neighbours) re-bake";
}

// terrain.render.far_material as a scene file gives it (the params the scene loads "terrain.render"
// with): "computed" (and no entry: the default) draws no chunk baked, "baked" most of them (the
// far ones); a wrong name is an
// error naming the parameter.
TEST_F(FarMaterialGl, TheSettingFromTheSceneFileSelectsTheProgram) {
  Ground g = make_ground();
  GlTarget target = GlTarget::create(kWidth, kHeight);
  for (const char* name : {"computed", "baked", ""}) {
    TerrainRenderSettings rs = settings_with_snow(350.0f);
    nlohmann::json json = nlohmann::json::object();
    if (*name != '\0') json["far_material"] = name;
    std::vector<std::string> warnings;
    ASSERT_TRUE(params_from_json(rs, json, warnings, "terrain.render").ok()) << name;
    auto r = TerrainRenderer::create(g.tree, &g.field, rs);
    ASSERT_TRUE(r.ok()) << r.error().describe();
    target.render(**r, far_camera(), kSky);
    const auto& stats = (*r)->frame_stats();
    if (std::string(name) != "baked") {
      EXPECT_EQ(stats.far_baked_chunks, 0u);
    } else {
      EXPECT_GE(stats.far_baked_chunks * 4, stats.selection.chunks * 3) << name;
    }
  }
  TerrainRenderSettings rs;
  std::vector<std::string> warnings;
  const Status bad = params_from_json(rs, nlohmann::json{{"far_material", "cached"}}, warnings, "terrain.render");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("far_material"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace sylva::terrain
