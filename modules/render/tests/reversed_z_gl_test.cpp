// Reversed-Z depth (glClipControl zero-to-one, 32-bit float depth, GREATER, clear 0) orders
// surfaces correctly both at 1e-2 m and at 1e5 m in the same frame with the same projection,
// where a conventional 24-bit depth buffer cannot separate them.
#include "support/render_test_support.hpp"

#include <sylva/render/buffer.hpp>
#include <sylva/render/camera.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <array>

namespace sylva::render {
namespace {

constexpr int kSize = 32;

class ReversedZTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    register_shader_source("rtest/mvp.vert",
                           "#version 450 core\n"
                           "layout(location = 0) in vec3 a_pos;\n"
                           "uniform mat4 u_mvp;\n"
                           "void main() { gl_Position = u_mvp * vec4(a_pos, 1.0); }\n");
    register_shader_source("rtest/color.frag",
                           "#version 450 core\n"
                           "uniform vec4 u_color;\n"
                           "out vec4 o_color;\n"
                           "void main() { o_color = u_color; }\n");
    program_ = test::build_or_fail({"rtest/mvp.vert", "rtest/color.frag"});
    // A unit square in x/y at z = 0, two triangles.
    const std::array<glm::vec3, 6> square{{{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, -1, 0}, {1, 1, 0}, {-1, 1, 0}}};
    vbo_ = Buffer::immutable(std::span<const glm::vec3>(square));
    vao_ = VertexArray::create();
    vao_.attribute(0, 0, 3, GL_FLOAT, 0);
    vao_.vertex_buffer(0, vbo_, sizeof(glm::vec3));
  }

  // Draws a square facing the camera at `distance` metres that fills the view.
  void draw_square(const glm::mat4& projection, double distance, const glm::vec4& color) {
    const float half = static_cast<float>(distance);  // wider than the 60-degree view
    const glm::mat4 model = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, static_cast<float>(-distance))),
                                       glm::vec3(half, half, 1.0f));
    program_.set("u_mvp", projection * model);
    program_.set("u_color", color);
    program_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 6);
  }

  Program program_;
  Buffer vbo_;
  VertexArray vao_;
};

// Near square red, far square green; the result must be red whichever is drawn first.
TEST_F(ReversedZTest, OrdersSurfacesAtOneCentimetreAndAtHundredKilometres) {
  const glm::mat4 projection = reversed_z_perspective({.fov_y = 1.0471976f, .aspect = 1.0f, .near_plane = 1.0e-3f});
  Framebuffer fb = test::make_target(kSize, kSize);
  ASSERT_TRUE(fb);
  for (const double distance : {1.0e-2, 1.0e5}) {
    const double gap = distance * 1.0e-5;  // 0.1 um at 1 cm, 1 m at 100 km
    for (const bool near_first : {true, false}) {
      fb.bind();
      fb.clear({0, 0, 0, 1});
      apply_reversed_z_state();
      if (near_first) {
        draw_square(projection, distance, {1, 0, 0, 1});
        draw_square(projection, distance + gap, {0, 1, 0, 1});
      } else {
        draw_square(projection, distance + gap, {0, 1, 0, 1});
        draw_square(projection, distance, {1, 0, 0, 1});
      }
      Result<Image> image = read_color(fb);
      ASSERT_TRUE(image.ok());
      EXPECT_EQ(test::count_color(*image, 1, 0, 0), kSize * kSize)
          << "distance " << distance << " near drawn first " << near_first;
      Result<Image> depth = read_depth(fb);
      ASSERT_TRUE(depth.ok());
      // Window depth is near / distance for the reversed infinite projection.
      EXPECT_NEAR(depth->at(kSize / 2, kSize / 2), 1.0e-3 / distance, 1.0e-3 / distance * 1.0e-5);
    }
  }
}

// The contrast that motivates reversed-Z: the classic [-1, 1] projection with a 24-bit depth
// buffer maps both squares at 100 km to the same depth, so draw order decides (z-fighting).
TEST_F(ReversedZTest, ConventionalDepthFailsWhereReversedZWorks) {
  Result<Framebuffer> fb = Framebuffer::create({.width = kSize, .height = kSize, .depth_format = GL_DEPTH_COMPONENT24});
  ASSERT_TRUE(fb.ok());
  const glm::mat4 classic = glm::infinitePerspective(1.0471976f, 1.0f, 1.0e-3f);
  int red_results = 0;
  for (const bool near_first : {true, false}) {
    fb->bind();
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthFunc(GL_LESS);
    glEnable(GL_DEPTH_TEST);
    fb->clear({0, 0, 0, 1}, 1.0f);
    const double d = 1.0e5;
    if (near_first) {
      draw_square(classic, d, {1, 0, 0, 1});
      draw_square(classic, d * (1.0 + 1.0e-5), {0, 1, 0, 1});
    } else {
      draw_square(classic, d * (1.0 + 1.0e-5), {0, 1, 0, 1});
      draw_square(classic, d, {1, 0, 0, 1});
    }
    Result<Image> image = read_color(*fb);
    ASSERT_TRUE(image.ok());
    red_results += test::count_color(*image, 1, 0, 0) == kSize * kSize ? 1 : 0;
  }
  apply_reversed_z_state();
  EXPECT_LT(red_results, 2) << "conventional depth unexpectedly resolved a 1e-5 relative gap at 100 km";
}

}  // namespace
}  // namespace sylva::render
