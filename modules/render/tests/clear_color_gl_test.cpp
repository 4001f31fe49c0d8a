// Clear-colour read-back through Framebuffer and read_color, single-sampled and MSAA.
#include "support/render_test_support.hpp"

#include <sylva/render/framebuffer.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

namespace sylva::render {
namespace {

using ClearColorTest = GlTest;

TEST_F(ClearColorTest, ReadsBackTheClearColour) {
  Framebuffer fb = test::make_target(37, 21);  // odd sizes catch row-alignment bugs
  ASSERT_TRUE(fb);
  fb.bind();
  fb.clear({0.25f, 0.5f, 0.75f, 1.0f});
  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  ASSERT_EQ(image->width(), 37);
  ASSERT_EQ(image->height(), 21);
  ASSERT_EQ(image->channels(), 4);
  // RGBA8 stores round(v * 255): 64, 128, 191.
  const float expected[4] = {64.0f / 255.0f, 128.0f / 255.0f, 191.0f / 255.0f, 1.0f};
  for (int y = 0; y < image->height(); ++y) {
    for (int x = 0; x < image->width(); ++x) {
      for (int c = 0; c < 4; ++c) ASSERT_NEAR(image->at(x, y, c), expected[c], 1.0e-6f) << x << "," << y << "," << c;
    }
  }
}

TEST_F(ClearColorTest, DepthClearsToZeroForReversedZ) {
  Framebuffer fb = test::make_target(16, 8);
  fb.bind();
  fb.clear({0, 0, 0, 1});
  Result<Image> depth = read_depth(fb);
  ASSERT_TRUE(depth.ok()) << depth.error().describe();
  for (float v : depth->data()) ASSERT_EQ(v, 0.0f);
  fb.clear({0, 0, 0, 1}, 0.625f);
  depth = read_depth(fb);
  for (float v : depth->data()) ASSERT_EQ(v, 0.625f);  // 32-bit float depth is exact
}

TEST_F(ClearColorTest, MultisampledTargetResolves) {
  Framebuffer fb = test::make_target(32, 16, 4);
  ASSERT_TRUE(fb);
  EXPECT_TRUE(fb.multisampled());
  fb.bind();
  fb.clear({1.0f, 0.0f, 0.5f, 1.0f});
  Result<Image> image = read_color(fb);
  ASSERT_TRUE(image.ok()) << image.error().describe();
  EXPECT_EQ(test::count_color(*image, 1.0f, 0.0f, 128.0f / 255.0f), 32 * 16);
}

// The resolve copies every pixel whatever state the last pass left: a scissor rectangle (blits
// obey it) and closed write masks (NVIDIA's driver honours them in blits; a pass ending with
// depth writes off left the resolved depth uninitialised there: NaN on an H200). The state is
// restored afterwards.
TEST_F(ClearColorTest, ResolveCopiesEveryPixelWhateverTheLastPassLeft) {
  Framebuffer fb = test::make_target(32, 16, 4);
  ASSERT_TRUE(fb.multisampled());
  fb.bind();
  fb.clear({1.0f, 0.0f, 0.5f, 1.0f}, 0.625f);
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 1, 1);
  glDepthMask(GL_FALSE);
  glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  Result<Image> depth = read_depth(fb);
  Result<Image> image = read_color(fb);
  EXPECT_TRUE(glIsEnabled(GL_SCISSOR_TEST));
  GLboolean depth_mask = GL_TRUE;
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask);
  EXPECT_EQ(depth_mask, GL_FALSE);
  glDisable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  ASSERT_TRUE(depth.ok()) << depth.error().describe();
  ASSERT_TRUE(image.ok()) << image.error().describe();
  std::size_t wrong_depth = 0;
  for (float v : depth->data()) wrong_depth += v == 0.625f ? 0 : 1;
  EXPECT_EQ(wrong_depth, 0u);
  EXPECT_EQ(test::count_color(*image, 1.0f, 0.0f, 128.0f / 255.0f), 32 * 16);
}

TEST_F(ClearColorTest, SeveralColourAttachments) {
  Result<Framebuffer> fb = Framebuffer::create({.width = 8, .height = 8, .color_formats = {GL_RGBA8, GL_RGBA16F}});
  ASSERT_TRUE(fb.ok()) << fb.error().describe();
  fb->bind();
  fb->clear({0.5f, 0.25f, 0.125f, 1.0f});
  Result<Image> a = read_color(*fb, 1);
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(a->at(3, 3, 0), 0.5f);  // half float holds these exactly
  EXPECT_EQ(a->at(3, 3, 2), 0.125f);
  Result<Image> out_of_range = read_color(*fb, 2);
  ASSERT_FALSE(out_of_range.ok());
  EXPECT_NE(out_of_range.error().message.find("attachment 2"), std::string::npos);
}

TEST_F(ClearColorTest, BadFramebufferRequestsAreErrors) {
  Result<Framebuffer> zero = Framebuffer::create({.width = 0, .height = 8});
  ASSERT_FALSE(zero.ok());
  EXPECT_EQ(zero.error().code, ErrorCode::kInvalidArgument);
  Result<Framebuffer> huge = Framebuffer::create({.width = 1 << 20, .height = 8});
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().code, ErrorCode::kLimit);
  Result<Framebuffer> samples = Framebuffer::create({.width = 8, .height = 8, .samples = 999});
  ASSERT_FALSE(samples.ok());
  EXPECT_EQ(samples.error().code, ErrorCode::kLimit);
  Result<Framebuffer> depth_only = Framebuffer::create({.width = 8, .height = 8, .color_formats = {}});
  ASSERT_TRUE(depth_only.ok()) << depth_only.error().describe();
  EXPECT_FALSE(read_color(*depth_only).ok());
}

}  // namespace
}  // namespace sylva::render
