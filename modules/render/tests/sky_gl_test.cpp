// The sky renderer and the shared GLSL lighting library agree with their CPU twins: the
// atmosphere's radiance per pixel direction (above and below the horizon), the sun disk where
// the sun is, the haze transmittance, and aerial perspective fading into the sky's colour.
#include "support/render_test_support.hpp"

#include <sylva/render/camera.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

constexpr int kW = 96;
constexpr int kH = 64;

using SkyTest = GlTest;

// World direction through the centre of pixel (x, row) for `cam` (row 0 = top).
glm::vec3 pixel_direction(const Camera& cam, int x, int row) {
  const glm::mat4 inv = glm::inverse(cam.view_projection());
  const float nx = (static_cast<float>(x) + 0.5f) / kW * 2.0f - 1.0f;
  const float ny = 1.0f - (static_cast<float>(row) + 0.5f) / kH * 2.0f;
  const glm::vec4 p = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
  return glm::normalize(glm::vec3(p) / p.w);
}

// Float target: the sky is HDR radiance, compared with the CPU twin to 0.5 % + 1e-4.
void expect_sky_matches_cpu(const Camera& cam, const Lighting& lighting, const char* name) {
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok()) << sky.error().describe();
  Result<Framebuffer> fb = Framebuffer::create({.width = kW, .height = kH, .color_formats = {GL_RGBA32F}});
  ASSERT_TRUE(fb.ok());
  fb->bind();
  fb->clear({1, 0, 1, 1}, 0.0f);
  sky->draw(cam, lighting);
  Result<Image> image = read_color(*fb);
  ASSERT_TRUE(image.ok());
  test::save_for_inspection(*image, name);
  int checked = 0;
  for (int row = 0; row < kH; row += 3) {
    for (int x = 0; x < kW; x += 5) {
      const glm::vec3 expected = sky_radiance(lighting, pixel_direction(cam, x, row));
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(image->at(x, row, c), expected[c], 5.0e-3f * expected[c] + 1.0e-4f) << x << "," << row << " channel " << c;
        ASSERT_GT(expected[c], 0.0f);
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
  // No magenta left: the sky covers every pixel at depth 0.
  EXPECT_EQ(test::count_color(*image, 1, 0, 1), 0);
}

TEST_F(SkyTest, AtmosphereMatchesCpuTwin) {
  Camera cam;
  cam.set_aspect(kW, kH);
  cam.set_position({1.0e6, 50.0, -2.0e6});  // position must not matter for the sky
  cam.set_yaw_pitch(0.3f, 0.1f);
  Lighting lighting;
  const glm::vec3 back = -cam.forward();
  lighting.sun_direction = glm::normalize(glm::vec3(back.x, 0.5f, back.z));  // behind, no disk in view
  expect_sky_matches_cpu(cam, lighting, "sky_atmosphere");
  // Toward a low sun, half the view below the horizon: the Mie glow and the haze below.
  lighting.sun_direction = sun_direction(0.4f, 0.08f);
  cam.set_yaw_pitch(0.5f, 0.0f);
  expect_sky_matches_cpu(cam, lighting, "sky_atmosphere_low_sun");
}

// Straight down (the sky a lake reflects from above, the haze under a steep view) toward a low
// sun: the GPU equals the CPU twin, and around the nadir there is no pinwheel: directions on a
// ring 1 degree from it agree within 2 % whatever their azimuth (the value is continuous at the
// nadir; farther out it varies smoothly with the azimuth, the sun side brighter). Seen red before
// the azimuth faded out near the nadir: the sun-side horizon's glow made a wedge pointing at the
// nadir (ring, red channel: 0.53 .. 4.74).
TEST_F(SkyTest, NoPinwheelAroundTheNadir) {
  Camera cam;
  cam.set_aspect(kW, kH);
  cam.set_yaw_pitch(0.2f, -1.5697963f);  // 0.01 rad short of straight down
  Lighting lighting;
  lighting.sun_direction = sun_direction(0.3f, 0.2f);
  expect_sky_matches_cpu(cam, lighting, "sky_nadir");
  glm::vec3 lo(1.0e30f), hi(0.0f);
  for (int k = 0; k < 36; ++k) {
    const float az = static_cast<float>(k) / 36.0f * 6.2831853f;
    const glm::vec3 d = glm::normalize(glm::vec3(0.0175f * std::sin(az), -1.0f, 0.0175f * std::cos(az)));
    const glm::vec3 v = sky_radiance(lighting, d);
    lo = glm::min(lo, v);
    hi = glm::max(hi, v);
  }
  for (int c = 0; c < 3; ++c) EXPECT_LT(hi[c], 1.02f * lo[c]) << "channel " << c << ": " << lo[c] << " .. " << hi[c];
}

TEST_F(SkyTest, NoDarkBandBelowTheHorizon) {
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok());
  Result<Framebuffer> fb = Framebuffer::create({.width = kW, .height = kH, .color_formats = {GL_RGBA32F}});
  ASSERT_TRUE(fb.ok());
  Camera cam;
  cam.set_aspect(kW, kH);
  cam.set_yaw_pitch(0.0f, -0.6f);  // looking down: most of the view is below the horizon
  Lighting lighting;
  fb->bind();
  fb->clear({0, 0, 0, 1}, 0.0f);
  sky->draw(cam, lighting);
  Result<Image> image = read_color(*fb);
  ASSERT_TRUE(image.ok());
  // Every pixel below the horizon, down to 30 degrees from the nadir (where its azimuth fades
  // out), shows the horizon's haze of its azimuth (not a ground colour).
  int below = 0;
  for (int row = 0; row < kH; ++row) {
    for (int x = 0; x < kW; ++x) {
      glm::vec3 d = pixel_direction(cam, x, row);
      if (d.y >= 0.0f || glm::length(glm::vec2(d.x, d.z)) < SkyTable::kNadirFade) continue;
      ++below;
      d.y = 0.0f;
      const glm::vec3 horizon = sky_radiance(lighting, glm::normalize(d));
      for (int c = 0; c < 3; ++c) {
        ASSERT_GT(horizon[c], 0.05f);
        ASSERT_NEAR(image->at(x, row, c), horizon[c], 5.0e-3f * horizon[c]) << x << "," << row;
      }
    }
  }
  EXPECT_GT(below, kW * kH / 2);
}

TEST_F(SkyTest, SunDiskWhereTheSunIs) {
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok());
  Framebuffer fb = test::make_target(kW, kH);
  Camera cam;
  cam.set_aspect(kW, kH);
  cam.perspective().fov_y = 0.1f;  // narrow, so the 0.5-degree disk covers pixels
  Lighting lighting;
  lighting.sun_direction = sun_direction(0.0f, 0.2f);
  cam.look_at(cam.position() + glm::dvec3(lighting.sun_direction));
  fb.bind();
  fb.clear({0, 0, 0, 1});
  sky->draw(cam, lighting);
  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok());
  test::save_for_inspection(*image, "sky_sun");
  EXPECT_EQ(image->at(kW / 2, kH / 2, 0), 1.0f);  // saturated at the centre
  EXPECT_EQ(image->at(kW / 2, kH / 2, 1), 1.0f);
  EXPECT_LT(image->at(0, 0, 0), 1.0f);  // corners outside the disk
}

TEST_F(SkyTest, SkyOnlyWhereNothingWasDrawn) {
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok());
  Framebuffer fb = test::make_target(kW, kH);
  Camera cam;
  cam.set_aspect(kW, kH);
  fb.bind();
  fb.clear({0, 0, 0, 1});
  // Pretend geometry covers the left half: depth 0.5 there.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, kW / 2, kH);
  const float depth = 0.5f;
  glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &depth);
  glDisable(GL_SCISSOR_TEST);
  sky->draw(cam, Lighting{});
  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok());
  for (int row = 0; row < kH; ++row) {
    ASSERT_EQ(image->at(kW / 4, row, 0), 0.0f) << row;   // covered: untouched
    ASSERT_GT(image->at(3 * kW / 4, row, 2), 0.1f) << row;  // open: sky
  }
  GLint func = 0;
  glGetIntegerv(GL_DEPTH_FUNC, &func);
  EXPECT_EQ(func, GL_GREATER);  // state restored
}

// A full-screen triangle at depth 0.5 for the probe shaders, as "rtest/fullscreen.vert".
void register_fullscreen_vert() {
  register_shader_source("rtest/fullscreen.vert",
                         "#version 450 core\n"
                         "void main() {\n"
                         "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;\n"
                         "  gl_Position = vec4(p, 0.5, 1.0);\n"
                         "}\n");
}

TEST_F(SkyTest, FogTransmittanceMatchesCpu) {
  embedded::register_render_shaders();
  register_fullscreen_vert();
  register_shader_source("rtest/fog_probe.frag",
                         "#version 450 core\n"
                         "#include \"render/lib/fog.glsl\"\n"
                         "out vec4 o_value;\n"
                         "void main() {\n"
                         "  float d = exp2(gl_FragCoord.x * 0.25);  // 1 m .. ~2^16 m across the row\n"
                         "  o_value = vec4(fog_transmittance(vec3(0.0, 0.0, -d)), d, sylva_fog.a, scene_time());\n"
                         "}\n");
  Program probe = test::build_or_fail({"rtest/fullscreen.vert", "rtest/fog_probe.frag"});
  ASSERT_TRUE(probe);
  Result<Framebuffer> fb = Framebuffer::create({.width = 64, .height = 1, .color_formats = {GL_RGBA32F}});
  ASSERT_TRUE(fb.ok());
  Lighting lighting;
  lighting.fog_density = 2.0e-4f;
  LightingUniforms uniforms = LightingUniforms::create();
  uniforms.update(lighting, 10.0, 12.5);
  uniforms.bind();
  fb->bind();
  glDisable(GL_DEPTH_TEST);
  probe.use();
  VertexArray vao = VertexArray::create();
  vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  Result<Image> image = read_color(*fb);
  ASSERT_TRUE(image.ok());
  for (int x = 0; x < 64; ++x) {
    const float d = image->at(x, 0, 1);
    ASSERT_NEAR(image->at(x, 0, 0), fog_transmittance(lighting.fog_density, d), 1.0e-5f) << "d=" << d;
  }
  EXPECT_FLOAT_EQ(image->at(0, 0, 2), 2.0e-4f);  // std140 block layout reaches the shader
  EXPECT_FLOAT_EQ(image->at(0, 0, 3), 12.5f);
  EXPECT_LT(image->at(63, 0, 0), 0.01f);  // 2^15.9 m of fog is opaque
}

// Aerial perspective: a black surface far away takes exactly the sky's colour of its
// direction (the horizon's haze below it), a near one stays nearly black, and blue fades first.
TEST_F(SkyTest, AerialPerspectiveFadesIntoTheSky) {
  embedded::register_render_shaders();
  register_fullscreen_vert();
  register_shader_source("rtest/aerial_probe.frag",
                         "#version 450 core\n"
                         "#include \"render/lib/fog.glsl\"\n"
                         "uniform vec3 u_dir;\n"
                         "out vec4 o_value;\n"
                         "void main() {\n"
                         "  float d = exp2(gl_FragCoord.x * 0.5);  // 1 m .. 2^32 m across the row\n"
                         "  o_value = vec4(apply_fog(vec3(0.0), u_dir * d), d);\n"
                         "}\n");
  Program probe = test::build_or_fail({"rtest/fullscreen.vert", "rtest/aerial_probe.frag"});
  ASSERT_TRUE(probe);
  Result<Framebuffer> fb = Framebuffer::create({.width = 64, .height = 1, .color_formats = {GL_RGBA32F}});
  ASSERT_TRUE(fb.ok());
  Lighting lighting;
  lighting.fog_density = 0.0f;  // the air alone
  LightingUniforms uniforms = LightingUniforms::create();
  uniforms.update(lighting, 100.0, 0.0);
  uniforms.bind();
  VertexArray vao = VertexArray::create();
  for (const glm::vec3 dir : {glm::normalize(glm::vec3(0.3f, 0.0f, -1.0f)), glm::normalize(glm::vec3(-1.0f, -0.05f, 0.2f))}) {
    fb->bind();
    glDisable(GL_DEPTH_TEST);
    probe.use();
    probe.set("u_dir", dir);
    vao.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    Result<Image> image = read_color(*fb);
    ASSERT_TRUE(image.ok());
    const glm::vec3 sky = sky_radiance(lighting, dir);
    for (int c = 0; c < 3; ++c) {
      EXPECT_LT(image->at(0, 0, c), 1.0e-3f * sky[c] + 1.0e-6f) << "1 m of air is clear";
      EXPECT_NEAR(image->at(63, 0, c), sky[c], 2.0e-3f * sky[c]) << "far away: the sky's own colour";
    }
    // At 10 km the blue haze is further along than the red.
    const int x10km = static_cast<int>(std::round(2.0 * std::log2(10000.0)));
    EXPECT_GT(image->at(x10km, 0, 2) / sky.b, image->at(x10km, 0, 0) / sky.r);
  }
}

TEST(SunDirection, AzimuthAndElevation) {
  EXPECT_NEAR(glm::length(sun_direction(0.0f, 0.0f) - glm::vec3(0, 0, -1)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(sun_direction(1.5707963f, 0.0f) - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(sun_direction(0.3f, 1.5707963f) - glm::vec3(0, 1, 0)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::length(sun_direction(2.0f, 0.7f)), 1.0f, 1e-6f);
  EXPECT_EQ(fog_transmittance(0.0f, 1.0e9f), 1.0f);
  EXPECT_EQ(fog_transmittance(1.0f, -5.0f), 1.0f);
}

}  // namespace
}  // namespace sylva::render
