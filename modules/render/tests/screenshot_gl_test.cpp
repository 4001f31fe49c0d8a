// Screenshots round-trip: what save_screenshot writes (PNG 8-bit, EXR half) reads back through
// core's read_image equal to the framebuffer contents; bad paths are errors, not crashes.
#include "support/render_test_support.hpp"

#include <sylva/render/camera.hpp>
#include <sylva/render/readback.hpp>
#include <sylva/render/sky.hpp>
#include <sylva/render/testing.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::render {
namespace {

using ScreenshotTest = GlTest;

Framebuffer render_scene(int w, int h) {
  Framebuffer fb = test::make_target(w, h);
  Result<SkyRenderer> sky = SkyRenderer::create();
  EXPECT_TRUE(sky.ok());
  Camera cam;
  cam.set_aspect(w, h);
  cam.set_yaw_pitch(0.2f, 0.05f);
  fb.bind();
  fb.clear({0, 0, 0, 1});
  // A coloured band on the left so the picture is not symmetric (catches flips).
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, h / 3, w / 4, h / 3);
  const float band[4] = {0.9f, 0.2f, 0.1f, 1.0f};
  const float depth = 0.5f;
  glClearNamedFramebufferfv(fb.id(), GL_COLOR, 0, band);
  glClearNamedFramebufferfv(fb.id(), GL_DEPTH, 0, &depth);
  glDisable(GL_SCISSOR_TEST);
  if (sky.ok()) sky->draw(cam, Lighting{});
  return fb;
}

TEST_F(ScreenshotTest, PngRoundTripIsExact) {
  Framebuffer fb = render_scene(96, 54);
  Result<Image> live = read_color(fb);
  ASSERT_TRUE(live.ok());
  const std::filesystem::path path = test::output_dir() / "screenshot_roundtrip.png";
  Status saved = save_screenshot(fb, path);
  ASSERT_TRUE(saved.ok()) << saved.error().describe();
  Result<Image> loaded = read_image(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
  ASSERT_EQ(loaded->width(), 96);
  ASSERT_EQ(loaded->height(), 54);
  ASSERT_EQ(loaded->channels(), 3);
  float worst = 0.0f;
  for (int y = 0; y < 54; ++y) {
    for (int x = 0; x < 96; ++x) {
      for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(loaded->at(x, y, c) - live->at(x, y, c)));
    }
  }
  EXPECT_LT(worst, 1.0e-6f);  // RGBA8 -> PNG 8-bit is lossless
  // The band is on the left, a third of the way down, as rendered (not flipped).
  EXPECT_NEAR(loaded->at(5, 27, 0), 0.9f, 1.0f / 255.0f);
  EXPECT_NEAR(loaded->at(90, 27, 0), live->at(90, 27, 0), 1e-6f);
  EXPECT_GT(std::abs(loaded->at(90, 27, 2) - 0.1f), 0.05f);  // the sky there is blue-white, not the band
}

TEST_F(ScreenshotTest, ExrRoundTripWithinHalfPrecision) {
  Framebuffer fb = render_scene(48, 32);
  Result<Image> live = read_color(fb);
  ASSERT_TRUE(live.ok());
  const std::filesystem::path path = test::output_dir() / "screenshot_roundtrip.exr";
  ASSERT_TRUE(save_screenshot(fb, path).ok());
  Result<Image> loaded = read_image(path);
  ASSERT_TRUE(loaded.ok()) << loaded.error().describe();
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 48; ++x) {
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(loaded->at(x, y, c), live->at(x, y, c), 1.0e-3f);
    }
  }
}

TEST_F(ScreenshotTest, BadPathIsAnErrorAndKeepsNothingHalfWritten) {
  Framebuffer fb = render_scene(16, 16);
  Status s = save_screenshot(fb, "/nonexistent-dir-sylva/shot.png");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("nonexistent-dir-sylva"), std::string::npos) << s.error().message;
}

}  // namespace
}  // namespace sylva::render
