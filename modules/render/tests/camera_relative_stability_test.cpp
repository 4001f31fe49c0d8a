// Invariant "no jitter far from the origin": with camera-relative rendering (world positions in
// double, model offset = object origin - camera position subtracted in double), an object
// rendered 1e5 .. 1e7 m from the world origin gives exactly the same pixels as the same view at
// the origin, for every sub-millimetre camera step. The naive float world-space path is shown
// to break at 1e7 m so the test is known to be able to fail.
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

constexpr int kW = 96;
constexpr int kH = 54;

class CameraRelativeTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    register_shader_source("rtest/rel.vert",
                           "#version 450 core\n"
                           "layout(location = 0) in vec3 a_pos;\n"
                           "uniform mat4 u_view_projection;\n"
                           "uniform mat4 u_model;\n"
                           "out vec3 v_local;\n"
                           "void main() {\n"
                           "  v_local = a_pos;\n"
                           "  gl_Position = u_view_projection * (u_model * vec4(a_pos, 1.0));\n"
                           "}\n");
    register_shader_source("rtest/rel.frag",
                           "#version 450 core\n"
                           "in vec3 v_local;\n"
                           "out vec4 o_color;\n"
                           "void main() { o_color = vec4(fract(v_local * 4.0), 1.0); }\n");
    program_ = test::build_or_fail({"rtest/rel.vert", "rtest/rel.frag"});
    // A small tilted fan of triangles, about 1 m across, with a checker-like gradient.
    const std::array<glm::vec3, 9> tris{{{-0.5f, -0.4f, 0.0f}, {0.5f, -0.3f, 0.1f}, {0.05f, 0.5f, -0.2f},
                                         {0.5f, -0.3f, 0.1f}, {0.6f, 0.4f, -0.3f}, {0.05f, 0.5f, -0.2f},
                                         {-0.5f, -0.4f, 0.0f}, {0.05f, 0.5f, -0.2f}, {-0.7f, 0.2f, 0.3f}}};
    vbo_ = Buffer::immutable(std::span<const glm::vec3>(tris));
    vao_ = VertexArray::create();
    vao_.attribute(0, 0, 3, GL_FLOAT, 0);
    vao_.vertex_buffer(0, vbo_, sizeof(glm::vec3));
    fb_ = test::make_target(kW, kH);
  }

  // Camera at `eye`, object at eye + (0.3, -0.2, -4); camera-relative path.
  Image render_relative(const glm::dvec3& eye) {
    Camera cam;
    cam.set_position(eye);
    cam.set_aspect(kW, kH);
    cam.set_yaw_pitch(0.05f, -0.02f);
    const glm::dvec3 object = eye + glm::dvec3(0.3, -0.2, -4.0);
    return draw(cam.view_projection(), cam.relative_model(object));
  }

  // The same scene with float world-space matrices (what camera-relative rendering avoids).
  Image render_naive(const glm::dvec3& eye) {
    Camera cam;
    cam.set_aspect(kW, kH);
    cam.set_yaw_pitch(0.05f, -0.02f);
    const glm::vec3 eye_f(eye);
    const glm::vec3 object_f(eye + glm::dvec3(0.3, -0.2, -4.0));
    const glm::mat4 view = cam.view_rotation() * glm::translate(glm::mat4(1.0f), -eye_f);
    const glm::mat4 model = glm::translate(glm::mat4(1.0f), object_f);
    return draw(cam.projection() * view, model);
  }

  Image draw(const glm::mat4& view_projection, const glm::mat4& model) {
    fb_.bind();
    fb_.clear({0, 0, 0, 1});
    program_.set("u_view_projection", view_projection);
    program_.set("u_model", model);
    program_.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 9);
    Result<Image> image = read_color(fb_);
    EXPECT_TRUE(image.ok());
    return image.ok() ? std::move(image).value() : Image();
  }

  Program program_;
  Buffer vbo_;
  VertexArray vao_;
  Framebuffer fb_;
};

TEST_F(CameraRelativeTest, NoJitterFrom1e5To1e7Metres) {
  const Image reference = render_relative({0.0, 0.0, 0.0});
  test::save_for_inspection(reference, "camera_relative_reference");
  int drawn = 0;
  for (float v : reference.data()) drawn += v > 0.0f ? 1 : 0;
  ASSERT_GT(drawn, 1000) << "the object must be visible";
  for (const double distance : {1.0e5, 1.0e6, 1.0e7}) {
    const glm::dvec3 base(distance, 0.37 * distance, -0.81 * distance);
    for (int step = 0; step < 5; ++step) {
      const glm::dvec3 eye = base + glm::dvec3(0.37e-3 * step, -0.21e-3 * step, 0.13e-3 * step);  // sub-mm steps
      const Image image = render_relative(eye);
      ASSERT_EQ(test::max_abs_diff(image, reference), 0.0f) << "distance " << distance << " step " << step;
    }
  }
}

TEST_F(CameraRelativeTest, NaiveFloatPathJittersAt1e7) {
  const Image reference = render_relative({0.0, 0.0, 0.0});
  const glm::dvec3 far_eye(1.0e7 + 0.25, 3.7e6, -8.1e6);
  const Image naive = render_naive(far_eye);
  test::save_for_inspection(naive, "camera_relative_naive_1e7");
  EXPECT_GT(test::max_abs_diff(naive, reference), 0.1f)
      << "float world coordinates at 1e7 m should visibly displace the object";
  // And near the origin the naive path agrees with the relative one (same maths, no loss).
  EXPECT_LT(test::max_abs_diff(render_naive({0.0, 0.0, 0.0}), reference), 2.0f / 255.0f);
}

}  // namespace
}  // namespace sylva::render
