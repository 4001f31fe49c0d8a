// A triangle through buffers, a vertex array and a program, checked pixel by pixel against the
// analytic coverage (pixel centres inside the triangle), with exact colour values.
#include "support/render_test_support.hpp"

#include <sylva/render/buffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace sylva::render {
namespace {

constexpr int kW = 64;
constexpr int kH = 48;

struct Vertex {
  float x, y;         // pixel coordinates
  unsigned char rgba[4];
};

class TriangleTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    register_shader_source("rtest/pixel.vert",
                           "#version 450 core\n"
                           "layout(location = 0) in vec2 a_pixel;\n"
                           "layout(location = 1) in vec4 a_color;\n"
                           "uniform vec2 u_size;\n"
                           "flat out vec4 v_color;\n"
                           "void main() {\n"
                           "  v_color = a_color;\n"
                           "  gl_Position = vec4(a_pixel / u_size * 2.0 - 1.0, 0.5, 1.0);\n"
                           "}\n");
    register_shader_source("rtest/flat.frag",
                           "#version 450 core\n"
                           "flat in vec4 v_color;\n"
                           "out vec4 o_color;\n"
                           "void main() { o_color = v_color; }\n");
  }
};

// Signed area test of a pixel centre against triangle a, b, c (counter-clockwise).
double edge(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

TEST_F(TriangleTest, ExactCoverageAndColour) {
  Framebuffer fb = test::make_target(kW, kH);
  ASSERT_TRUE(fb);
  // Vertices off the pixel-centre lattice so no centre lies on an edge (no tie-breaking).
  const std::array<Vertex, 3> verts{{{6.3f, 4.2f, {0, 255, 0, 255}},
                                     {57.7f, 11.1f, {0, 255, 0, 255}},
                                     {19.4f, 43.9f, {0, 255, 0, 255}}}};
  const std::array<unsigned, 3> indices{0, 1, 2};
  Buffer vbo = Buffer::immutable(std::span<const Vertex>(verts));
  Buffer ibo = Buffer::immutable(std::span<const unsigned>(indices));
  VertexArray vao = VertexArray::create();
  vao.attribute(0, 0, 2, GL_FLOAT, offsetof(Vertex, x));
  vao.attribute(1, 0, 4, GL_UNSIGNED_BYTE, offsetof(Vertex, rgba), true);
  vao.vertex_buffer(0, vbo, sizeof(Vertex));
  vao.index_buffer(ibo);
  Program program = test::build_or_fail({"rtest/pixel.vert", "rtest/flat.frag"});
  ASSERT_TRUE(program);
  program.set("u_size", glm::vec2(kW, kH));

  fb.bind();
  fb.clear({0.0f, 0.0f, 1.0f, 1.0f});
  glDisable(GL_DEPTH_TEST);
  program.use();
  vao.bind();
  glDrawElements(GL_TRIANGLES, 3, GL_UNSIGNED_INT, nullptr);

  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  test::save_for_inspection(*image, "triangle");
  int inside = 0;
  int mismatches = 0;
  for (int row = 0; row < kH; ++row) {
    const int gl_y = kH - 1 - row;  // Image row 0 is the top
    for (int x = 0; x < kW; ++x) {
      const double px = x + 0.5;
      const double py = gl_y + 0.5;
      const double e0 = edge(verts[0].x, verts[0].y, verts[1].x, verts[1].y, px, py);
      const double e1 = edge(verts[1].x, verts[1].y, verts[2].x, verts[2].y, px, py);
      const double e2 = edge(verts[2].x, verts[2].y, verts[0].x, verts[0].y, px, py);
      const bool covered = e0 > 0 && e1 > 0 && e2 > 0;
      inside += covered ? 1 : 0;
      const float g = covered ? 1.0f : 0.0f;
      const float b = covered ? 0.0f : 1.0f;
      if (image->at(x, row, 0) != 0.0f || image->at(x, row, 1) != g || image->at(x, row, 2) != b) {
        if (++mismatches < 5) ADD_FAILURE() << "pixel " << x << "," << gl_y << " covered=" << covered;
      }
    }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(inside, 400);  // the triangle is about 870 px^2
}

TEST_F(TriangleTest, DynamicBufferGrowsAndKeepsDrawing) {
  Framebuffer fb = test::make_target(kW, kH);
  Program program = test::build_or_fail({"rtest/pixel.vert", "rtest/flat.frag"});
  ASSERT_TRUE(program);
  program.set("u_size", glm::vec2(kW, kH));
  Buffer vbo = Buffer::dynamic(sizeof(Vertex));  // too small on purpose: upload grows it
  // Two triangles forming the left half of the target, red.
  const std::array<Vertex, 6> quad{{{0, 0, {255, 0, 0, 255}},
                                    {32, 0, {255, 0, 0, 255}},
                                    {32, 48, {255, 0, 0, 255}},
                                    {0, 0, {255, 0, 0, 255}},
                                    {32, 48, {255, 0, 0, 255}},
                                    {0, 48, {255, 0, 0, 255}}}};
  vbo.upload(std::span<const Vertex>(quad));
  EXPECT_GE(vbo.size(), sizeof(quad));
  std::array<Vertex, 6> back{};
  vbo.read(0, sizeof(back), back.data());
  EXPECT_EQ(back[4].x, 32.0f);
  VertexArray vao = VertexArray::create();
  vao.attribute(0, 0, 2, GL_FLOAT, offsetof(Vertex, x));
  vao.attribute(1, 0, 4, GL_UNSIGNED_BYTE, offsetof(Vertex, rgba), true);
  vao.vertex_buffer(0, vbo, sizeof(Vertex));
  fb.bind();
  fb.clear({0, 0, 0, 1});
  glDisable(GL_DEPTH_TEST);
  program.use();
  vao.bind();
  glDrawArrays(GL_TRIANGLES, 0, 6);
  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(test::count_color(*image, 1, 0, 0), 32 * 48);
  EXPECT_EQ(test::count_color(*image, 0, 0, 0), 32 * 48);
  EXPECT_EQ(image->at(31, 10, 0), 1.0f);
  EXPECT_EQ(image->at(32, 10, 0), 0.0f);
}

}  // namespace
}  // namespace sylva::render
