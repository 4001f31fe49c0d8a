// Culling formulas: seed 001's thinning law, conservative frustum culling, orientation culling,
// tile tests that agree with blade tests, tessellation levels.
#include <sylva/grass/culling.hpp>
#include <sylva/grass/generator.hpp>

#include "support/fields.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace sylva::grass {
namespace {

struct View {
  glm::mat4 vp;
  CullView cull;
};

View make_view(const glm::vec3& eye, const glm::vec3& target, float fov_deg = 60.0f, float aspect = 16.0f / 9.0f,
               float height_px = 144.0f) {
  const glm::mat4 proj = glm::perspective(glm::radians(fov_deg), aspect, 0.05f, 500.0f);
  const glm::mat4 view = glm::lookAt(eye, target, glm::vec3(0, 1, 0));
  View v;
  v.vp = proj * view;
  v.cull = make_cull_view(v.vp, eye, glm::normalize(target - eye), height_px, glm::radians(fov_deg));
  return v;
}

BladeSet make_field(float density = 40.0f, bool control_jitter = false) {
  GrassFieldSettings field;
  field.density = density;
  BladeSettings blade;
  blade.control_jitter = control_jitter;
  const HeightField ground = testing::make_ground(-40.0, 100.0);
  return generate_blades(field, blade, GrassMaps::uniform({{0, 0}, {60, 60}}), ground, {0, 0, 0}).value();
}

TEST(GrassCulling, Seed001ThinningLaw) {
  CullSettings s;
  s.thinning_start = 0.0f;
  s.thinning_min_keep = 0.0f;
  s.near_distance = 80.0f;
  for (float d = 0.0f; d < 100.0f; d += 3.7f) EXPECT_NEAR(distance_keep(d, s), std::max(0.0f, 1.0f - d / 80.0f), 1e-6f);
  s.thinning_start = 20.0f;
  s.thinning_min_keep = 0.1f;
  EXPECT_EQ(distance_keep(10.0f, s), 1.0f);
  EXPECT_NEAR(distance_keep(50.0f, s), 0.55f, 1e-6f);
  EXPECT_EQ(distance_keep(80.0f, s), 0.0f);
  s.distance_thinning = false;
  EXPECT_EQ(distance_keep(79.0f, s), 1.0f);
  EXPECT_EQ(distance_keep(81.0f, s), 0.0f);
  // Width compensation keeps keep * width ~ constant until the 4x cap.
  s.width_compensation = 1.0f;
  EXPECT_NEAR(width_scale(0.5f, s), 2.0f, 1e-6f);
  EXPECT_NEAR(width_scale(0.1f, s), 4.0f, 1e-6f);
  s.width_compensation = 0.0f;
  EXPECT_EQ(width_scale(0.1f, s), 1.0f);
}

TEST(GrassCulling, MeasuredThinningMatchesTheLaw) {
  const BladeSet set = make_field(60.0f);
  CullSettings s;
  s.frustum = false;
  s.orientation = false;
  s.thinning_start = 5.0f;
  s.near_distance = 40.0f;
  s.thinning_min_keep = 0.0f;
  const glm::vec3 cam(30.0f, 1.7f, 30.0f);
  const View v = make_view(cam, cam + glm::vec3(0, 0, -1));
  // Kept share in distance rings versus keep(d).
  for (float r0 = 0.0f; r0 < 30.0f; r0 += 5.0f) {
    int total = 0, kept = 0;
    double keep_sum = 0.0;
    for (const Blade& b : set.blades) {
      const float d = glm::length(b.root() - cam);
      if (d < r0 || d >= r0 + 5.0f) continue;
      ++total;
      keep_sum += distance_keep(d, s);
      kept += cull_blade(b, v.cull, s) == CullResult::kVisible;
    }
    ASSERT_GT(total, 500);
    EXPECT_NEAR(static_cast<double>(kept) / total, keep_sum / total, 0.02) << "ring " << r0;
  }
}

TEST(GrassCulling, FrustumCullingIsConservative) {
  for (const bool jitter : {false, true}) {  // with seed 001's control-point jitter: the drawn curve
    const BladeSet set = make_field(30.0f, jitter);
    CullSettings s;
    s.orientation = false;
    s.distance_thinning = false;
    s.near_distance = 1000.0f;
    const View v = make_view({30.0f, 1.7f, 30.0f}, {38.0f, 0.5f, 22.0f});
    int culled = 0;
    for (const Blade& b : set.blades) {
      if (cull_blade(b, v.cull, s) != CullResult::kFrustum) continue;
      ++culled;
      // Every point of the drawn blade (centre curve +- half width) is outside the view volume.
      const glm::vec3 wd = blade_width_dir(b.up_dir(), b.orientation()) * (0.5f * b.width());
      for (int i = 0; i <= 8; ++i) {
        const glm::vec3 c = bezier_point(b.root(), drawn_control(b), b.tip(), i / 8.0f);
        for (const glm::vec3& p : {c - wd, c + wd}) {
          const glm::vec4 clip = v.vp * glm::vec4(p, 1.0f);
          const bool inside = clip.w > 0 && std::abs(clip.x) <= clip.w && std::abs(clip.y) <= clip.w;
          ASSERT_FALSE(inside) << "a frustum-culled blade has a visible point (jitter " << jitter << ")";
        }
      }
    }
    EXPECT_GT(culled, static_cast<int>(set.blades.size() / 2)) << "a typical view culls most of the field";
  }
}

TEST(GrassCulling, OrientationCullsOnlyThinEdgeOnBlades) {
  Blade b{};
  b.v0 = glm::vec4(0, 0, 0, 0.0f);  // orientation 0: width along +x
  b.v1 = glm::vec4(0, 0.4f, 0, 0.4f);
  b.v2 = glm::vec4(0, 0.4f, 0.0f, 0.01f);
  b.up = glm::vec4(0, 1, 0, 50.0f);
  b.attr = glm::vec4(0.1f, 0, 0, 0);
  CullSettings s;
  s.frustum = false;
  s.distance_thinning = false;
  // Looking along +x from 20 m: edge-on and thin -> culled.
  View far = make_view({-20, 0.2f, 0}, {0, 0.2f, 0});
  EXPECT_EQ(cull_blade(b, far.cull, s), CullResult::kOrientation);
  // Looking along +z from 20 m: face-on -> kept.
  View face = make_view({0, 0.2f, -20}, {0, 0.2f, 0});
  EXPECT_EQ(cull_blade(b, face.cull, s), CullResult::kVisible);
  // Edge-on but close at a high resolution: the sliver is wider than orientation_max_px -> kept.
  View near = make_view({-0.3f, 0.02f, 0.02f}, {0, 0.02f, 0}, 60.0f, 16.0f / 9.0f, 2160.0f);
  EXPECT_GT(std::abs(glm::normalize(glm::vec3(0.3f, -0.02f, -0.02f)).x), s.orientation_threshold);
  EXPECT_EQ(cull_blade(b, near.cull, s), CullResult::kVisible);
  // 18 degrees off edge-on (|cos| = 0.95) keeps 31 % of its width: kept by default (threshold
  // 0.97 = 14 degrees), culled by the paper's 0.9.
  View oblique = make_view({-20.0f * std::cos(0.314f), 0.0f, 20.0f * std::sin(0.314f)}, {0, 0.0f, 0});
  EXPECT_EQ(cull_blade(b, oblique.cull, s), CullResult::kVisible);
  CullSettings paper = s;
  paper.orientation_threshold = 0.9f;
  EXPECT_EQ(cull_blade(b, oblique.cull, paper), CullResult::kOrientation);
}

TEST(GrassCulling, TileTestNeverHidesAVisibleBlade) {
  const BladeSet set = make_field(20.0f);
  CullSettings s;
  s.near_distance = 25.0f;
  for (const glm::vec3& target : {glm::vec3(50, 0, 50), glm::vec3(0, 0, 30), glm::vec3(30, -10, 30)}) {
    const View v = make_view({30.0f, 3.0f, 30.0f}, target);
    int tiles_culled = 0;
    for (const GrassTile& t : set.tiles) {
      if (tile_visible(t, v.cull, s)) continue;
      ++tiles_culled;
      for (std::uint32_t i = t.first; i < t.first + t.count; ++i) {
        const CullResult r = cull_blade(set.blades[i], v.cull, s);
        ASSERT_TRUE(r == CullResult::kFrustum || r == CullResult::kDistance || r == CullResult::kDensity) << to_string(r);
      }
    }
    EXPECT_GT(tiles_culled, 0);
  }
  const View v = make_view({30.0f, 3.0f, 30.0f}, {50, 0, 50});
  const CullCounts counts = cull_blade_set(set, v.cull, s);
  EXPECT_EQ(counts.considered, set.blades.size());
  EXPECT_EQ(counts.visible + counts.density + counts.distance + counts.frustum + counts.orientation, counts.considered);
  EXPECT_GT(counts.visible, 0u);
  EXPECT_GE(counts.segments, counts.visible);
}

TEST(GrassCulling, VisibleSetOfATileIsWorldAnchoredUnderCameraMotion) {
  // Issue: "the visible blade set of a tile does not change with the camera inside the near
  // range". A camera walking around and over a tile (every blade closer than thinning_start,
  // the tile in view) sees exactly the same blades of it: distance thinning and density read
  // only per-blade constants (rank), so nothing appears, vanishes or swims. Orientation culling
  // is the one view-dependent test; it may only drop blades that are edge-on and sub-pixel.
  const BladeSet set = make_field(40.0f);
  const GrassTile* tile = nullptr;
  for (const GrassTile& t : set.tiles) {
    const glm::vec3 c = 0.5f * (t.bounds_min + t.bounds_max);
    if (t.count > 300 && std::abs(c.x - 30.0f) < 4.0f && std::abs(c.z - 30.0f) < 4.0f) tile = &t;
  }
  ASSERT_NE(tile, nullptr);
  const glm::vec3 centre = 0.5f * (tile->bounds_min + tile->bounds_max);
  CullSettings s;
  s.thinning_start = 15.0f;
  s.near_distance = 40.0f;
  s.density_scale = 0.8f;  // a quality setting below 1 must not make the set view-dependent either
  std::vector<std::uint32_t> first;
  int views = 0, orientation_only = 0;
  for (int k = 0; k < 12; ++k) {
    const float a = 0.52f * static_cast<float>(k);
    const float r = 6.0f + 0.7f * static_cast<float>(k % 4);
    const glm::vec3 eye = centre + glm::vec3(r * std::cos(a), 2.0f + 0.5f * static_cast<float>(k % 3), r * std::sin(a));
    const View v = make_view(eye, centre, 90.0f);
    for (const float corner_x : {tile->bounds_min.x, tile->bounds_max.x})
      for (const float corner_z : {tile->bounds_min.z, tile->bounds_max.z})
        ASSERT_LT(glm::length(glm::vec3(corner_x, centre.y, corner_z) - eye), s.thinning_start);
    std::vector<std::uint32_t> seen;
    CullSettings no_orientation = s;
    no_orientation.orientation = false;
    for (std::uint32_t i = tile->first; i < tile->first + tile->count; ++i) {
      const CullResult r0 = cull_blade(set.blades[i], v.cull, no_orientation);
      ASSERT_NE(r0, CullResult::kFrustum) << "the whole tile is in view";
      if (r0 == CullResult::kVisible) seen.push_back(i);
      const CullResult r1 = cull_blade(set.blades[i], v.cull, s);
      if (r1 != r0) {
        ASSERT_EQ(r1, CullResult::kOrientation);
        ++orientation_only;
      }
    }
    if (views++ == 0) {
      first = seen;
      EXPECT_GT(first.size(), tile->count / 2);
      EXPECT_LT(first.size(), tile->count);  // density_scale removes some, always the same ones
    } else {
      EXPECT_EQ(seen, first) << "view " << k;
    }
  }
  RecordProperty("orientation_culled_blade_views", orientation_only);
}

TEST(GrassCulling, TessellationFollowsProjectedSize) {
  Blade b{};
  b.v0 = glm::vec4(0, 0, 0, 0);
  b.v1 = glm::vec4(0, 0.5f, 0, 0.5f);
  b.v2 = glm::vec4(0, 0.5f, 0, 0.01f);
  b.up = glm::vec4(0, 1, 0, 1);
  CullSettings s;
  s.pixels_per_segment = 5.0f;
  s.max_tess_level = 8.0f;
  int prev = 100;
  for (const float d : {0.3f, 1.0f, 3.0f, 10.0f, 30.0f, 100.0f}) {
    const View v = make_view({0, 0.25f, d}, {0, 0.25f, 0});
    const int n = tessellation_segments(b, v.cull, s);
    EXPECT_LE(n, prev);
    EXPECT_GE(n, 1);
    EXPECT_LE(n, 8);
    const float px = 0.5f * v.cull.pixels_per_radian / d;
    EXPECT_EQ(n, std::clamp(static_cast<int>(std::ceil(px / 5.0f)), 1, 8)) << d;
    prev = n;
  }
}

// Seed 001 eq. 2.3 (cull.distance_tess_law): n = ceil(s (1 - d / d_max)) from the root distance,
// whatever the projected size, at least 1 (beyond d_max the blade is culled, not drawn at 0).
TEST(GrassCulling, DistanceLawIsSeed001Equation23) {
  Blade b{};
  b.v0 = glm::vec4(0, 0, 0, 0);
  b.v1 = glm::vec4(0, 0.5f, 0, 0.5f);
  b.v2 = glm::vec4(0, 0.5f, 0, 0.01f);
  b.up = glm::vec4(0, 1, 0, 1);
  CullSettings s;
  s.distance_tess_law = true;
  s.max_tess_level = 8.0f;
  s.near_distance = 40.0f;
  for (const float d : {0.0f, 4.0f, 10.0f, 20.0f, 35.0f, 39.9f, 60.0f}) {
    const View v = make_view({0, 0.0f, d}, {0, 0.0f, -1.0f});
    const int expected = std::clamp(static_cast<int>(std::ceil(8.0f * (1.0f - d / 40.0f))), 1, 8);
    EXPECT_EQ(tessellation_segments(b, v.cull, s), expected) << d;
  }
  s.near_distance = 0.5f;  // smallest setting: finite, 1 segment far out
  EXPECT_EQ(tessellation_segments(b, make_view({0, 0, 1000.0f}, {0, 0, 0}).cull, s), 1);
}

// Seed 001 pitfall "LOD popping" (cull.tess_spacing): walking the camera away in 1 cm steps,
// equal spacing's ceil-ed level jumps by a whole segment at every integer, the fractional levels
// move by at most a few hundredths per step (continuous), and spacing_segments follows the GL
// rules (even >= 2, odd >= 1).
TEST(GrassCulling, FractionalSpacingMorphsWhereEqualSpacingPops) {
  Blade b{};
  b.v0 = glm::vec4(0, 0, 0, 0);
  b.v1 = glm::vec4(0, 0.5f, 0, 0.5f);
  b.v2 = glm::vec4(0, 0.5f, 0, 0.01f);
  b.up = glm::vec4(0, 1, 0, 1);
  CullSettings s;
  s.pixels_per_segment = 5.0f;
  s.max_tess_level = 8.0f;
  const TessSpacing spacings[3] = {TessSpacing::kEqual, TessSpacing::kFractionalEven, TessSpacing::kFractionalOdd};
  float max_step[3] = {0, 0, 0};
  int jumps[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    s.tess_spacing = spacings[i];
    float prev = -1.0f;
    for (int cm = 200; cm <= 1000; ++cm) {  // 2 m to 10 m: levels 6.2 down to 1.25
      const float d = cm * 0.01f;
      const View v = make_view({0, 0.25f, d}, {0, 0.25f, 0});
      const float level = tessellation_level(b, v.cull, s);
      const int segments = tessellation_segments(b, v.cull, s);
      ASSERT_EQ(segments, i == 0 ? static_cast<int>(level) : spacing_segments(level, spacings[i])) << d;
      if (i == 1) {
        ASSERT_EQ(segments % 2, 0);
      }
      if (i == 2) {
        ASSERT_EQ(segments % 2, 1);
      }
      if (prev >= 0.0f) {
        const float step = std::abs(level - prev);
        max_step[i] = std::max(max_step[i], step);
        jumps[i] += step > 0.5f;
      }
      prev = level;
    }
  }
  std::printf("largest level change per 1 cm, 2..10 m: equal %.4f (%d jumps), fractional_even %.4f, fractional_odd %.4f\n",
              max_step[0], jumps[0], max_step[1], max_step[2]);
  EXPECT_EQ(max_step[0], 1.0f);
  EXPECT_EQ(jumps[0], 5);  // ceil-ed levels 7 ... 2 pass 6, 5, 4, 3, 2
  for (int i = 1; i < 3; ++i) {
    EXPECT_LT(max_step[i], 0.04f);
    EXPECT_EQ(jumps[i], 0);
  }
  // Fractional levels are the unrounded law: px / pixels_per_segment.
  s.tess_spacing = TessSpacing::kFractionalEven;
  const View v = make_view({0, 0.25f, 4.0f}, {0, 0.25f, 0});
  const glm::vec3 mid = bezier_point(b.root(), b.control(), b.tip(), 0.5f);
  EXPECT_NEAR(tessellation_level(b, v.cull, s), 0.5f * v.cull.pixels_per_radian / glm::length(mid - v.cull.camera) / 5.0f, 1e-4f);
  s.distance_tess_law = true;  // seed 001 eq. 2.3 without its ceil
  s.near_distance = 40.0f;
  EXPECT_NEAR(tessellation_level(b, v.cull, s), 8.0f * (1.0f - glm::length(v.cull.camera) / 40.0f), 1e-4f);
  s.tess_spacing = TessSpacing::kEqual;
  EXPECT_EQ(tessellation_level(b, v.cull, s), 8.0f);  // ceil(7.2)

  // GL 4.5 §11.2.2 segment counts.
  EXPECT_EQ(spacing_segments(1.0f, TessSpacing::kFractionalEven), 2);
  EXPECT_EQ(spacing_segments(2.0f, TessSpacing::kFractionalEven), 2);
  EXPECT_EQ(spacing_segments(2.01f, TessSpacing::kFractionalEven), 4);
  EXPECT_EQ(spacing_segments(7.5f, TessSpacing::kFractionalEven), 8);
  EXPECT_EQ(spacing_segments(1.0f, TessSpacing::kFractionalOdd), 1);
  EXPECT_EQ(spacing_segments(1.01f, TessSpacing::kFractionalOdd), 3);
  EXPECT_EQ(spacing_segments(3.0f, TessSpacing::kFractionalOdd), 3);
  EXPECT_EQ(spacing_segments(100.0f, TessSpacing::kFractionalOdd), 63);
  EXPECT_EQ(spacing_segments(2.5f, TessSpacing::kEqual), 3);
  // A sub-draw holds the blades of the largest count the spacing makes of max_tess_level.
  EXPECT_EQ(blades_per_draw(8.0f, TessSpacing::kFractionalEven), blades_per_draw(8.0f));
  EXPECT_EQ(blades_per_draw(8.0f, TessSpacing::kFractionalOdd), blades_per_draw(9.0f));
  EXPECT_EQ(blades_per_draw(7.0f, TessSpacing::kFractionalEven), blades_per_draw(8.0f));
}

TEST(GrassCulling, SubDrawsStayUnderTheTessellatedVertexBudget) {
  // Invariant: blades_per_draw(L) blades at the most segments L can produce (2 (ceil(L) + 1)
  // vertices each, L capped at 64) never exceed kTessVerticesPerDraw, and a sub-draw holds at
  // least one blade whatever the setting (0, negative, fractional, NaN, beyond 64).
  for (const float level : {1.0f, 2.0f, 7.5f, 8.0f, 8.5f, 16.0f, 63.1f, 64.0f}) {
    const std::uint32_t blades = blades_per_draw(level);
    const std::uint32_t vertices = 2u * (static_cast<std::uint32_t>(std::ceil(level)) + 1u);
    EXPECT_LE(std::uint64_t{blades} * vertices, kTessVerticesPerDraw) << level;
    EXPECT_GT(std::uint64_t{blades + 1} * vertices, kTessVerticesPerDraw) << level << ": no needless extra draws";
  }
  EXPECT_EQ(blades_per_draw(8.0f), 1820u);  // the default max_tess_level
  EXPECT_EQ(blades_per_draw(64.0f), 252u);
  EXPECT_EQ(blades_per_draw(1.0e6f), blades_per_draw(64.0f));
  EXPECT_EQ(blades_per_draw(std::numeric_limits<float>::quiet_NaN()), blades_per_draw(64.0f));
  EXPECT_EQ(blades_per_draw(0.0f), blades_per_draw(1.0f));
  EXPECT_EQ(blades_per_draw(-5.0f), blades_per_draw(1.0f));
}

}  // namespace
}  // namespace sylva::grass
