// A tessellation pipeline (vert -> tesc -> tese -> frag) draws: a quad patch tessellated into
// a 4x4 grid (32 triangles, counted with GL_PRIMITIVES_GENERATED) whose evaluation shader
// places it in a known rectangle; every pixel inside is drawn, nothing outside.
#include "support/render_test_support.hpp"

#include <sylva/render/queries.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include <gtest/gtest.h>

namespace sylva::render {
namespace {

class TessellationTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    register_shader_source("rtest/tess.vert",
                           "#version 450 core\n"
                           "void main() { gl_Position = vec4(0.0); }\n");
    register_shader_source("rtest/tess.tesc",
                           "#version 450 core\n"
                           "layout(vertices = 1) out;\n"
                           "uniform float u_level;\n"
                           "void main() {\n"
                           "  gl_out[gl_InvocationID].gl_Position = gl_in[gl_InvocationID].gl_Position;\n"
                           "  gl_TessLevelOuter[0] = u_level; gl_TessLevelOuter[1] = u_level;\n"
                           "  gl_TessLevelOuter[2] = u_level; gl_TessLevelOuter[3] = u_level;\n"
                           "  gl_TessLevelInner[0] = u_level; gl_TessLevelInner[1] = u_level;\n"
                           "}\n");
    register_shader_source("rtest/tess.tese",
                           "#version 450 core\n"
                           "layout(quads, equal_spacing, ccw) in;\n"
                           "out vec2 v_uv;\n"
                           "void main() {\n"
                           "  v_uv = gl_TessCoord.xy;\n"
                           "  // NDC rectangle [-0.5, 0.5] x [-0.5, 0.5].\n"
                           "  vec2 p = gl_TessCoord.xy - 0.5;\n"
                           "  gl_Position = vec4(p, 0.5, 1.0);\n"
                           "}\n");
    register_shader_source("rtest/tess.frag",
                           "#version 450 core\n"
                           "in vec2 v_uv;\n"
                           "out vec4 o_color;\n"
                           "void main() { o_color = vec4(v_uv, 0.0, 1.0); }\n");
  }
};

TEST_F(TessellationTest, QuadPatchTessellatesAndDraws) {
  GLint max_level = 0;
  glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &max_level);
  ASSERT_GE(max_level, 64);
  Framebuffer fb = test::make_target(64, 64);
  Program program = test::build_or_fail({"rtest/tess.vert", "rtest/tess.tesc", "rtest/tess.tese", "rtest/tess.frag"});
  ASSERT_TRUE(program);
  program.set("u_level", 4.0f);
  VertexArray vao = VertexArray::create();
  fb.bind();
  fb.clear({0, 0, 0, 0});
  glDisable(GL_DEPTH_TEST);
  program.use();
  vao.bind();
  glPatchParameteri(GL_PATCH_VERTICES, 1);
  PassQuery query = PassQuery::create(true);
  query.begin(1);
  glDrawArrays(GL_PATCHES, 0, 1);
  query.end();
  std::optional<PassQueryResult> r = query.wait_all();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->primitives, 32u);  // 4 x 4 quads, two triangles each
  EXPECT_EQ(r->samples, 32u * 32u);

  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok());
  test::save_for_inspection(*image, "tessellation");
  // NDC [-0.5, 0.5] is pixels [16, 48) on both axes.
  int drawn = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool inside = x >= 16 && x < 48 && y >= 16 && y < 48;
      const bool is_drawn = image->at(x, y, 3) > 0.5f;
      ASSERT_EQ(is_drawn, inside) << x << "," << y;
      drawn += is_drawn ? 1 : 0;
      if (inside) {
        // The evaluation shader's (u, v) is interpolated across the tessellated grid.
        const float u = (static_cast<float>(x) + 0.5f - 16.0f) / 32.0f;
        const float v = (static_cast<float>(63 - y) + 0.5f - 16.0f) / 32.0f;
        ASSERT_NEAR(image->at(x, y, 0), u, 1.0f / 255.0f + 1.0e-4f) << x << "," << y;
        ASSERT_NEAR(image->at(x, y, 1), v, 1.0f / 255.0f + 1.0e-4f) << x << "," << y;
      }
    }
  }
  EXPECT_EQ(drawn, 32 * 32);

  // A higher level generates more primitives: level 16 -> 16 * 16 * 2.
  program.set("u_level", 16.0f);
  query.begin(2);
  glDrawArrays(GL_PATCHES, 0, 1);
  query.end();
  r = query.wait_all();
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->primitives, 512u);
}

}  // namespace
}  // namespace sylva::render
