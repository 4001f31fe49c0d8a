// Brush maths: a dab changes exactly the texels inside its radius (by the falloff weight),
// strokes resample evenly, smoothing and flattening converge without overshoot, unit maps stay
// in [0, 1], noise is deterministic.
#include "brush.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace sylva;
using namespace sylva::editor;
using scene::MapGrid;
using scene::MapKind;
using scene::TexelRect;

namespace {

MapGrid flat(int w, int h, float v = 0.0f) { return MapGrid(w, h, v, {0.0, 0.0}, {1.0, 1.0}); }

MapGrid bumpy(int w, int h) {
  MapGrid g = flat(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) g.at(i, j) = ((i * 7 + j * 13) % 11) * 1.5f - 4.0f + (i == 20 && j == 20 ? 30.0f : 0.0f);
  return g;
}

}  // namespace

TEST(Brush, FalloffWeights) {
  for (Falloff f : {Falloff::kConstant, Falloff::kLinear, Falloff::kSmooth, Falloff::kGaussian}) {
    EXPECT_FLOAT_EQ(falloff_weight(f, 0.0), 1.0f);
    EXPECT_EQ(falloff_weight(f, 1.0), 0.0f);
    EXPECT_EQ(falloff_weight(f, 1.5), 0.0f);
    EXPECT_EQ(falloff_weight(f, std::nan("")), 0.0f);
    float prev = 1.0f;
    for (double t = 0.0; t < 1.0; t += 0.05) {
      const float w = falloff_weight(f, t);
      EXPECT_LE(w, prev + 1e-7f);
      EXPECT_GE(w, 0.0f);
      prev = w;
    }
  }
  EXPECT_NEAR(falloff_weight(Falloff::kLinear, 0.25), 0.75f, 1e-6);
  EXPECT_NEAR(falloff_weight(Falloff::kSmooth, 0.5), 0.5f, 1e-6);
}

TEST(Brush, ADabChangesExactlyTheTexelsInsideItsRadius) {
  MapGrid g = flat(40, 30);
  g.texel_origin = {-10.0, 5.0};
  g.texel_size = {0.5, 0.5};
  BrushSettings b;
  b.op = BrushOp::kRaise;
  b.radius = 3.2f;
  b.strength = 2.0f;
  b.falloff = Falloff::kLinear;
  const glm::dvec2 c{-3.1, 11.3};
  const MapGrid before = g;
  const TexelRect changed = apply_dab(g, MapKind::kHeight, b, c, 0.0f);
  int expected_count = 0;
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const double d = glm::distance(g.world(i, j), c);
      const float expected = d < b.radius ? before.at(i, j) + b.strength * static_cast<float>(1.0 - d / b.radius) : before.at(i, j);
      EXPECT_FLOAT_EQ(g.at(i, j), expected) << i << "," << j;
      if (d < b.radius) {
        ++expected_count;
        EXPECT_TRUE(i >= changed.x0 && i < changed.x1 && j >= changed.y0 && j < changed.y1) << "changed rect misses " << i << "," << j;
      }
    }
  }
  EXPECT_GT(expected_count, 100);
  // The rectangle is tight: every border row/column holds a changed texel.
  EXPECT_EQ(changed, dab_rect(g, c, b.radius));
  // A dab off the map changes nothing.
  EXPECT_TRUE(apply_dab(g, MapKind::kHeight, b, {500.0, 500.0}, 0.0f).empty());
}

TEST(Brush, StrokesResampleEvenly) {
  const std::vector<glm::dvec2> pts = {{0, 0}, {10, 0}, {10, 5}};
  const std::vector<glm::dvec2> dabs = stroke_dabs(pts, 2.0);
  ASSERT_EQ(dabs.size(), 8u);  // 0,2,...,10 along x then 2 and 4 along z (15 m / 2 m + the start)
  for (std::size_t k = 1; k < dabs.size(); ++k) {
    EXPECT_LE(glm::distance(dabs[k], dabs[k - 1]), 2.0 + 1e-9);
  }
  EXPECT_EQ(dabs[5], glm::dvec2(10, 0));
  EXPECT_EQ(dabs[7], glm::dvec2(10, 4));
  EXPECT_EQ(stroke_dabs(std::vector<glm::dvec2>{{3, 4}}, 1.0).size(), 1u);
}

// Invariant: smoothing never leaves the range of the old values and converges to flat.
TEST(Brush, SmoothingConvergesWithoutOvershoot) {
  MapGrid g = bumpy(41, 41);
  float lo = 1e9f, hi = -1e9f;
  for (float v : g.values) lo = std::min(lo, v), hi = std::max(hi, v);
  BrushSettings b;
  b.op = BrushOp::kSmooth;
  b.radius = 100.0f;
  b.strength = 1.0f;
  b.falloff = Falloff::kConstant;
  auto spread = [&] {
    float a = 1e9f, z = -1e9f;
    for (float v : g.values) a = std::min(a, v), z = std::max(z, v);
    return z - a;
  };
  float last = spread();
  for (int k = 0; k < 400; ++k) {
    apply_dab(g, MapKind::kHeight, b, {20.0, 20.0}, 0.0f);
    for (float v : g.values) {
      ASSERT_GE(v, lo - 1e-4f);
      ASSERT_LE(v, hi + 1e-4f);
    }
    const float s = spread();
    ASSERT_LE(s, last + 1e-4f) << "the range never grows, step " << k;
    last = s;
  }
  EXPECT_LT(last, 0.05f * (hi - lo)) << "smoothing converges toward flat";
}

// Invariant: flatten moves every texel monotonically toward the target and never past it.
TEST(Brush, FlatteningConvergesMonotonicallyWithoutOvershoot) {
  MapGrid g = bumpy(30, 30);
  BrushSettings b;
  b.op = BrushOp::kFlatten;
  b.radius = 9.0f;
  b.strength = 0.3f;
  b.falloff = Falloff::kSmooth;
  const glm::dvec2 c{15.0, 15.0};
  const float target = resolve_target(g, b, c);
  EXPECT_FLOAT_EQ(target, sample_grid(g, c));
  for (int k = 0; k < 300; ++k) {
    const MapGrid prev = g;
    apply_dab(g, MapKind::kHeight, b, c, target);
    for (std::size_t n = 0; n < g.values.size(); ++n) {
      const float before = prev.values[n], after = g.values[n];
      ASSERT_LE(std::fabs(after - target), std::fabs(before - target) + 1e-5f) << "moves toward the target";
      ASSERT_FALSE((before - target) * (after - target) < 0.0f) << "never crosses it";
    }
  }
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i)
      if (glm::distance(g.world(i, j), c) < 0.8 * b.radius) {
        EXPECT_NEAR(g.at(i, j), target, 1e-3) << i << "," << j;
      }
  b.use_target = true;
  b.target = 7.0f;
  EXPECT_FLOAT_EQ(resolve_target(g, b, c), 7.0f);
}

TEST(Brush, UnitMapsStayInRangeAndPaintErase) {
  MapGrid g = flat(20, 20, 0.5f);
  BrushSettings b;
  b.radius = 5.0f;
  b.falloff = Falloff::kConstant;
  b.op = BrushOp::kRaise;
  b.strength = 3.0f;
  apply_dab(g, MapKind::kUnit, b, {10.0, 10.0}, 0.0f);
  EXPECT_EQ(g.at(10, 10), 1.0f);
  b.op = BrushOp::kLower;
  apply_dab(g, MapKind::kUnit, b, {10.0, 10.0}, 0.0f);
  EXPECT_EQ(g.at(10, 10), 0.0f);
  b.op = BrushOp::kPaint;
  b.strength = 0.5f;
  b.use_target = true;
  b.target = 0.8f;
  apply_dab(g, MapKind::kUnit, b, {10.0, 10.0}, resolve_target(g, b, {10, 10}));
  EXPECT_FLOAT_EQ(g.at(10, 10), 0.4f);
  b.op = BrushOp::kErase;
  b.use_target = false;
  b.strength = 1.0f;
  apply_dab(g, MapKind::kUnit, b, {10.0, 10.0}, resolve_target(g, b, {10, 10}));
  EXPECT_EQ(g.at(10, 10), 0.0f);
  EXPECT_EQ(g.at(0, 0), 0.5f) << "outside the radius";
}

TEST(Brush, NoiseIsDeterministicAndBounded) {
  MapGrid a = flat(32, 32), c = flat(32, 32);
  BrushSettings b;
  b.op = BrushOp::kNoise;
  b.radius = 12.0f;
  b.strength = 2.0f;
  b.noise_scale = 4.0f;
  apply_dab(a, MapKind::kHeight, b, {16, 16}, 0.0f);
  apply_dab(c, MapKind::kHeight, b, {16, 16}, 0.0f);
  EXPECT_EQ(a.values, c.values);
  float lo = 0, hi = 0;
  for (float v : a.values) lo = std::min(lo, v), hi = std::max(hi, v);
  EXPECT_GE(lo, -2.0f);
  EXPECT_LE(hi, 2.0f);
  EXPECT_GT(hi - lo, 0.2f) << "noise actually changes the map";
}

// Colour maps (grass.tint): paint goes to the colour's channel, erase to white (no tint), other
// ops act per channel unchanged.
TEST(Brush, ColourChannelBrushes) {
  BrushSettings b;
  b.color = {0.9f, 0.2f, 0.0f};
  b.op = BrushOp::kPaint;
  for (int c = 0; c < 3; ++c) {
    const BrushSettings cb = color_channel_brush(b, c);
    EXPECT_EQ(cb.op, BrushOp::kPaint);
    EXPECT_TRUE(cb.use_target);
    EXPECT_EQ(cb.target, b.color[c]);
  }
  b.op = BrushOp::kErase;
  EXPECT_EQ(color_channel_brush(b, 1).op, BrushOp::kPaint);
  EXPECT_EQ(color_channel_brush(b, 1).target, 1.0f);
  b.op = BrushOp::kSmooth;
  EXPECT_EQ(color_channel_brush(b, 2).op, BrushOp::kSmooth);
  EXPECT_EQ(color_channel_ids("grass.tint"), (std::array<std::string, 3>{"grass.tint_r", "grass.tint_g", "grass.tint_b"}));
}
