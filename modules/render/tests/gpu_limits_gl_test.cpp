// Sizes checked before allocating and GL errors that fail a frame instead of scrolling by:
// render targets over their byte budget are refused without a GL call that could run out of
// memory, and check_frame_gl_errors turns any GL error since its mark into an error that names
// the frame and the first message.
#include <sylva/render/framebuffer.hpp>
#include <sylva/render/gl_debug.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

using namespace sylva;
using namespace sylva::render;

using GpuLimitsGl = GlTest;

TEST(FramebufferBytes, CountsAttachmentsSamplesAndResolveTargets) {
  EXPECT_EQ(Framebuffer::estimated_bytes({.width = 100, .height = 10, .color_formats = {GL_RGBA8}}), 100u * 10u * 8u);
  EXPECT_EQ(Framebuffer::estimated_bytes({.width = 100, .height = 10, .color_formats = {GL_RGBA16F},
                                          .depth_format = GL_NONE}),
            100u * 10u * 8u);
  // 4 samples of (RGBA8 + depth) plus the single-sample resolve pair.
  EXPECT_EQ(Framebuffer::estimated_bytes({.width = 10, .height = 10, .color_formats = {GL_RGBA8}, .samples = 4}),
            10u * 10u * (8u * 4u + 8u));
}

TEST_F(GpuLimitsGl, RenderTargetOverItsBudgetIsRefusedBeforeAllocating) {
  const std::size_t mark = gl_error_mark();
  // 16384^2 RGBA32F + float depth = 5 GiB: within GL's side limits, beyond what a frame may hold.
  auto fb = Framebuffer::create({.width = 16384, .height = 16384, .color_formats = {GL_RGBA32F}});
  ASSERT_FALSE(fb.ok());
  EXPECT_EQ(fb.error().code, ErrorCode::kLimit);
  EXPECT_NE(fb.error().message.find("16384x16384"), std::string::npos) << fb.error().message;
  EXPECT_NE(fb.error().message.find("5120 MiB"), std::string::npos) << fb.error().message;
  EXPECT_TRUE(check_frame_gl_errors(mark, "refusal").ok());
}

TEST_F(GpuLimitsGl, AnyGlErrorInAFrameFailsItNamingTheFirstMessage) {
  const std::size_t clean = gl_error_mark();
  EXPECT_TRUE(check_frame_gl_errors(clean, "frame 0").ok());
  const std::size_t mark = gl_error_mark();
  glBindBufferBase(GL_UNIFORM_BUFFER, 1u << 20, 0);  // index far beyond GL_MAX_UNIFORM_BUFFER_BINDINGS
  glBindBufferBase(GL_UNIFORM_BUFFER, 1u << 20, 0);
  Status s = check_frame_gl_errors(mark, "frame 7");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kGl);
  EXPECT_NE(s.error().message.find("during frame 7"), std::string::npos) << s.error().message;
  EXPECT_NE(s.error().message.find("GL_INVALID_VALUE"), std::string::npos) << s.error().message;
  take_gl_errors();  // provoked on purpose: not this test's failure
  // The next frame starts clean.
  EXPECT_TRUE(check_frame_gl_errors(gl_error_mark(), "frame 8").ok());
}
