// The sky dome (per-vertex table look-up, per-pixel phase functions and sun disk) draws the same
// picture as the per-pixel sky it replaced, sky_color() of every pixel's direction, and covers
// every pixel at depth 0, over view directions from straight down to straight up, narrow to
// wide fields of view, and suns high, low, behind the camera and below the horizon.
#include "support/render_test_support.hpp"

#include <sylva/render/camera.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/sky_dome.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace sylva::render {
namespace {

constexpr int kW = 96;
constexpr int kH = 64;

using SkyDomeTest = GlTest;

// The full-screen per-pixel sky the dome replaced, as the reference.
Program per_pixel_sky() {
  embedded::register_render_shaders();
  register_shader_source("rtest/sky_per_pixel.vert",
                         "#version 450 core\n"
                         "uniform mat4 u_inv_view_projection;\n"
                         "out vec3 v_direction;\n"
                         "void main() {\n"
                         "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;\n"
                         "  gl_Position = vec4(p, 0.0, 1.0);\n"
                         "  vec4 near_point = u_inv_view_projection * vec4(p, 1.0, 1.0);\n"
                         "  v_direction = near_point.xyz / near_point.w;\n"
                         "}\n");
  register_shader_source("rtest/sky_per_pixel.frag",
                         "#version 450 core\n"
                         "#include \"render/lib/sky.glsl\"\n"
                         "in vec3 v_direction;\n"
                         "out vec4 o_color;\n"
                         "void main() { o_color = vec4(sky_color(normalize(v_direction)), 1.0); }\n");
  return test::build_or_fail({"rtest/sky_per_pixel.vert", "rtest/sky_per_pixel.frag"});
}

struct View {
  const char* name;
  float yaw;
  float pitch;
  float fov_y;
};

struct Sun {
  const char* name;
  float azimuth;  // from the camera's yaw
  float elevation;
};

// Pixels farther from the reference than 0.5 % + 1e-4 (HDR radiance, below one 8-bit step
// after tone mapping), those farther than 8 % + 1e-2, the worst relative difference (of
// values over 1e-3), and the magenta (uncovered) pixels.
struct Comparison {
  int off = 0;
  int far = 0;
  int holes = 0;
  float worst = 0.0f;
};

Comparison compare_with_per_pixel(SkyRenderer& sky, Program& reference, const View& view, const Sun& sun) {
  Camera cam;
  cam.set_aspect(kW, kH);
  cam.perspective().fov_y = view.fov_y;
  cam.set_yaw_pitch(view.yaw, view.pitch);
  Lighting lighting;
  lighting.sun_direction = sun_direction(view.yaw + sun.azimuth, sun.elevation);
  Result<Framebuffer> fb = Framebuffer::create({.width = kW, .height = kH, .color_formats = {GL_RGBA32F}});
  EXPECT_TRUE(fb.ok());
  fb->bind();
  apply_reversed_z_state();
  fb->clear({1, 0, 1, 1}, 0.0f);
  sky.draw(cam, lighting);
  Result<Image> dome = read_color(*fb);
  // The reference into the same target, with the same lighting block bound.
  fb->clear({1, 0, 1, 1}, 0.0f);
  reference.set("u_inv_view_projection", glm::inverse(cam.view_projection()));
  reference.use();
  glDisable(GL_DEPTH_TEST);
  VertexArray vao = VertexArray::create();
  vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glEnable(GL_DEPTH_TEST);
  Result<Image> expected = read_color(*fb);
  EXPECT_TRUE(dome.ok() && expected.ok());
  Comparison result;
  if (!dome.ok() || !expected.ok()) return result;
  result.holes = test::count_color(*dome, 1, 0, 1, 0.0f);
  for (int row = 0; row < kH; ++row) {
    for (int x = 0; x < kW; ++x) {
      bool off = false;
      bool far = false;
      for (int c = 0; c < 3; ++c) {
        const float e = expected->at(x, row, c);
        const float d = std::abs(dome->at(x, row, c) - e);
        result.worst = std::max(result.worst, d / std::max(e, 1.0e-3f));
        off = off || d > 5.0e-3f * e + 1.0e-4f;
        far = far || d > 0.08f * e + 1.0e-2f;
      }
      result.off += off ? 1 : 0;
      result.far += far ? 1 : 0;
    }
  }
  if (result.off > 0 || result.holes > 0) {
    test::save_for_inspection(*dome, std::string("sky_dome_") + view.name + "_" + sun.name);
  }
  return result;
}

// With the sun up, at most 2 pixels of a view differ by more than 0.5 % (none by 1.5 %). With
// the sun below the horizon (twilight) neighbouring table columns differ up to a hundredfold and
// the interpolation is off by up to ~7 % (or 1e-2 where the sky is nearly black; at most 2
// pixels a view beyond), e.g. 1020 of "low"'s pixels over 0.5 %: bounded here, not hidden
// (modules/render/README.md).
// Seen red: with the zenith's fan left out, the views up showed magenta holes (12 each);
// with the table's rows not cut (kRowSteps 1), 25 of the 40 view / sun pairs had pixels off.
TEST_F(SkyDomeTest, MatchesThePerPixelSkyAndCoversEveryPixel) {
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok()) << sky.error().describe();
  Program reference = per_pixel_sky();
  ASSERT_TRUE(reference);
  const View views[] = {
      {"down", 0.2f, -1.5697963f, 1.0471976f}, {"steep", 1.1f, -0.6f, 1.0471976f},
      {"horizon", -0.4f, 0.0f, 1.0471976f},     {"low", 2.5f, 0.05f, 0.3f},
      {"raised", -2.0f, 0.4f, 1.0471976f},     {"up", 0.7f, 1.5697963f, 1.0471976f},
      {"wide", 0.0f, 0.1f, 2.8f},              {"wide_down", 3.0f, -1.2f, 2.8f},
  };
  const Sun suns[] = {
      {"ahead_high", 0.1f, 1.2f}, {"ahead_low", -0.05f, 0.05f}, {"behind", 3.1f, 0.4f},
      {"side_low", 1.5f, 0.15f}, {"set", 0.3f, -0.08f},
  };
  int compared = 0;
  for (const View& view : views) {
    for (const Sun& sun : suns) {
      const Comparison c = compare_with_per_pixel(*sky, reference, view, sun);
      EXPECT_EQ(c.holes, 0) << view.name << " / " << sun.name;
      if (sun.elevation > 0.0f) {
        EXPECT_LE(c.off, 2) << view.name << " / " << sun.name << ": worst relative difference " << c.worst;
        EXPECT_LT(c.worst, 0.015f) << view.name << " / " << sun.name;
      }
      EXPECT_LE(c.far, 2) << view.name << " / " << sun.name << ": worst relative difference " << c.worst;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 40);
}

// Looking straight at the sun through a narrow field of view: the disk and its limb darkening
// come out as the per-pixel sky draws them (the phase functions' peak is per pixel too).
TEST_F(SkyDomeTest, SunDiskMatchesThePerPixelSky) {
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok());
  Program reference = per_pixel_sky();
  ASSERT_TRUE(reference);
  for (const float elevation : {0.02f, 0.5f}) {
    const View view{"sun", 0.4f, elevation, 0.02f};
    const Comparison c = compare_with_per_pixel(*sky, reference, view, Sun{"in_view", 0.0f, elevation});
    EXPECT_EQ(c.holes, 0) << elevation;
    EXPECT_EQ(c.off, 0) << elevation << ": worst relative difference " << c.worst;
  }
}

// Every edge of the mesh borders exactly two triangles: a closed surface around the camera, so
// no direction misses it.
TEST(SkyDome, MeshIsClosed) {
  const SkyDomeMesh mesh = build_sky_dome();
  ASSERT_EQ(mesh.indices.size() % 3, 0u);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = mesh.indices[t + k];
      const std::uint32_t b = mesh.indices[t + (k + 1) % 3];
      ASSERT_LT(std::max(a, b), mesh.directions.size());
      ++edges[{std::min(a, b), std::max(a, b)}];
    }
  }
  for (const auto& [edge, count] : edges) ASSERT_EQ(count, 2) << edge.first << "-" << edge.second;
  for (const glm::vec3& d : mesh.directions) ASSERT_NEAR(glm::length(d), 1.0f, 1.0e-5f);
  // A ring on the horizon, and the table's first rows (0.25 degrees up) cut finer.
  const std::vector<float> rings = sky_dome_ring_elevations();
  EXPECT_TRUE(std::find(rings.begin(), rings.end(), 0.0f) != rings.end());
  EXPECT_GE(std::count_if(rings.begin(), rings.end(), [](float e) { return e > 0.0f && e <= 0.0045f; }), 4);
}

}  // namespace
}  // namespace sylva::render
