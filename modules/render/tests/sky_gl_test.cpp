// The sky renderer and the shared GLSL lighting library agree with their CPU twins: sky
// gradient colours per pixel direction, the sun disk where the sun is, and fog transmittance.
#include "support/render_test_support.hpp"

#include <sylva/render/camera.hpp>
#include <sylva/render/lighting_uniforms.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

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

TEST_F(SkyTest, GradientMatchesCpuTwin) {
  Result<SkyRenderer> sky = SkyRenderer::create();
  ASSERT_TRUE(sky.ok()) << sky.error().describe();
  Framebuffer fb = test::make_target(kW, kH);
  Camera cam;
  cam.set_aspect(kW, kH);
  cam.set_position({1.0e6, 50.0, -2.0e6});  // position must not matter for the sky
  cam.set_yaw_pitch(0.3f, 0.1f);
  Lighting lighting;
  lighting.sun_direction = -cam.forward();  // sun behind the camera: pure gradient in view
  fb.bind();
  fb.clear({1, 0, 1, 1});
  sky->draw(cam, lighting);
  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok());
  test::save_for_inspection(*image, "sky_gradient");
  int checked = 0;
  for (int row = 0; row < kH; row += 3) {
    for (int x = 0; x < kW; x += 5) {
      const glm::vec3 expected = sky_gradient(lighting, pixel_direction(cam, x, row));
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(image->at(x, row, c), expected[c], 2.5f / 255.0f) << x << "," << row << " channel " << c;
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 300);
  // No magenta left: the sky covers every pixel at depth 0.
  EXPECT_EQ(test::count_color(*image, 1, 0, 1), 0);
  // Top is nearer the zenith colour than the bottom (blue channel higher relative to red).
  EXPECT_GT(image->at(kW / 2, 0, 2) - image->at(kW / 2, 0, 0), image->at(kW / 2, kH - 1, 2) - image->at(kW / 2, kH - 1, 0));
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

TEST_F(SkyTest, FogTransmittanceMatchesCpu) {
  embedded::register_render_shaders();
  register_shader_source("rtest/fullscreen.vert",
                         "#version 450 core\n"
                         "void main() {\n"
                         "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;\n"
                         "  gl_Position = vec4(p, 0.5, 1.0);\n"
                         "}\n");
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
