// Point lights (point_lights.hpp): the GLSL sum over lights equals the CPU formula per pixel
// (seed attenuation 1/(Kc + Kl d + Kq d^2) with the range window), Kc = 1 never amplifies,
// lights end at their range, the 16-light limit and bad values are clear errors, far from the
// origin the camera-relative upload stays exact.
#include "support/render_test_support.hpp"

#include <sylva/render/camera.hpp>
#include <sylva/render/point_lights.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace sylva::render {
namespace {

constexpr int kSize = 64;

TEST(PointLightAttenuation, SeedFormulaAndWindow) {
  const PointLightAttenuation a;  // seed defaults
  EXPECT_FLOAT_EQ(a.constant, 1.0f);
  EXPECT_FLOAT_EQ(a.linear, 0.045f);
  EXPECT_FLOAT_EQ(a.quadratic, 0.0075f);
  EXPECT_FLOAT_EQ(point_light_attenuation(a, 1.0e9f, 0.0f), 1.0f);  // never amplified at d = 0
  const float d = 10.0f;
  const float seed = 1.0f / (1.0f + 0.045f * d + 0.0075f * d * d);
  EXPECT_NEAR(point_light_attenuation(a, 1.0e9f, d), seed, 1e-6f);  // window ~1 far inside the range
  EXPECT_EQ(point_light_attenuation(a, 50.0f, 50.0f), 0.0f);
  EXPECT_EQ(point_light_attenuation(a, 50.0f, 80.0f), 0.0f);
  float last = 2.0f;
  for (float x = 0.0f; x <= 60.0f; x += 0.5f) {
    const float f = point_light_attenuation(a, 50.0f, x);
    EXPECT_LE(f, last);  // monotonic falloff
    EXPECT_GE(f, 0.0f);
    last = f;
  }
}

using PointLightsGl = GlTest;

struct GroundDraw {
  Program program;
  VertexArray vao;
  Framebuffer fb;
};

GroundDraw make_ground() {
  register_shader_source("rtest/pl_ground.vert", R"(#version 450 core
uniform mat4 u_view_projection;
uniform vec3 u_origin_rel;  // world origin minus camera
out vec3 v_rel;
void main() {
  vec2 q = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;  // covers [-1, 3]
  vec3 world = vec3(q.x * 30.0, 0.0, q.y * 30.0);
  v_rel = u_origin_rel + world;
  gl_Position = u_view_projection * vec4(v_rel, 1.0);
}
)");
  register_shader_source("rtest/pl_ground.frag", R"(#version 450 core
#include "render/lib/point_lights.glsl"
in vec3 v_rel;
layout(location = 0) out vec4 o_color;
void main() { o_color = vec4(sylva_point_lights_diffuse(v_rel, vec3(0.0, 1.0, 0.0)), 1.0); }
)");
  embedded::register_render_shaders();
  GroundDraw g;
  g.program = test::build_or_fail({"rtest/pl_ground.vert", "rtest/pl_ground.frag"});
  g.vao = VertexArray::create();
  FramebufferDesc desc;
  desc.width = desc.height = kSize;
  desc.color_formats = {GL_RGBA32F};
  Result<Framebuffer> fb = Framebuffer::create(desc);
  EXPECT_TRUE(fb.ok());
  if (fb.ok()) g.fb = std::move(*fb);
  return g;
}

Image render_ground(GroundDraw& g, const Camera& cam, const glm::dvec3& origin) {
  g.fb.bind();
  g.fb.clear({0, 0, 0, 0}, 0.0f);
  g.program.use();
  g.program.set("u_view_projection", cam.view_projection());
  g.program.set("u_origin_rel", glm::vec3(origin - cam.position()));
  g.vao.bind();
  glDisable(GL_CULL_FACE);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  Result<Image> img = read_color(g.fb);
  EXPECT_TRUE(img.ok());
  return img.ok() ? std::move(*img) : Image{};
}

TEST_F(PointLightsGl, ShaderMatchesCpuFormula) {
  for (const glm::dvec3 origin : {glm::dvec3(0.0), glm::dvec3(1.0e6, 0.0, -2.0e6)}) {
    GroundDraw g = make_ground();
    Camera cam;
    cam.set_aspect(kSize, kSize);
    cam.set_position(origin + glm::dvec3(0.0, 12.0, 14.0));
    cam.look_at(origin);
    std::vector<PointLight> lights(3);
    lights[0].position = origin + glm::dvec3(-4.0, 1.5, 0.0);
    lights[0].color = {1.0f, 0.5f, 0.2f};
    lights[0].intensity = 3.0f;
    lights[1].position = origin + glm::dvec3(5.0, 3.0, -3.0);
    lights[1].color = {0.2f, 0.6f, 1.0f};
    lights[1].range = 9.0f;
    lights[2].position = origin + glm::dvec3(0.0, 0.5, 6.0);
    lights[2].attenuation = {1.0f, 0.7f, 1.8f};
    PointLightUniforms ubo = PointLightUniforms::create();
    ASSERT_TRUE(ubo.update(lights, cam.position()).ok());
    EXPECT_EQ(ubo.count(), 3);
    ubo.bind();
    const Image img = render_ground(g, cam, origin);
    test::save_for_inspection(img, "point_lights");
    const glm::mat4 inv = glm::inverse(cam.view_projection());
    int checked = 0;
    float worst = 0.0f;
    for (int row = 0; row < kSize; ++row) {
      for (int x = 0; x < kSize; ++x) {
        for (int c = 0; c < 4; ++c) ASSERT_TRUE(std::isfinite(img.at(x, row, c)));
        if (img.at(x, row, 3) < 0.5f) continue;
        const float nx = (static_cast<float>(x) + 0.5f) / kSize * 2.0f - 1.0f;
        const float ny = 1.0f - (static_cast<float>(row) + 0.5f) / kSize * 2.0f;
        const glm::vec4 p = inv * glm::vec4(nx, ny, 0.5f, 1.0f);
        const glm::dvec3 dir = glm::normalize(glm::dvec3(glm::vec3(p) / p.w));
        const glm::dvec3 ground = cam.position() + dir * ((origin.y - cam.position().y) / dir.y);
        glm::vec3 expected(0.0f);
        for (const PointLight& l : lights) {
          const glm::dvec3 to = l.position - ground;
          const float d = static_cast<float>(glm::length(to));
          const float n_dot_l = static_cast<float>(to.y) / d;
          expected += l.color * l.intensity * point_light_attenuation(l.attenuation, l.range, d) * std::max(n_dot_l, 0.0f);
        }
        for (int c = 0; c < 3; ++c) {
          // Pixel centres vs. interpolated positions: allow 2 % plus a small absolute term.
          const float tol = 0.02f * expected[c] + 2e-3f;
          worst = std::max(worst, std::abs(img.at(x, row, c) - expected[c]) - tol);
          EXPECT_NEAR(img.at(x, row, c), expected[c], tol) << x << "," << row << " channel " << c;
        }
        ++checked;
      }
    }
    EXPECT_GT(checked, kSize * kSize / 2);
  }
}

TEST_F(PointLightsGl, LimitAndBadValuesAreClearErrors) {
  PointLightUniforms ubo = PointLightUniforms::create();
  std::vector<PointLight> many(kMaxPointLights + 4);
  Status st = ubo.update(many, {0, 0, 0});
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().code, ErrorCode::kLimit);
  EXPECT_NE(st.error().message.find("at most 16"), std::string::npos) << st.error().message;
  EXPECT_EQ(ubo.count(), kMaxPointLights);  // the first 16 stay usable
  std::vector<PointLight> bad(3);
  bad[2].intensity = NAN;
  st = ubo.update(bad, {0, 0, 0});
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(st.error().message.find("point light 2"), std::string::npos) << st.error().message;
  EXPECT_EQ(ubo.count(), 2);
  bad[2].intensity = 1.0f;
  bad[1].range = 0.0f;
  EXPECT_FALSE(ubo.update(bad, {0, 0, 0}).ok());
  ASSERT_TRUE(ubo.update({}, {0, 0, 0}).ok());
  EXPECT_EQ(ubo.count(), 0);
}

}  // namespace
}  // namespace sylva::render
