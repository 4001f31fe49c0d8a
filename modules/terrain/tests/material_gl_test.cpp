// The terrain material on headless llvmpipe (issue 19): snow placed by altitude in metres (a
// 300 m lowland hill has none, the same hill at 3000 m is white on top, a 60 N late winter brings
// it down), near ground with detail at 2 m above it, and cliffs textured without stretching.
#include <sylva/render/testing.hpp>
#include <sylva/terrain/renderer.hpp>

#include "../src/material_gpu.hpp"
#include "support/gl_support.hpp"
#include "support/terrain_test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace sylva::terrain {
namespace {

using namespace testing;
using TerrainMaterialGl = render::GlTest;

const glm::vec4 kSky(0.3f, 0.5f, 0.9f, 1.0f);

std::unique_ptr<TerrainRenderer> make_renderer(const HeightField& field, const TerrainRenderSettings& rs = {}) {
  ChunkTreeSettings ts;
  ts.leaf_dimension = 33;
  auto tree = std::make_shared<const ChunkTree>(std::move(ChunkTree::build(field, ts)).value());
  TerrainRenderSettings settings = rs;
  settings.receive_shadows = false;
  return std::move(TerrainRenderer::create(tree, &field, settings)).value();
}

render::Camera look(const glm::dvec3& eye, float yaw_deg, float pitch_deg, int w, int h) {
  render::Camera c;
  c.set_position(eye);
  c.set_yaw_pitch(glm::radians(yaw_deg), glm::radians(pitch_deg));
  c.perspective().fov_y = glm::radians(60.0f);
  c.perspective().near_plane = 0.05f;
  c.perspective().far_plane = 0.0f;
  c.set_aspect(w, h);
  return c;
}

float luma(const Image& im, int x, int y) { return 0.2126f * im.at(x, y, 0) + 0.7152f * im.at(x, y, 1) + 0.0722f * im.at(x, y, 2); }

// A round 300 m hill (Gaussian, sigma 300 m: at most 31 degrees steep) standing on `base` metres,
// on a 2 km square, 8 m spacing.
HeightField hill(float base) {
  return make_field(257, 257, 8.0, [&](int i, int j) {
    const double x = i * 8.0 - 1024.0, z = j * 8.0 - 1024.0;
    return static_cast<float>(base + 300.0 * std::exp(-(x * x + z * z) / (2.0 * 300.0 * 300.0)));
  });
}

struct SnowCount {
  std::size_t snow = 0;     // white pixels of the materials view
  std::size_t terrain = 0;  // pixels that are not sky
  double snow_luma = 0.0;   // mean shaded luminance where the materials view is white
  double other_luma = 0.0;  // mean shaded luminance of the other terrain pixels
};

// The hill from 1.3 km south-west, 18 degrees down: materials view and shaded view.
SnowCount count_snow(float base, const Climate& climate) {
  const HeightField field = hill(base);
  auto r = make_renderer(field);
  r->set_climate(climate);
  GlTarget target = GlTarget::create(256, 144);
  target.lighting.fog_density = 0.0f;
  target.lighting.sun_intensity = 1.2f;  // no tone mapping here: keep the picture below 1
  const double d = 1300.0;
  const render::Camera cam = look({1024.0 - d * 0.7, base + 0.36 * d, 1024.0 + d * 0.7}, -45.0f, -18.0f, 256, 144);
  r->settings().debug_view = DebugView::kMaterials;
  const Image layers = target.render(*r, cam, kSky);
  r->settings().debug_view = DebugView::kShaded;
  const Image shaded = target.render(*r, cam, kSky);
  const std::string name = std::to_string(static_cast<int>(base)) + "_" + std::to_string(static_cast<int>(climate.latitude_deg)) +
                           "_" + std::to_string(static_cast<int>(climate.season * 100.0f));
  save_png(layers, "material_layers_" + name);
  save_png(shaded, "material_shaded_" + name);
  SnowCount c;
  std::size_t other = 0;
  for (int y = 0; y < 144; ++y)
    for (int x = 0; x < 256; ++x) {
      if (is_color(layers, x, y, kSky)) continue;
      ++c.terrain;
      const bool white = layers.at(x, y, 0) > 0.9f && layers.at(x, y, 1) > 0.9f && layers.at(x, y, 2) > 0.9f;
      (white ? c.snow_luma : c.other_luma) += luma(shaded, x, y);
      if (white) {
        ++c.snow;
      } else {
        ++other;
      }
    }
  if (c.snow > 0) c.snow_luma /= static_cast<double>(c.snow);
  if (other > 0) c.other_luma /= static_cast<double>(other);
  return c;
}

// Issue 19: a user's 16-bit lowland map (relief ~300 m) got snow on its highest hill because the
// bands were shares of the relief. In metres, a 300 m hill has no snow in summer or in a 45 N
// winter (line ~560 m); the same hill raised to 3000 m is white on top; 60 N at the end of
// winter (line at the sea) covers even the lowland hill.
TEST_F(TerrainMaterialGl, SnowLiesAboveTheSnowLineInMetres) {
  const SnowCount low = count_snow(0.0f, {45.0f, 0.4f});
  EXPECT_GT(low.terrain, 256u * 144u / 2);
  EXPECT_EQ(low.snow, 0u) << "snow on a 300 m hill in summer";
  EXPECT_EQ(count_snow(0.0f, {45.0f, 0.9f}).snow, 0u) << "snow on a 300 m hill in a 45 N winter (line ~560 m)";

  const SnowCount high = count_snow(2700.0f, {45.0f, 0.4f});
  EXPECT_GT(high.snow, high.terrain / 50) << "no snow on the top of a 3000 m hill (snow line 2800 m)";
  EXPECT_LT(high.snow, high.terrain / 2) << "snow below the snow line";
  EXPECT_GT(high.snow_luma, 2.0 * high.other_luma) << "the snow is not bright in the shaded picture";

  const SnowCount north_winter = count_snow(0.0f, {60.0f, 0.9f});
  EXPECT_GT(north_winter.snow, north_winter.terrain / 10) << "a 60 N late winter leaves the lowland bare";
}

// Contrast at the pixel scale: mean |L - mean of its 3x3 neighbourhood| / mean L over the lower
// third of the picture.
double near_detail(const Image& im) {
  double hf = 0.0, sum = 0.0;
  std::size_t n = 0;
  for (int y = im.height() * 2 / 3; y < im.height() - 1; ++y)
    for (int x = 1; x < im.width() - 1; ++x) {
      double mean = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) mean += luma(im, x + dx, y + dy);
      mean /= 9.0;
      hf += std::fabs(luma(im, x, y) - mean);
      sum += luma(im, x, y);
      ++n;
    }
  return hf / std::max(sum, 1e-9);
}

// "No blurry ground within 5 m of the camera" at 1280x720: a meadow seen from 2 m, looking 25
// degrees down (the lower third of the picture is ground 1.4-2.9 m away).
TEST_F(TerrainMaterialGl, NearGroundHasDetailAtThePixelScale) {
  const HeightField field = fbm_field(129, 129, 2.0, 3.0f, 5u);
  GlTarget target = GlTarget::create(1280, 720);
  target.lighting.fog_density = 0.0f;
  const glm::dvec3 eye(128.0, field.height(128.0, 128.0) + 2.0, 128.0);
  const render::Camera cam = look(eye, 30.0f, -25.0f, 1280, 720);
  auto r = make_renderer(field);
  const Image detailed = target.render(*r, cam, kSky);
  save_png(detailed, "material_near_ground");
  TerrainRenderSettings flat;
  flat.material.detail_strength = 0.0f;
  auto plain = make_renderer(field, flat);
  const Image smooth = target.render(*plain, cam, kSky);
  const double with = near_detail(detailed), without = near_detail(smooth);
  std::printf("near-ground contrast: %.4f with detail, %.4f without\n", with, without);
  EXPECT_GT(with, 0.012) << "the ground 1-3 m from the camera is blurry";
  EXPECT_LT(without, 0.004) << "the measure must tell flat layers from detail";
}

// A 200 m wall (the height rises over two 1 m samples: ~89 degrees) seen head-on from 80 m:
// planar (x/z) mapping smears the texture down the whole wall; triplanar keeps its grain
// round, so the luminance varies about as much along the vertical as along the horizontal.
TEST_F(TerrainMaterialGl, CliffTextureIsNotStretched) {
  const HeightField field = make_field(257, 257, 1.0, [](int i, int) { return i < 150 ? 0.0f : (i < 152 ? 100.0f * (i - 149) : 200.0f); });
  auto r = make_renderer(field);
  GlTarget target = GlTarget::create(320, 240);
  target.lighting.fog_density = 0.0f;
  target.lighting.sun_direction = glm::normalize(glm::vec3(-0.6f, 0.5f, 0.3f));  // lights the wall (it faces -x)
  const render::Camera cam = look({70.0, 100.0, 128.0}, -90.0f, 0.0f, 320, 240);
  r->settings().debug_view = DebugView::kShaded;
  const Image im = target.render(*r, cam, kSky);
  save_png(im, "material_cliff");
  double gx = 0.0, gy = 0.0;
  for (int y = 60; y < 180; ++y)
    for (int x = 80; x < 240; ++x) {
      ASSERT_FALSE(is_color(im, x, y, kSky)) << "the wall must fill the measured window";
      const double dx = luma(im, x + 1, y) - luma(im, x, y), dy = luma(im, x, y + 1) - luma(im, x, y);
      gx += dx * dx;
      gy += dy * dy;
    }
  std::printf("cliff gradient energy: horizontal %.4f, vertical %.4f, ratio %.2f\n", gx, gy, gy / std::max(gx, 1e-12));
  EXPECT_GT(gx, 1e-3) << "the wall has no texture";
  EXPECT_GT(gy / gx, 0.4) << "the wall's texture is stretched vertically";
  EXPECT_LT(gy / gx, 2.5);
}

// The per-chunk variants (material.glsl SYLVA_TERRAIN_FIRST_SCALE) leave out a detail scale only
// where its fade is 0 on every pixel: for ground at least `depth` in front of the camera, on any
// plane through a pixel's point, anywhere on the screen, the coarse derivatives of every 2x2 quad
// holding that pixel (neighbours' rays met on the same plane, as the rasteriser extrapolates)
// span at least 1/32 of each dropped scale's tile.
TEST(TerrainMaterialVariants, DroppedDetailScalesHaveFadedOnEveryPixel) {
  const double fov = 45.0 * 3.14159265358979 / 180.0, tile = 2.5;
  const int width = 1920, height = 1080;
  const double focal = 0.5 * height / std::tan(0.5 * fov);
  const double ratio[3] = {1.0, 5.3, 28.0};
  auto ray = [&](double x, double y) { return glm::dvec3((x + 0.5 - 0.5 * width) / focal, (0.5 * height - y - 0.5) / focal, 1.0); };
  int dropped = 0;
  double tightest = 1e9;
  for (double depth : {3.0, 40.0, 110.0, 250.0, 600.0, 1500.0, 3500.0, 8000.0, 30000.0}) {
    const int k = first_detail_scale(depth, fov, double(width) / height, height, static_cast<float>(tile));
    dropped += k;
    for (int px : {0, 1, width / 3, width / 2, width - 2}) {
      for (int py : {0, 1, height / 2, height - 2}) {
        const glm::dvec3 p = ray(px, py) * depth;  // view depth (z) = depth
        for (int a = 0; a < 90; a += 8) {
          for (int b = 0; b < 360; b += 30) {
            const double ar = a * 3.14159265358979 / 180.0, br = b * 3.14159265358979 / 180.0;
            glm::dvec3 n(std::sin(ar) * std::cos(br), std::sin(ar) * std::sin(br), -std::cos(ar));
            const glm::dvec3 dir = glm::normalize(ray(px, py));
            if (std::abs(glm::dot(n, dir)) < 1e-3) continue;
            if (glm::dot(n, dir) > 0.0) n = -n;
            auto on_plane = [&](double x, double y, glm::dvec3& q) {
              const glm::dvec3 r = ray(x, y);
              const double t = glm::dot(p, n) / glm::dot(r, n);
              q = r * t;
              return t > 0.0;
            };
            for (int ox : {-1, 0}) {
              for (int oy : {-1, 0}) {
                glm::dvec3 o, qx, qy;
                if (!on_plane(px + ox, py + oy, o) || !on_plane(px + ox + 1, py + oy, qx) ||
                    !on_plane(px + ox, py + oy + 1, qy)) {
                  continue;  // a neighbour's ray misses the plane: an unbounded footprint
                }
                const double footprint = std::max(glm::length(qx - o), glm::length(qy - o));
                for (int j = 0; j < k; ++j) {
                  const double texels = footprint / (tile * ratio[j]);
                  tightest = std::min(tightest, texels * 32.0);
                  ASSERT_GE(texels, 1.0 / 32.0) << "scale " << j << " dropped at depth " << depth << " pixel (" << px
                                                << ", " << py << ") tilt " << a << " azimuth " << b;
                }
              }
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(dropped, 12);  // first scales 0 0 0 1 1 2 2 3 3 over the depths
  EXPECT_EQ(first_detail_scale(3.0, fov, 16.0 / 9.0, height, 2.5f), 0);
  EXPECT_EQ(first_detail_scale(30000.0, fov, 16.0 / 9.0, height, 2.5f), 3);
  std::printf("tightest dropped-scale footprint: %.3f x the fade's end\n", tightest);
}

}  // namespace
}  // namespace sylva::terrain
