// Hot reload from the source tree: a program rebuilds when its stage file or an included file
// changes on disk; a broken edit keeps the previous program and reports file:line.
#include "support/render_test_support.hpp"

#include <sylva/render/readback.hpp>
#include <sylva/render/shader_library.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/vertex_array.hpp>

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

namespace sylva::render {
namespace {

namespace fs = std::filesystem;

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  // Make the change visible even on file systems with coarse timestamps.
  static auto stamp = fs::file_time_type::clock::now();
  stamp += std::chrono::seconds(2);
  fs::last_write_time(path, stamp);
}

class HotReloadTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    // One folder per test: ctest -j runs the cases of this file at once, and shared files made
    // one case see another's broken edit.
    dir_ = test::output_dir() / "hot_reload" / ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::create_directories(dir_);
    vert_ = (dir_ / "hr.vert").string();
    frag_ = (dir_ / "hr.frag").string();
    lib_ = (dir_ / "colour.glsl").string();
    write_file(vert_, "#version 450 core\n"
                      "void main() {\n"
                      "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;\n"
                      "  gl_Position = vec4(p, 0.5, 1.0);\n"
                      "}\n");
    write_file(lib_, "vec4 colour() { return vec4(1.0, 0.0, 0.0, 1.0); }\n");
    write_file(frag_, "#version 450 core\n#include \"colour.glsl\"\nout vec4 o;\nvoid main() { o = colour(); }\n");
    // Embedded copies hold stale text on purpose: with hot reload the files win.
    static const std::string vert_path = vert_, frag_path = frag_, lib_path = lib_;
    static const EmbeddedShader table[] = {
        {"hrtest/hr.vert", vert_path, "#version 450 core\nvoid main() { gl_Position = vec4(0.0); }\n"},
        {"hrtest/hr.frag", frag_path, "#version 450 core\nout vec4 o;\nvoid main() { o = vec4(0.0); }\n"},
        {"hrtest/colour.glsl", lib_path, "vec4 colour() { return vec4(0.0); }\n"},
    };
    register_embedded_shaders(table);
    was_on_ = shader_hot_reload();
    set_shader_hot_reload(true);
    fb_ = test::make_target(8, 8);
    vao_ = VertexArray::create();
  }
  void TearDown() override {
    set_shader_hot_reload(was_on_);
    GlTest::TearDown();
  }

  glm::vec4 draw(const Program& p) {
    fb_.bind();
    fb_.clear({0, 0, 0, 0});
    glDisable(GL_DEPTH_TEST);
    p.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    Result<Image> image = read_color(fb_);
    EXPECT_TRUE(image.ok());
    return {image->at(4, 4, 0), image->at(4, 4, 1), image->at(4, 4, 2), image->at(4, 4, 3)};
  }

  fs::path dir_;
  std::string vert_, frag_, lib_;
  bool was_on_ = false;
  Framebuffer fb_;
  VertexArray vao_;
};

TEST_F(HotReloadTest, RebuildsOnStageAndIncludeChanges) {
  Result<Program> p = Program::create({"hrtest/hr.vert", "hrtest/hr.frag"});
  ASSERT_TRUE(p.ok()) << p.error().describe();
  EXPECT_EQ(p->files().size(), 3u);  // vert, frag, and the include
  EXPECT_EQ(draw(*p), glm::vec4(1, 0, 0, 1));
  EXPECT_FALSE(p->reload_if_changed());  // nothing changed yet

  write_file(lib_, "vec4 colour() { return vec4(0.0, 1.0, 0.0, 1.0); }\n");
  EXPECT_TRUE(p->reload_if_changed());
  EXPECT_EQ(draw(*p), glm::vec4(0, 1, 0, 1));

  write_file(frag_, "#version 450 core\n#include \"colour.glsl\"\nout vec4 o;\nvoid main() { o = colour().gbra; }\n");
  EXPECT_TRUE(p->reload_if_changed());
  EXPECT_EQ(draw(*p), glm::vec4(1, 0, 0, 1));  // (0, 1, 0, 1).gbra
}

TEST_F(HotReloadTest, BrokenEditKeepsPreviousProgram) {
  Result<Program> p = Program::create({"hrtest/hr.vert", "hrtest/hr.frag"});
  ASSERT_TRUE(p.ok());
  const GLuint before = p->id();
  write_file(lib_, "vec4 colour() {\n  return vec4(1.0, 0.0, 0.0, 1.0)\n}\n");  // missing ';' on line 2
  EXPECT_FALSE(p->reload_if_changed());
  EXPECT_EQ(p->id(), before);
  EXPECT_NE(p->last_reload_error().find("hrtest/colour.glsl:"), std::string::npos) << p->last_reload_error();
  EXPECT_EQ(draw(*p), glm::vec4(1, 0, 0, 1));  // still the old, working program
  EXPECT_FALSE(p->reload_if_changed());        // reported once, not every frame
  write_file(lib_, "vec4 colour() { return vec4(0.0, 0.0, 1.0, 1.0); }\n");
  EXPECT_TRUE(p->reload_if_changed());
  EXPECT_TRUE(p->last_reload_error().empty());
  EXPECT_EQ(draw(*p), glm::vec4(0, 0, 1, 1));
}

TEST_F(HotReloadTest, OffMeansEmbeddedText) {
  set_shader_hot_reload(false);
  Result<std::string> text = shader_source("hrtest/colour.glsl");
  ASSERT_TRUE(text.ok());
  EXPECT_EQ(*text, "vec4 colour() { return vec4(0.0); }\n");
  Result<Program> p = Program::create({"hrtest/hr.vert", "hrtest/hr.frag"});
  ASSERT_TRUE(p.ok());
  write_file(lib_, "vec4 colour() { return vec4(0.5); }\n");
  EXPECT_FALSE(p->reload_if_changed());
}

}  // namespace
}  // namespace sylva::render
