// Brush stability: extreme radius, strength, spacing and coordinates never produce NaN/Inf,
// never leave unit maps' [0, 1], and a dab far outside the map touches nothing.
#include "brush.hpp"
#include "undo.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace sylva;
using namespace sylva::editor;

// Invariant: every value stays finite (height maps) or in [0, 1] (unit maps) for any brush.
TEST(BrushStability, ExtremeBrushesKeepMapsFiniteAndInRange) {
  for (scene::MapKind kind : {scene::MapKind::kHeight, scene::MapKind::kUnit}) {
    for (BrushOp op : {BrushOp::kRaise, BrushOp::kLower, BrushOp::kPaint, BrushOp::kErase, BrushOp::kFlatten,
                       BrushOp::kSmooth, BrushOp::kNoise}) {
      for (float radius : {0.01f, 3.0f, 1.0e5f}) {
        for (float strength : {0.0f, 1.0f, 1.0e4f}) {
          scene::MapGrid g(24, 16, 0.5f, {-1.0e6, 1.0e6}, {0.5, 0.5});
          BrushSettings b;
          b.op = op;
          b.radius = radius;
          b.strength = strength;
          b.noise_scale = 0.01f;
          const glm::dvec2 c = g.world(12, 8);
          const float target = resolve_target(g, b, c);
          for (int k = 0; k < 20; ++k) apply_dab(g, kind, b, c, target);
          for (float v : g.values) {
            ASSERT_TRUE(std::isfinite(v));
            if (kind == scene::MapKind::kUnit) {
              ASSERT_GE(v, 0.0f);
              ASSERT_LE(v, 1.0f);
            }
          }
        }
      }
    }
  }
}

// Invariant: stroke resampling is bounded and finite for tiny spacing over long strokes, and
// dabs far away or with NaN centres change nothing.
TEST(BrushStability, StrokesAndFarDabs) {
  const std::vector<glm::dvec2> pts = {{0, 0}, {1.0e3, 0}};
  EXPECT_EQ(stroke_dabs(pts, 1.0).size(), 1001u);
  const std::vector<glm::dvec2> same = {{5, 5}, {5, 5}, {5, 5}};
  EXPECT_EQ(stroke_dabs(same, 0.1).size(), 1u);
  scene::MapGrid g(8, 8, 0.25f, {0, 0}, {1, 1});
  const scene::MapGrid before = g;
  BrushSettings b;
  b.radius = 2.0f;
  EXPECT_TRUE(apply_dab(g, scene::MapKind::kUnit, b, {1.0e9, -1.0e9}, 1.0f).empty());
  EXPECT_TRUE(apply_dab(g, scene::MapKind::kUnit, b, {std::nan(""), 0.0}, 1.0f).empty());
  EXPECT_EQ(g.values, before.values);
  // The recorder handles rectangles entirely outside the map.
  StrokeRecorder rec("m", g);
  rec.before_dab({100, 100, 120, 120});
  EXPECT_FALSE(rec.finish().has_value());
}
