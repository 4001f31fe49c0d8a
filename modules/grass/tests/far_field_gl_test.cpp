// The far field on the GPU: a dolly from 8 m to 120 m through the blade -> clump -> ground
// transitions; the share of the field's footprint covered by grass changes by at most 1 %
// (absolute) per frame and never falls below kMinCoverage. Invariants: coverage continuity (no
// pops) across LOD transitions, and coverage itself (a field that fades to bare soil, or draws
// nothing at all, has no pops either).
#include <sylva/core/image_metrics.hpp>
#include <sylva/grass/far_field.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/render/testing.hpp>

#include "support/fields.hpp"
#include "support/gl_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sylva::grass {
namespace {

using GrassFarFieldGl = render::GlTest;

struct Meadow {
  GrassFieldSettings field;
  BladeSettings blade;
  GrassRenderSettings render;
  FarFieldSettings far;
  HeightField ground{81, 81, 1.0, {-40.0, -40.0}};
  GrassMaps maps = GrassMaps::uniform({{-20.0, -20.0}, {20.0, 20.0}});
  Meadow() {
    field.density = 120.0f;
    render.simulate = false;
    render.cull.near_distance = 30.0f;
    render.cull.thinning_start = 10.0f;
    render.cull.thinning_min_keep = 0.0f;
    far.clump_fade_in = 15.0f;
    far.mid_distance = 100.0f;
    far.mid_fade = 30.0f;
    // Seed 003's layers alone: with the under-layer the footprint is covered at every distance,
    // which would pass trivially.
    far.under_layer = false;
  }
};

// Lowest share of the footprint the grass may cover at any distance of the dolly. Measured on
// llvmpipe: 0.32 at 10 m (blades only), rising to 0.48 at 120 m; a layer that draws nothing or
// fades to soil drops far below.
constexpr double kMinCoverage = 0.25;
// The footprint must be measured over enough pixels for a 1 % step to mean something.
constexpr std::size_t kMinFootprintPixels = 5000;

struct Coverage {
  std::size_t footprint_pixels = 0;
  double share = 0.0;
};

// Pixel (x, y) shows something other than the soil (clear) colour.
bool differs(const Image& im, int x, int y, const glm::vec4& soil) {
  return std::abs(im.at(x, y, 0) - soil.r) + std::abs(im.at(x, y, 1) - soil.g) + std::abs(im.at(x, y, 2) - soil.b) > 0.03f;
}

// Share of footprint pixels that show grass (differ from the soil colour).
Coverage coverage(const Image& img, const Image& footprint, const glm::vec4& soil) {
  std::size_t inside = 0, covered = 0;
  for (int y = 0; y < img.height(); ++y) {
    for (int x = 0; x < img.width(); ++x) {
      if (!differs(footprint, x, y, soil)) continue;
      ++inside;
      covered += differs(img, x, y, soil);
    }
  }
  return {inside, inside > 0 ? static_cast<double>(covered) / static_cast<double>(inside) : 0.0};
}

// Share of all pixels that show grass.
double covered_share(const Image& img, const glm::vec4& soil) {
  std::size_t covered = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) covered += differs(img, x, y, soil);
  return static_cast<double>(covered) / static_cast<double>(img.pixel_count());
}

// Renders `far` alone from the scene's camera.
Image render_far(testing::GlScene& scene, FarField& far, render::PassStats* stats = nullptr) {
  scene.begin();
  far.update(scene.camera, scene.size());
  scene.target.bind();
  far.draw_far(scene.camera, scene.wind, 0.0, stats);
  return scene.read();
}

GrassMaps uniform_density(const Rect& rect, float density) {
  Image img(8, 8, 1);
  for (float& v : img.data()) v = density;
  return GrassMaps::from_images(rect, &img, nullptr, nullptr).value();
}

TEST_F(GrassFarFieldGl, DollyThroughTransitionsKeepsCoverage) {
  Meadow m;
  auto blades = generate_blades(m.field, m.blade, m.maps, m.ground, {0, 0, 0});
  ASSERT_TRUE(blades.ok());
  auto near = GrassField::create(std::move(*blades), m.render);
  ASSERT_TRUE(near.ok()) << near.error().message;
  auto far = FarField::create(m.field, m.blade, m.maps, m.ground, {0, 0, 0}, m.far);
  ASSERT_TRUE(far.ok()) << far.error().message;
  far->set_near(m.render.cull.near_distance, m.render.physics.wind_response, 60.0f, m.render.base_color, m.render.tip_color);
  // The footprint: the ground layer at full density and fade everywhere.
  FarFieldSettings full = m.far;
  full.clumps = false;
  full.mid_distance = 1.0f;  // fade 1 from 1 m on: the camera never comes closer
  full.mid_fade = 1.0f;
  full.coverage_gain = 10.0f;  // cover = 1 - exp(-10 * tau) ~ 1: every texel
  auto footprint_layer = FarField::create(m.field, m.blade, m.maps, m.ground, {0, 0, 0}, full);
  ASSERT_TRUE(footprint_layer.ok()) << footprint_layer.error().message;

  // 384 x 216: sub-pixel blades alias, and the per-frame coverage noise falls with the pixel count.
  testing::GlScene scene = testing::GlScene::create(384, 216);
  const int frames = 113;
  double prev = -1.0, worst = 0.0, lowest = 1.0;
  int worst_frame = -1, lowest_frame = -1;
  std::string curve;
  for (int i = 0; i < frames; ++i) {
    // 1 m per frame through both transitions, as a dolly zoom: the field keeps its size on
    // screen, so every frame measures coverage over thousands of pixels.
    const double d = 8.0 + 1.0 * i;
    const double elevation = 0.35;  // rad
    scene.camera.perspective().fov_y = static_cast<float>(2.0 * std::atan(14.0 / d));
    scene.camera.set_position({0.0, d * std::sin(elevation), d * std::cos(elevation)});
    scene.camera.look_at({0.0, 0.0, 0.0});
    scene.begin();
    footprint_layer->update(scene.camera, scene.size());
    footprint_layer->draw_far(scene.camera, scene.wind, 0.0);
    const Image footprint = scene.read();
    scene.begin();
    near->update(scene.camera, scene.size(), 0.0, 0.0f, scene.wind);
    far->update(scene.camera, scene.size());
    scene.target.bind();
    near->draw_blades(scene.camera);
    far->draw_far(scene.camera, scene.wind, 0.0);
    const Image img = scene.read();
    if (i == 8 || i == 20 || i == 40) testing::save_png(img, "grass_dolly_" + std::to_string(i));
    const Coverage cov = coverage(img, footprint, scene.clear_color);
    EXPECT_GE(cov.footprint_pixels, kMinFootprintPixels) << "frame " << i;
    const double c = cov.share;
    if (c < lowest) {
      lowest = c;
      lowest_frame = i;
    }
    curve += std::to_string(static_cast<int>(d)) + ":" + std::to_string(c).substr(0, 5) + " ";
    if (prev >= 0.0 && std::abs(c - prev) > worst) {
      worst = std::abs(c - prev);
      worst_frame = i;
    }
    prev = c;
  }
  std::printf("coverage by distance: %s\n", curve.c_str());
  RecordProperty("worst_coverage_step", std::to_string(worst));
  RecordProperty("worst_frame", std::to_string(worst_frame));
  RecordProperty("lowest_coverage", std::to_string(lowest));
  EXPECT_LE(worst, 0.01) << "at frame " << worst_frame << "; curve " << curve;
  EXPECT_GE(lowest, kMinCoverage) << "at frame " << lowest_frame << "; curve " << curve;
}

}  // namespace
}  // namespace sylva::grass

namespace sylva::grass {
namespace {

// Seed 003 §2.4.2 overcrowding guard (grass.far.dense_extra_billboards): at density 0.8 every tile
// gets 4 clumps more (1151 -> 1551 over 100 tiles), and the shifted strand threshold keeps the
// covered share of a clumps-only view of the 40 m patch (4 to 44 m away) within kDenseTolerance
// (relative) of the plain rule's, while the picture does change. Measured on llvmpipe: 0.1514 off,
// 0.1480 on (-2.2 %); keeping the strand count instead (k = n / (n + 4)) gave +8 %.
constexpr double kDenseTolerance = 0.05;

TEST_F(GrassFarFieldGl, DenseExtraBillboardsKeepTheCoverage) {
  Meadow m;
  m.maps = uniform_density({{-20.0, -20.0}, {20.0, 20.0}}, 0.8f);  // 10 x 10 tiles of 4 m
  m.far.ground = false;
  m.far.clump_fade_in = 0.0f;
  m.far.mid_distance = 10000.0f;
  m.far.mid_fade = 0.0f;
  testing::GlScene scene = testing::GlScene::create(384, 216);
  scene.camera.set_position({0.0, 8.0, 24.0});
  scene.camera.look_at({0.0, 0.0, 2.0});
  auto draw = [&](bool dense, std::size_t& count, std::uint64_t& drawn) {
    FarFieldSettings far = m.far;
    far.dense_extra_billboards = dense;
    auto f = FarField::create(m.field, m.blade, m.maps, m.ground, {0, 0, 0}, far);
    EXPECT_TRUE(f.ok()) << f.error().message;
    f->set_near(0.5f, m.render.physics.wind_response, 60.0f, m.render.base_color, m.render.tip_color);
    const Image img = render_far(scene, *f);
    count = f->clump_count();
    drawn = f->last_clumps_drawn();
    return img;
  };
  std::size_t count_off = 0, count_on = 0;
  std::uint64_t drawn_off = 0, drawn_on = 0;
  const Image off = draw(false, count_off, drawn_off);
  const Image on = draw(true, count_on, drawn_on);
  testing::save_png(on, "grass_dense_extra");
  const double share_off = covered_share(off, scene.clear_color), share_on = covered_share(on, scene.clear_color);
  std::size_t changed = 0;
  for (int y = 0; y < on.height(); ++y)
    for (int x = 0; x < on.width(); ++x) changed += differs(on, x, y, glm::vec4(off.at(x, y, 0), off.at(x, y, 1), off.at(x, y, 2), 1.0f));
  std::printf("clumps off %zu on %zu (drawn %llu / %llu), covered share off %.4f on %.4f, changed %.4f\n", count_off, count_on,
              static_cast<unsigned long long>(drawn_off), static_cast<unsigned long long>(drawn_on), share_off, share_on,
              static_cast<double>(changed) / static_cast<double>(on.pixel_count()));
  EXPECT_EQ(count_on - count_off, 4u * 100u);  // dense_extra_per_tile x tiles
  EXPECT_GT(drawn_on, drawn_off);
  EXPECT_GT(share_off, 0.1);  // the patch is seen
  EXPECT_NEAR(share_on / share_off, 1.0, kDenseTolerance);
  EXPECT_GT(static_cast<double>(changed) / static_cast<double>(on.pixel_count()), 0.03);  // other clumps, other strands
}

// Seed 003 §2.5 / Fig. 3.15 (grass.far.noise_subregions): a uniform density 0.5 ground layer seen
// from straight above at 16 px/m, texture repeat 2 m, far tiles of 4 m. Off, the picture repeats
// with the texture (shifted by one far tile = two repeats = 64 px, the grass/soil pattern is the
// same); on, neighbouring tiles show different parts of the texture (about half the pixels
// differ, as for independent patterns at coverage 0.5), and the covered share stays.
TEST_F(GrassFarFieldGl, NoiseSubregionsBreakTheRepeatAndKeepTheCoverage) {
  Meadow m;
  m.maps = uniform_density({{-20.0, -20.0}, {20.0, 20.0}}, 0.5f);
  m.far.clumps = false;
  m.far.mid_distance = 1.0f;  // fade 1 from 1 m on
  m.far.mid_fade = 1.0f;
  m.far.coverage_gain = 10.0f;  // cover ~ 1: the texel share is the density
  m.far.texture_scale = 2.0f;
  m.far.noise_tile = 4.0f;
  testing::GlScene scene = testing::GlScene::create(256, 144);
  const double height = 10.0;
  scene.camera.perspective().fov_y = static_cast<float>(2.0 * std::atan(4.5 / height));  // 144 px = 9 m
  scene.camera.set_position({0.0, height, 0.0});
  scene.camera.set_yaw_pitch(0.0f, -1.5707963f);
  auto draw = [&](bool sub) {
    FarFieldSettings far = m.far;
    far.noise_subregions = sub;
    auto f = FarField::create(m.field, m.blade, m.maps, m.ground, {0, 0, 0}, far);
    EXPECT_TRUE(f.ok()) << f.error().message;
    f->set_near(m.render.cull.near_distance, m.render.physics.wind_response, 60.0f, m.render.base_color, m.render.tip_color);
    return render_far(scene, *f);
  };
  const int shift = 64;  // one far tile
  auto repeat_mismatch = [&](const Image& img) {
    std::size_t n = 0, differ = 0;
    for (int y = 0; y < img.height(); ++y) {
      for (int x = 0; x + shift < img.width(); ++x) {
        ++n;
        differ += differs(img, x, y, scene.clear_color) != differs(img, x + shift, y, scene.clear_color);
      }
    }
    return static_cast<double>(differ) / static_cast<double>(n);
  };
  const Image off = draw(false);
  const Image on = draw(true);
  testing::save_png(on, "grass_noise_subregions");
  const double share_off = covered_share(off, scene.clear_color), share_on = covered_share(on, scene.clear_color);
  const double rep_off = repeat_mismatch(off), rep_on = repeat_mismatch(on);
  std::printf("covered share off %.4f on %.4f; pixels differing one tile apart: off %.4f on %.4f\n", share_off, share_on,
              rep_off, rep_on);
  EXPECT_NEAR(share_off, 0.5, 0.05);
  EXPECT_NEAR(share_on, share_off, 0.02);
  EXPECT_LT(rep_off, 0.1);
  EXPECT_GT(rep_on, 0.35);
}

// Seed 003 §4.3 (grass.far.coarse_ground): a hilly 384 m field of 1 m samples, its ground layer
// drawn over every texel (density 1, under-layer), camera 9 m up looking along it; coarse chunks
// (4 x 4 ordinary chunks, 4 m spacing) from 40 m on. Triangles drawn fall; the layer covers the
// same share of the picture (the coarse surface differs only in silhouettes far away) and has no
// hole: no clear pixel below the farthest layer pixel of its column (a crack at a coarse/ordinary
// border would show one), as without the option.
TEST_F(GrassFarFieldGl, CoarseGroundDrawsFewerTrianglesWithoutHoles) {
  Meadow m;
  m.ground = HeightField(385, 385, 1.0, {0.0, 0.0});
  for (int j = 0; j < 385; ++j)
    for (int i = 0; i < 385; ++i)
      m.ground.sample(i, j) = static_cast<float>(2.5 * std::sin(0.35 * i + 0.7 * std::sin(0.1 * j)) +
                                                 1.5 * std::cos(0.3 * j + 0.4 * std::sin(0.13 * i)));
  m.ground.update_range();
  m.maps = GrassMaps::uniform({{0.0, 0.0}, {384.0, 384.0}});
  m.far.clumps = false;
  m.far.under_layer = true;  // every texel where the density is 1
  m.far.mid_distance = 1.0f;
  m.far.mid_fade = 1.0f;
  m.far.far_distance = 100000.0f;
  m.far.far_fade = 0.0f;
  m.far.max_slope_deg = 90.0f;
  m.far.ground_spacing = 1.0f;
  m.far.coarse_distance = 40.0f;
  m.far.coarse_spacing_factor = 4;
  testing::GlScene scene = testing::GlScene::create(384, 216);
  scene.camera.set_position({192.0, 9.0, 12.0});
  scene.camera.look_at({192.0, 0.0, 110.0});
  struct Shot {
    Image img;
    render::PassStats stats;
    std::uint64_t coarse = 0;
  };
  auto draw = [&](bool coarse) {
    FarFieldSettings far = m.far;
    far.coarse_ground = coarse;
    auto f = FarField::create(m.field, m.blade, m.maps, m.ground, {192, 0, 192}, far);
    EXPECT_TRUE(f.ok()) << f.error().message;
    f->set_near(m.render.cull.near_distance, m.render.physics.wind_response, 60.0f, m.render.base_color, m.render.tip_color);
    Shot s;
    s.img = render_far(scene, *f, &s.stats);
    s.coarse = f->last_coarse_chunks_drawn();
    return s;
  };
  // Clear pixels between a column's nearest (bottom) and farthest layer pixel.
  auto holes = [&](const Image& img) {
    const bool top_down = covered_share(img, scene.clear_color) > 0.0 && differs(img, img.width() / 2, img.height() - 1, scene.clear_color);
    std::size_t n = 0;
    for (int x = 0; x < img.width(); ++x) {
      int last = -1;  // rows counted from the near (bottom) edge
      for (int r = 0; r < img.height(); ++r)
        if (differs(img, x, top_down ? img.height() - 1 - r : r, scene.clear_color)) last = r;
      for (int r = 0; r < last; ++r) n += !differs(img, x, top_down ? img.height() - 1 - r : r, scene.clear_color);
    }
    return n;
  };
  const Shot off = draw(false);
  const Shot on = draw(true);
  testing::save_png(off.img, "grass_coarse_off");
  testing::save_png(on.img, "grass_coarse_on");
  const double share_off = covered_share(off.img, scene.clear_color), share_on = covered_share(on.img, scene.clear_color);
  const std::size_t holes_off = holes(off.img), holes_on = holes(on.img);
  std::printf("ground triangles off %llu on %llu (coarse chunks %llu); covered share off %.4f on %.4f; holes off %zu on %zu\n",
              static_cast<unsigned long long>(off.stats.triangles), static_cast<unsigned long long>(on.stats.triangles),
              static_cast<unsigned long long>(on.coarse), share_off, share_on, holes_off, holes_on);
  EXPECT_EQ(off.coarse, 0u);
  EXPECT_GT(on.coarse, 0u);
  EXPECT_LT(on.stats.triangles * 3, off.stats.triangles);
  EXPECT_GT(share_off, 0.5);
  EXPECT_NEAR(share_on, share_off, 0.01);
  EXPECT_EQ(holes_off, 0u);
  EXPECT_EQ(holes_on, holes_off);
}

}  // namespace
}  // namespace sylva::grass
