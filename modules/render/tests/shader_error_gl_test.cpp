// Shader preprocessing and error reporting: errors name the original file and line, in the
// stage file and in included files, before and after an #include.
#include <sylva/render/shader_library.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

namespace sylva::render {
namespace {

using ShaderErrorTest = GlTest;

// Line numbers below are 1-based lines of these sources.
constexpr const char* kGoodLib =
    "// line 1\n"
    "float helper(float x) {\n"
    "  return x * 2.0;\n"
    "}\n";
constexpr const char* kBadLib =
    "// line 1\n"
    "float broken(float x) {\n"
    "  return x * undefined_thing;\n"  // line 3: error
    "}\n";

class ShaderErrors : public ShaderErrorTest {
 protected:
  void SetUp() override {
    ShaderErrorTest::SetUp();
    register_shader_source("rtest/lib/good.glsl", kGoodLib);
    register_shader_source("rtest/lib/bad.glsl", kBadLib);
    register_shader_source("rtest/plain.vert",
                           "#version 450 core\n"
                           "void main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n");
  }
};

TEST_F(ShaderErrors, ErrorInStageFileAfterIncludeNamesFileAndLine) {
  register_shader_source("rtest/after_include.frag",
                         "#version 450 core\n"                   // 1
                         "#include \"rtest/lib/good.glsl\"\n"    // 2
                         "out vec4 o_color;\n"                   // 3
                         "void main() {\n"                       // 4
                         "  o_color = vec4(helper(1.0));\n"      // 5
                         "  o_color += not_declared;\n"          // 6: error
                         "}\n");
  Result<Program> p = Program::create({"rtest/plain.vert", "rtest/after_include.frag"});
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().code, ErrorCode::kGl);
  EXPECT_NE(p.error().message.find("rtest/after_include.frag:6"), std::string::npos) << p.error().message;
  EXPECT_NE(p.error().message.find("not_declared"), std::string::npos) << p.error().message;
}

TEST_F(ShaderErrors, ErrorInIncludedFileNamesThatFile) {
  register_shader_source("rtest/includes_bad.frag",
                         "#version 450 core\n"
                         "// a comment\n"
                         "#include \"rtest/lib/good.glsl\"\n"
                         "#include \"lib/bad.glsl\"\n"  // relative to rtest/
                         "out vec4 o_color;\n"
                         "void main() { o_color = vec4(broken(helper(1.0))); }\n");
  Result<Program> p = Program::create({"rtest/plain.vert", "rtest/includes_bad.frag"});
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.error().message.find("rtest/lib/bad.glsl:3"), std::string::npos) << p.error().message;
  // Every message about bad.glsl's line 3 names bad.glsl, none the including file.
  EXPECT_EQ(p.error().message.find("rtest/includes_bad.frag:3"), std::string::npos) << p.error().message;
  EXPECT_EQ(p.error().message.find("0:"), std::string::npos) << "raw source-string numbers leaked:\n"
                                                              << p.error().message;
}

TEST_F(ShaderErrors, ErrorInVertexStageIsReported) {
  register_shader_source("rtest/bad.vert",
                         "#version 450 core\n"
                         "void main() {\n"
                         "  gl_Position = vec3(1.0);\n"  // line 3: type mismatch
                         "}\n");
  register_shader_source("rtest/ok.frag",
                         "#version 450 core\nout vec4 o;\nvoid main() { o = vec4(1.0); }\n");
  Result<Program> p = Program::create({"rtest/bad.vert", "rtest/ok.frag"});
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.error().message.find("rtest/bad.vert:3"), std::string::npos) << p.error().message;
}

TEST_F(ShaderErrors, DefinesDoNotShiftLineNumbers) {
  register_shader_source("rtest/with_defines.frag",
                         "#version 450 core\n"
                         "out vec4 o_color;\n"
                         "void main() {\n"
                         "#if VARIANT == 2\n"
                         "  o_color = vec4(oops);\n"  // line 5
                         "#else\n"
                         "  o_color = vec4(1.0);\n"
                         "#endif\n"
                         "}\n");
  Result<Program> ok = Program::create({"rtest/plain.vert", "rtest/with_defines.frag"},
                                       {{"VARIANT", "1"}, {"UNUSED", "3.0"}});
  EXPECT_TRUE(ok.ok()) << ok.error().describe();
  Result<Program> bad = Program::create({"rtest/plain.vert", "rtest/with_defines.frag"}, {{"VARIANT", "2"}});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("rtest/with_defines.frag:5"), std::string::npos) << bad.error().message;
}

TEST_F(ShaderErrors, MissingIncludeNamesIncludingLine) {
  register_shader_source("rtest/missing.frag",
                         "#version 450 core\n"
                         "\n"
                         "#include \"rtest/lib/nope.glsl\"\n"
                         "void main() {}\n");
  Result<Program> p = Program::create({"rtest/plain.vert", "rtest/missing.frag"});
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().code, ErrorCode::kNotFound);
  EXPECT_NE(p.error().message.find("rtest/missing.frag:3"), std::string::npos) << p.error().message;
  EXPECT_NE(p.error().message.find("rtest/lib/nope.glsl"), std::string::npos) << p.error().message;
}

TEST_F(ShaderErrors, IncludeCycleIsAnError) {
  register_shader_source("rtest/lib/a.glsl", "#include \"rtest/lib/b.glsl\"\n");
  register_shader_source("rtest/lib/b.glsl", "\n#include \"rtest/lib/a.glsl\"\n");
  register_shader_source("rtest/cycle.frag", "#version 450 core\n#include \"rtest/lib/a.glsl\"\nvoid main() {}\n");
  Result<PreprocessedShader> pre = preprocess_shader("rtest/cycle.frag");
  ASSERT_FALSE(pre.ok());
  EXPECT_EQ(pre.error().code, ErrorCode::kParse);
  EXPECT_NE(pre.error().message.find("rtest/lib/b.glsl:2"), std::string::npos) << pre.error().message;
  EXPECT_NE(pre.error().message.find("cycle"), std::string::npos) << pre.error().message;
}

TEST_F(ShaderErrors, MalformedIncludeAndMissingVersion) {
  register_shader_source("rtest/malformed.frag", "#version 450 core\n#include <rtest/lib/good.glsl>\n");
  Result<PreprocessedShader> pre = preprocess_shader("rtest/malformed.frag");
  ASSERT_FALSE(pre.ok());
  EXPECT_NE(pre.error().message.find("rtest/malformed.frag:2"), std::string::npos) << pre.error().message;

  register_shader_source("rtest/noversion.frag", "void main() {}\n");
  Result<PreprocessedShader> nv = preprocess_shader("rtest/noversion.frag");
  ASSERT_FALSE(nv.ok());
  EXPECT_NE(nv.error().message.find("#version"), std::string::npos);

  Result<Program> unknown = Program::create({"rtest/plain.vert", "rtest/not_registered.frag"});
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ErrorCode::kNotFound);
  EXPECT_NE(unknown.error().message.find("rtest/not_registered.frag"), std::string::npos);

  Result<Program> bad_stage = Program::create({"rtest/lib/good.glsl"});
  ASSERT_FALSE(bad_stage.ok());
  EXPECT_NE(bad_stage.error().message.find("rtest/lib/good.glsl"), std::string::npos);
}

TEST_F(ShaderErrors, IncludedOnceEvenWhenIncludedTwice) {
  register_shader_source("rtest/lib/uses_good.glsl", "#include \"rtest/lib/good.glsl\"\n"
                                                     "float twice(float x) { return helper(helper(x)); }\n");
  register_shader_source("rtest/twice.frag",
                         "#version 450 core\n"
                         "#include \"rtest/lib/good.glsl\"\n"
                         "#include \"rtest/lib/uses_good.glsl\"\n"
                         "#include \"rtest/lib/good.glsl\"\n"
                         "out vec4 o;\n"
                         "void main() { o = vec4(twice(0.25)); }\n");
  Result<PreprocessedShader> pre = preprocess_shader("rtest/twice.frag");
  ASSERT_TRUE(pre.ok()) << pre.error().describe();
  std::size_t count = 0;
  for (std::size_t pos = pre->text.find("float helper"); pos != std::string::npos;
       pos = pre->text.find("float helper", pos + 1)) {
    ++count;
  }
  EXPECT_EQ(count, 1u);
  Result<Program> p = Program::create({"rtest/plain.vert", "rtest/twice.frag"});
  EXPECT_TRUE(p.ok()) << p.error().describe();
}

TEST_F(ShaderErrors, IncludeInsideBlockCommentIsIgnored) {
  register_shader_source("rtest/commented.frag",
                         "#version 450 core\n"
                         "/* an example:\n"
                         "#include \"rtest/lib/nope.glsl\"\n"
                         "*/\n"
                         "out vec4 o;\n"
                         "void main() { o = vec4(1.0); }\n");
  Result<Program> p = Program::create({"rtest/plain.vert", "rtest/commented.frag"});
  EXPECT_TRUE(p.ok()) << p.error().describe();
}

TEST(ShaderLog, MapsSourceStringNumbers) {
  const std::vector<std::string> files{"mod/a.frag", "mod/lib/b.glsl"};
  // Lines are encoded as file_index * kShaderLineStride + line, so the source-string number
  // the driver prints does not matter (Mesa prints 0 for many errors after a #line).
  EXPECT_EQ(map_shader_log("1:100012(5): error: x", files), "mod/lib/b.glsl:12(5): error: x");
  EXPECT_EQ(map_shader_log("0:100012(5): error: x", files), "mod/lib/b.glsl:12(5): error: x");
  EXPECT_EQ(map_shader_log("0:7(2): error: x", files), "mod/a.frag:7(2): error: x");
  EXPECT_EQ(map_shader_log("0(7) : error C0000: y", files), "mod/a.frag:7 : error C0000: y");
  EXPECT_EQ(map_shader_log("ERROR: 1:100003: z", files), "ERROR: mod/lib/b.glsl:3: z");
  EXPECT_EQ(map_shader_log("no location here", files), "no location here");
  EXPECT_EQ(map_shader_log("0:900001(1): error: unknown file", files), "0:900001(1): error: unknown file");
}

TEST(ShaderLog, StageFromExtension) {
  EXPECT_EQ(shader_stage_for("m/x.vert"), static_cast<GLenum>(GL_VERTEX_SHADER));
  EXPECT_EQ(shader_stage_for("m/x.tesc"), static_cast<GLenum>(GL_TESS_CONTROL_SHADER));
  EXPECT_EQ(shader_stage_for("m/x.tese"), static_cast<GLenum>(GL_TESS_EVALUATION_SHADER));
  EXPECT_EQ(shader_stage_for("m/x.geom"), static_cast<GLenum>(GL_GEOMETRY_SHADER));
  EXPECT_EQ(shader_stage_for("m/x.frag"), static_cast<GLenum>(GL_FRAGMENT_SHADER));
  EXPECT_EQ(shader_stage_for("m/x.comp"), static_cast<GLenum>(GL_COMPUTE_SHADER));
  EXPECT_EQ(shader_stage_for("m/x.glsl"), 0u);
}

TEST_F(ShaderErrorTest, EmbeddedRenderLibraryCompiles) {
  embedded::register_render_shaders();
  EXPECT_TRUE(has_shader("render/lib/common.glsl"));
  EXPECT_TRUE(has_shader("render/lib/lighting.glsl"));
  EXPECT_TRUE(has_shader("render/lib/fog.glsl"));
  EXPECT_TRUE(has_shader("render/lib/sky.glsl"));
  register_shader_source("rtest/all_libs.frag",
                         "#version 450 core\n"
                         "#include \"render/lib/common.glsl\"\n"
                         "#include \"render/lib/lighting.glsl\"\n"
                         "#include \"render/lib/fog.glsl\"\n"
                         "#include \"render/lib/sky.glsl\"\n"
                         "in vec3 v_pos;\n"
                         "out vec4 o;\n"
                         "void main() {\n"
                         "  vec3 n = normalize(vec3(0.0, 1.0, 0.2));\n"
                         "  vec3 c = shade_diffuse(vec3(0.5), n, 1.0) + sky_color(n) * saturate(luminance(n));\n"
                         "  o = vec4(apply_fog(c, v_pos) + blinn_phong(n, n, sun_direction(), 32.0), 1.0);\n"
                         "}\n");
  register_shader_source("rtest/all_libs.vert",
                         "#version 450 core\nout vec3 v_pos;\n"
                         "void main() { v_pos = vec3(1.0); gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n");
  Result<Program> p = Program::create({"rtest/all_libs.vert", "rtest/all_libs.frag"});
  EXPECT_TRUE(p.ok()) << p.error().describe();
}

}  // namespace
}  // namespace sylva::render
