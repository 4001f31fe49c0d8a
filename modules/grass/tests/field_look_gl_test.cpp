// The look of a whole field across seed 003's levels of detail, seen like a walker sees a meadow
// (1.7 m above flat ground, looking along it): blades near, clumps in the middle, the ground
// layer far, with the under-layer between the blades.
//  - No band: the field's mean luminance in the distance bins 5-35 m (blades), 35-150 m (blades
//    thinning into clumps) and 150 m+ (ground layer) stays within kBandTolerance of the near bin.
//    The shipped LOD before the under-layer (terrain showing between thinning blades and clumps,
//    far layers coloured and lit on their own) showed a darker band from 35 to 150 m in the
//    meadow; the test also renders clumps 30 % darker than calibrated and requires the metric to
//    see that band, so it can fail.
//  - Blades match the ground beneath them: in 8-30 m, the mean colour of blade pixels and of the
//    undergrowth pixels between them (pixels the blade-free picture shows unchanged) agree within
//    kGroundTolerance in luminance, and their chromaticities within kChromaTolerance.
// The ground is flat, so every pixel's distance is the distance along its ray to y = 0.
#include <sylva/grass/far_field.hpp>
#include <sylva/grass/generator.hpp>
#include <sylva/grass/grass_field.hpp>
#include <sylva/render/testing.hpp>

#include "support/gl_scene.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

namespace sylva::grass {
namespace {

using GrassFieldLookGl = render::GlTest;

constexpr double kBandTolerance = 0.06;    // |bin mean / near-bin mean - 1|
constexpr double kGroundTolerance = 0.15;  // |blade mean / undergrowth mean - 1| (luminance)
constexpr double kChromaTolerance = 0.06;  // distance of (r, g) chromaticities

double luminance(const Image& im, int x, int y) {
  return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
}

struct Walker {
  GrassFieldSettings field;
  BladeSettings blade;
  GrassRenderSettings render;
  FarFieldSettings far;
  HeightField ground{201, 201, 12.0, {-1200.0, -2200.0}};
  // Blades in a strip ahead of the camera; clumps and the ground layer continue beyond it.
  GrassMaps maps = GrassMaps::uniform({{-20.0, -60.0}, {20.0, 2.0}});
  Walker() {
    field.density = 100.0f;
    render.simulate = false;
    far.clump_margin = 160.0f;
    far.ground_margin = 2000.0f;
    far.ground_spacing = 4.0f;
  }
};

struct Pictures {
  Image full;
  Image without_blades;
};

Pictures render_walker(const Walker& w, testing::GlScene& scene) {
  auto blades = generate_blades(w.field, w.blade, w.maps, w.ground, {0, 0, 0});
  EXPECT_TRUE(blades.ok());
  auto near = GrassField::create(std::move(*blades), w.render);
  EXPECT_TRUE(near.ok()) << near.error().message;
  auto far = FarField::create(w.field, w.blade, w.maps, w.ground, {0, 0, 0}, w.far);
  EXPECT_TRUE(far.ok()) << far.error().message;
  far->set_near(w.render.cull.near_distance, w.render.physics.wind_response, 60.0f, w.render.base_color, w.render.tip_color,
                w.render.shading.ambient, w.render.shading.translucency);
  near->set_sorted_draw_order(true);
  Pictures out;
  for (int pass = 0; pass < 2; ++pass) {
    scene.begin();
    near->update(scene.camera, scene.size(), 0.0, 0.0f, scene.wind);
    far->update(scene.camera, scene.size());
    scene.target.bind();
    if (pass == 0) near->draw_blades(scene.camera);
    far->draw_far(scene.camera, scene.wind, 0.0);
    (pass == 0 ? out.full : out.without_blades) = scene.read();
  }
  return out;
}

// Suns (towards the sun): mid-morning from behind-right, and low against the light (translucent
// blades glow, the case a flat far layer gets most wrong).
constexpr std::array<glm::vec3, 2> kSuns{glm::vec3(0.5f, 0.8f, 0.3f), glm::vec3(0.3f, 0.35f, -1.0f)};

testing::GlScene walker_scene(const glm::vec3& sun = kSuns[0]) {
  testing::GlScene scene = testing::GlScene::create(800, 450);
  scene.lighting.sun_direction = glm::normalize(sun);
  scene.lighting.sun_intensity = 1.5f;  // the picture stays below 1 (RGBA8, no tone mapping)
  scene.camera.perspective().fov_y = glm::radians(50.0f);
  scene.camera.set_position({0.0, 1.7, 0.0});
  scene.camera.look_at({0.0, 1.7 - std::tan(glm::radians(4.0)) * 100.0, -100.0});
  return scene;
}

// Distance along the ray of pixel (x, y) to the ground plane y = 0; negative above the horizon.
double ground_distance(const testing::GlScene& scene, int x, int y) {
  const glm::ivec2 size = scene.size();
  const glm::mat4 inv = glm::inverse(scene.camera.view_projection());
  // Picture rows run top-down; NDC y up.
  const glm::vec4 ndc(2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(size.x) - 1.0f,
                      1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(size.y), 0.5f, 1.0f);
  const glm::vec4 p = inv * ndc;
  const glm::vec3 dir = glm::normalize(glm::vec3(p) / p.w);
  if (!(dir.y < -1e-6f)) return -1.0;
  const double h = scene.camera.position().y;
  return h / -static_cast<double>(dir.y);
}

// Mean luminance per distance bin over the middle third of the columns (inside the blade strip).
constexpr std::array<double, 4> kBins{5.0, 35.0, 150.0, 2000.0};

std::array<double, 3> bin_means(const Image& img, const testing::GlScene& scene) {
  std::array<double, 3> sum{}, count{};
  for (int y = 0; y < img.height(); ++y) {
    for (int x = img.width() / 3; x < 2 * img.width() / 3; ++x) {
      const double d = ground_distance(scene, x, y);
      for (std::size_t b = 0; b < 3; ++b) {
        if (d >= kBins[b] && d < kBins[b + 1]) {
          sum[b] += luminance(img, x, y);
          count[b] += 1.0;
        }
      }
    }
  }
  std::array<double, 3> mean{};
  for (std::size_t b = 0; b < 3; ++b) {
    EXPECT_GE(count[b], 1000.0) << "too few pixels in bin " << b;
    mean[b] = count[b] > 0.0 ? sum[b] / count[b] : 0.0;
  }
  return mean;
}

double worst_band(const std::array<double, 3>& m) {
  return std::max(std::abs(m[1] / m[0] - 1.0), std::abs(m[2] / m[0] - 1.0));
}

TEST_F(GrassFieldLookGl, NoBrightnessBandWhereBladesThinIntoClumps) {
  const Walker shipped;
  for (std::size_t sun = 0; sun < kSuns.size(); ++sun) {
    testing::GlScene lit = walker_scene(kSuns[sun]);
    const Pictures p = render_walker(shipped, lit);
    testing::save_png(p.full, "grass_field_look_sun" + std::to_string(sun));
    const std::array<double, 3> m = bin_means(p.full, lit);
    std::printf("sun %zu: mean luminance 5-35 m %.4f, 35-150 m %.4f, 150 m+ %.4f\n", sun, m[0], m[1], m[2]);
    RecordProperty("band_sun" + std::to_string(sun), std::to_string(worst_band(m)));
    EXPECT_LE(worst_band(m), kBandTolerance) << "sun " << sun << ": bins " << m[0] << " " << m[1] << " " << m[2];
  }

  // The metric can fail: clumps 30 % darker than calibrated make the 35-150 m band it looks for.
  Walker dark = shipped;
  dark.far.clump_brightness = 0.7f * shipped.far.clump_brightness;
  testing::GlScene scene = walker_scene();
  const std::array<double, 3> q = bin_means(render_walker(dark, scene).full, scene);
  std::printf("clumps 30 %% darker: 5-35 m %.4f, 35-150 m %.4f, 150 m+ %.4f\n", q[0], q[1], q[2]);
  EXPECT_GT(worst_band(q), kBandTolerance) << "the metric must see a band of darker clumps";
}

TEST_F(GrassFieldLookGl, BladesMatchTheGroundBeneathThem) {
  testing::GlScene scene = walker_scene();
  const Walker shipped;
  const Pictures p = render_walker(shipped, scene);
  glm::dvec3 blade_sum(0.0), ground_sum(0.0);
  double blade_n = 0.0, ground_n = 0.0;
  for (int y = 0; y < p.full.height(); ++y) {
    for (int x = p.full.width() / 3; x < 2 * p.full.width() / 3; ++x) {
      const double d = ground_distance(scene, x, y);
      if (d < 8.0 || d > 30.0) continue;
      const glm::dvec3 c(p.full.at(x, y, 0), p.full.at(x, y, 1), p.full.at(x, y, 2));
      const glm::dvec3 g(p.without_blades.at(x, y, 0), p.without_blades.at(x, y, 1), p.without_blades.at(x, y, 2));
      const bool blade = glm::length(c - g) > 1.5 / 255.0;
      (blade ? blade_sum : ground_sum) += c;
      (blade ? blade_n : ground_n) += 1.0;
    }
  }
  ASSERT_GT(blade_n, 2000.0);
  ASSERT_GT(ground_n, 2000.0);
  const glm::dvec3 b = blade_sum / blade_n, g = ground_sum / ground_n;
  auto lum = [](const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; };
  auto chroma = [](const glm::dvec3& c) { return glm::dvec2(c.r, c.g) / std::max(c.r + c.g + c.b, 1e-9); };
  const double ratio = lum(b) / lum(g);
  const double chroma_distance = glm::length(chroma(b) - chroma(g));
  std::printf("8-30 m: blades (%.3f %.3f %.3f) on %.0f px, undergrowth (%.3f %.3f %.3f) on %.0f px: luminance ratio %.3f, "
              "chroma distance %.4f\n",
              b.r, b.g, b.b, blade_n, g.r, g.g, g.b, ground_n, ratio, chroma_distance);
  RecordProperty("luminance_ratio", std::to_string(ratio));
  RecordProperty("chroma_distance", std::to_string(chroma_distance));
  EXPECT_LE(std::abs(ratio - 1.0), kGroundTolerance);
  EXPECT_LE(chroma_distance, kChromaTolerance);
}

}  // namespace
}  // namespace sylva::grass
