// Context creation, GL version, debug output and the error recorder that GL tests rely on.
#include <sylva/render/gl_context.hpp>
#include <sylva/render/gl_debug.hpp>
#include <sylva/render/testing.hpp>

#include <epoxy/gl.h>
#include <gtest/gtest.h>

#include <cstdlib>

namespace sylva::render {
namespace {

using ContextTest = GlTest;

TEST_F(ContextTest, HeadlessIsGl45Core) {
  EXPECT_EQ(context_->kind(), ContextKind::kHeadless);
  EXPECT_GE(epoxy_gl_version(), 45);
  GLint mask = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
  EXPECT_NE(mask & GL_CONTEXT_CORE_PROFILE_BIT, 0);
  EXPECT_FALSE(context_->renderer().empty());
  EXPECT_NE(context_->platform().find("EGL"), std::string::npos) << context_->platform();
  EXPECT_EQ(context_->framebuffer_size(), glm::ivec2(0, 0));
  EXPECT_EQ(context_->window(), nullptr);
}

TEST_F(ContextTest, ErrorRecorderCatchesGlErrors) {
  const std::size_t before = gl_error_count();
  glEnable(0x1234);  // GL_INVALID_ENUM on purpose
  (void)check_gl_errors("provoked");
  const std::vector<std::string> errors = take_errors();
  ASSERT_FALSE(errors.empty());
  EXPECT_GT(gl_error_count(), before);
  bool names_enum = false;
  for (const std::string& e : errors) names_enum = names_enum || e.find("INVALID_ENUM") != std::string::npos ||
                                                       e.find("GL_INVALID_ENUM") != std::string::npos ||
                                                       e.find("invalid") != std::string::npos;
  EXPECT_TRUE(names_enum) << errors.front();
}

TEST_F(ContextTest, CheckGlErrorsReturnsStatus) {
  EXPECT_TRUE(check_gl_errors("clean").ok());
  glBindBuffer(GL_ARRAY_BUFFER, 987654);  // not a buffer name: GL_INVALID_OPERATION
  Status s = check_gl_errors("bad bind");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("bad bind"), std::string::npos);
  EXPECT_NE(s.error().message.find("GL_INVALID_OPERATION"), std::string::npos) << s.error().message;
  (void)take_errors();
}

TEST_F(ContextTest, SecondHeadlessContextCoexists) {
  Result<GlContext> other = GlContext::create_headless();
  ASSERT_TRUE(other.ok()) << other.error().describe();
  EXPECT_GE(epoxy_gl_version(), 45);
  other.value().make_current();
  GLuint buffer = 0;
  glCreateBuffers(1, &buffer);
  EXPECT_NE(buffer, 0u);
  glDeleteBuffers(1, &buffer);
  context_->make_current();
}

TEST(WindowContext, ReportsWhetherADisplayExists) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  const bool env = (display != nullptr && *display != '\0') || (wayland != nullptr && *wayland != '\0');
  if (!env) {
    EXPECT_FALSE(display_available());
    Result<GlContext> window = GlContext::create_window({.width = 64, .height = 64, .visible = false});
    if (!window.ok()) {
      EXPECT_EQ(window.error().code, ErrorCode::kGl);
    }
    return;
  }
  if (!display_available()) GTEST_SKIP() << "DISPLAY is set but GLFW cannot open it";
  Result<GlContext> window = GlContext::create_window({.width = 64, .height = 48, .visible = false});
  ASSERT_TRUE(window.ok()) << window.error().describe();
  EXPECT_EQ(window->kind(), ContextKind::kWindow);
  EXPECT_NE(window->window(), nullptr);
  EXPECT_GE(epoxy_gl_version(), 45);
  const glm::ivec2 size = window->framebuffer_size();
  EXPECT_GT(size.x, 0);
  EXPECT_GT(size.y, 0);
}

TEST(WindowContext, RejectsBadSize) {
  Result<GlContext> window = GlContext::create_window({.width = 0, .height = 10});
  ASSERT_FALSE(window.ok());
  EXPECT_EQ(window.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(window.error().message.find("0x10"), std::string::npos);
}

}  // namespace
}  // namespace sylva::render
