// Seed 001 variants of the blade drawing (issue #20), on the GL renderer:
//  - grass.blade.control_jitter (eq. 2.4, r3/r4): the same blades, the same visible count, other
//    blade shapes;
//  - grass.render.cull.tess_spacing (pitfall "LOD popping"): a 1 cm camera step across an integer
//    tessellation level pops the picture with equal spacing and barely moves it with the
//    fractional spacings.
#include <sylva/core/image_metrics.hpp>
#include <sylva/grass/culling.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/grass/physics.hpp>
#include <sylva/render/testing.hpp>

#include "support/fields.hpp"
#include "support/gl_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

namespace sylva::grass {
namespace {

using GrassBladeVariantsGl = render::GlTest;

BladeSet make_field(bool jitter) {
  GrassFieldSettings field;
  field.density = 60.0f;
  BladeSettings blade;
  blade.control_jitter = jitter;
  const HeightField ground = testing::make_ground(-10.0, 30.0);
  return generate_blades(field, blade, GrassMaps::uniform({{0, 0}, {20, 20}}), ground, {10.0, 0.0, 10.0}).value();
}

std::size_t foreground_pixels(const Image& image, const glm::vec4& background) {
  const Image mask = mask_from_background(image, background, 1e-3f).value();
  std::size_t n = 0;
  for (const float v : mask.data()) n += v > 0.5f;
  return n;
}

TEST_F(GrassBladeVariantsGl, ControlJitterChangesBladeShapesNotCounts) {
  GrassRenderSettings rs;
  rs.simulate = false;
  rs.cull.frustum = false;  // the jittered hull must not change the visible set here
  testing::GlScene scene = testing::GlScene::create();
  Image pictures[2];
  GrassFrameStats stats[2];
  for (int jitter = 0; jitter < 2; ++jitter) {
    BladeSet set = make_field(jitter == 1);
    const glm::dvec3 origin = set.origin;
    auto field = GrassField::create(std::move(set), rs);
    ASSERT_TRUE(field.ok()) << field.error().message;
    field->set_sorted_draw_order(true);
    scene.camera.set_position(origin + glm::dvec3(-6.0, 1.2, 6.0));
    scene.camera.look_at(origin + glm::dvec3(2.0, 0.1, -2.0));
    pictures[jitter] = scene.render(*field);
    stats[jitter] = field->read_frame_stats();
    if (jitter == 0) {
      // Off is deterministic: a second frame is the same picture.
      EXPECT_EQ(count_exceeding(pictures[0], scene.render(*field), 0.0f).value().pixels, 0u);
    }
  }
  testing::save_png(pictures[0], "grass_control_jitter_off");
  testing::save_png(pictures[1], "grass_control_jitter_on");
  const std::size_t blade_pixels = foreground_pixels(pictures[0], scene.clear_color);
  const DifferenceCount diff = count_exceeding(pictures[0], pictures[1], 0.02f).value();
  const double share = static_cast<double>(diff.pixels) / static_cast<double>(blade_pixels);
  std::printf("blades %llu / %llu, visible %llu / %llu; blade pixels %zu, changed by the jitter %zu (%.1f %% of the blade "
              "pixels)\n",
              static_cast<unsigned long long>(stats[0].blades_total), static_cast<unsigned long long>(stats[1].blades_total),
              static_cast<unsigned long long>(stats[0].counts.visible), static_cast<unsigned long long>(stats[1].counts.visible),
              blade_pixels, diff.pixels, 100.0 * share);
  EXPECT_EQ(stats[0].blades_total, stats[1].blades_total);
  EXPECT_EQ(stats[0].counts.visible, stats[1].counts.visible);
  EXPECT_GT(stats[0].counts.visible, 5000u);
  EXPECT_GT(blade_pixels, diff.total / 5) << "the picture must show grass";
  EXPECT_GT(share, 0.2) << "jittered control points must change the blades' shapes";
}

// Blades on an arc around the point C, each bent sideways (across the view), rotated copies of
// one another: from C every blade's mid-point is at the same distance, so all of them cross a
// tessellation level at the same camera position.
BladeSet make_arc(float height, float radius) {
  BladeSet set;
  constexpr int kBlades = 15;
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  for (int i = 0; i < kBlades; ++i) {
    const float phi = glm::radians(-21.0f + 42.0f * static_cast<float>(i) / (kBlades - 1));
    Blade b{};
    const glm::vec3 root(radius * std::sin(phi), 0.0f, -radius * std::cos(phi));
    const float orientation = std::fmod(2.0f * std::numbers::pi_v<float> - phi, 2.0f * std::numbers::pi_v<float>);
    const glm::vec3 w = blade_width_dir(up, orientation);  // across the view
    b.v0 = glm::vec4(root, orientation);
    b.v1 = glm::vec4(root + up * height, height);
    b.v2 = glm::vec4(root + height * glm::normalize(up + 0.9f * w), 0.05f);
    b.up = glm::vec4(up, 50.0f);
    b.attr = glm::vec4(0.0f, 0.5f, pack_color(glm::vec3(0.5f)), 0.3f);
    validate_blade(b);
    b.rest = glm::vec4(b.tip() - b.root(), 0.0f);
    set.blades.push_back(b);
  }
  GrassTile tile;
  tile.count = kBlades;
  tile.expected = kBlades;
  tile.bounds_min = glm::vec3(-radius - height, -height, -radius - height);
  tile.bounds_max = glm::vec3(radius + height, height, radius + height);
  set.tiles.push_back(tile);
  set.max_height = height;
  return set;
}

TEST_F(GrassBladeVariantsGl, FractionalSpacingMorphsWhereEqualSpacingPops) {
  constexpr float kHeight = 0.5f, kRadius = 1.5f, kEye = 0.25f;
  BladeSet set = make_arc(kHeight, kRadius);
  const Blade probe = set.blades[3];
  GrassRenderSettings rs;
  rs.simulate = false;
  rs.shape = BladeShape::kQuad;
  rs.cull.max_tess_level = 8.0f;
  auto field = GrassField::create(std::move(set), rs);
  ASSERT_TRUE(field.ok()) << field.error().message;
  field->set_sorted_draw_order(true);
  testing::GlScene scene = testing::GlScene::create(512, 288);
  const glm::vec3 c(0.0f, kEye, 0.0f);
  const float ppr = 288.0f / (2.0f * std::tan(0.5f * scene.camera.perspective().fov_y));
  const float mid_distance = glm::length(bezier_point(probe.root(), probe.control(), probe.tip(), 0.5f) - c);

  // Two frames 1 cm apart in camera distance around C, where the level is `level_at_c` for every
  // blade: either the camera really moves 5 mm behind / in front of C along the view (-z), or it
  // stays at C and pixels_per_segment moves the level by what that step does (level ~ 1 /
  // distance: level_at_c (1 -/+ 0.005 / mid_distance)), which keeps the parallax of the step out of
  // the picture and leaves only what the tessellation does.
  struct Pair {
    Image behind, front;
    std::uint64_t segments_behind = 0, segments_front = 0, primitives_behind = 0, primitives_front = 0;
  };
  auto frames = [&](TessSpacing spacing, float level_at_c, bool move_camera) {
    field->settings().cull.tess_spacing = spacing;
    Pair p;
    for (const float dz : {0.005f, -0.005f}) {
      const float level = move_camera ? level_at_c : level_at_c * (1.0f - dz / mid_distance);
      field->settings().cull.pixels_per_segment = kHeight * ppr / (mid_distance * level);
      const float z = move_camera ? dz : 0.0f;
      scene.camera.set_position(glm::dvec3(0.0, kEye, z));
      scene.camera.look_at(glm::dvec3(0.0, kEye - 0.1, z - 1.0));
      Image img = scene.render(*field);
      const GrassFrameStats s = field->read_frame_stats();
      EXPECT_EQ(s.counts.visible, 15u) << "every blade is drawn whatever the spacing";
      // cull.comp's segment count (the GLSL twin) against the CPU formula.
      const CullView view = make_cull_view(glm::mat4(1.0f), glm::vec3(scene.camera.position()), scene.camera.forward(),
                                           288.0f, scene.camera.perspective().fov_y);
      EXPECT_EQ(s.counts.segments, 15u * static_cast<std::uint64_t>(tessellation_segments(probe, view, field->settings().cull)));
      const auto times = field->gpu_times(true);
      const std::uint64_t primitives = times ? times->primitives : 0;
      (dz > 0.0f ? p.behind : p.front) = std::move(img);
      (dz > 0.0f ? p.segments_behind : p.segments_front) = s.counts.segments;
      (dz > 0.0f ? p.primitives_behind : p.primitives_front) = primitives;
    }
    return p;
  };
  const char* names[3] = {"equal", "fractional_even", "fractional_odd"};
  const TessSpacing spacings[3] = {TessSpacing::kEqual, TessSpacing::kFractionalEven, TessSpacing::kFractionalOdd};
  std::size_t changed[3] = {0, 0, 0}, changed_moving[3] = {0, 0, 0};
  std::uint64_t primitives_front[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) {
    const Pair p = frames(spacings[i], 3.0f, false);
    const Pair m = frames(spacings[i], 3.0f, true);
    changed[i] = count_exceeding(p.behind, p.front, 0.02f).value().pixels;
    changed_moving[i] = count_exceeding(m.behind, m.front, 0.02f).value().pixels;
    primitives_front[i] = p.primitives_front;
    std::printf("%s across level 3: segments %llu -> %llu, triangles %llu -> %llu; pixels changed by the 1 cm step: %zu "
                "(level only), %zu (camera moved)\n",
                names[i], static_cast<unsigned long long>(p.segments_behind), static_cast<unsigned long long>(p.segments_front),
                static_cast<unsigned long long>(p.primitives_behind), static_cast<unsigned long long>(p.primitives_front),
                changed[i], changed_moving[i]);
    EXPECT_EQ(m.segments_behind, p.segments_behind);
    EXPECT_EQ(m.segments_front, p.segments_front);
    if (i == 0) {
      EXPECT_EQ(p.segments_behind, 15u * 3u);  // level 2.99 -> ceil 3
      EXPECT_EQ(p.segments_front, 15u * 4u);   // level 3.01 -> ceil 4: the pop
      testing::save_png(p.behind, "grass_spacing_equal_behind");
      testing::save_png(p.front, "grass_spacing_equal_front");
    }
  }
  // The same camera step where no integer is crossed (level 3.5 at C): the motion alone.
  const Pair still = frames(TessSpacing::kEqual, 3.5f, true);
  const std::size_t motion = count_exceeding(still.behind, still.front, 0.02f).value().pixels;
  const std::size_t blade_pixels = foreground_pixels(still.front, scene.clear_color);
  std::printf("blade pixels %zu; equal at level 3.5 (no crossing), camera moved 1 cm: %zu pixels changed\n", blade_pixels, motion);
  EXPECT_GT(blade_pixels, 2000u) << "the blades must fill part of the picture";
  // Level only: equal pops a share of the blade pixels, the fractional spacings hardly any.
  EXPECT_GT(changed[0], blade_pixels / 20) << "equal spacing pops at the integer level";
  EXPECT_GT(changed[0], 10 * std::max<std::size_t>(changed[1], 1)) << "fractional_even morphs";
  EXPECT_GT(changed[0], 10 * std::max<std::size_t>(changed[2], 1)) << "fractional_odd morphs";
  // With the camera moving, the pop comes on top of the parallax that every spacing shows.
  EXPECT_GT(changed_moving[0], motion + changed[0] / 3);
  EXPECT_LT(changed_moving[1], motion + changed[0] / 4);
  EXPECT_LT(changed_moving[2], motion + changed[0] / 4);
  // The tessellator really runs the other spacing (blade.tese layout): at level 3.01 odd
  // spacing makes 5 segments where equal makes 4.
  EXPECT_NE(primitives_front[2], primitives_front[0]);
}

}  // namespace
}  // namespace sylva::grass
