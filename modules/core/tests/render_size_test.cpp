// Rendered image sizes: parsed once for the player, editor and bench, bounded per side and in
// pixels so a frame's render targets fit (16384x16384 used to write a black picture, exit 0).
#include <sylva/core/render_size.hpp>

#include <gtest/gtest.h>

using sylva::parse_render_size;

TEST(RenderSize, AcceptsSizesWithinBothBounds) {
  EXPECT_EQ(parse_render_size("1280x720", "--size").value(), glm::ivec2(1280, 720));
  EXPECT_EQ(parse_render_size("16X16", "--size").value(), glm::ivec2(16, 16));
  EXPECT_EQ(parse_render_size("8192x8192", "--size").value(), glm::ivec2(8192, 8192));
  EXPECT_EQ(parse_render_size("16384x4096", "--size").value(), glm::ivec2(16384, 4096));
}

TEST(RenderSize, RefusesWithTheParameterAndTheLimit) {
  auto huge = parse_render_size("16384x16384", "--size");
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().message,
            "--size: 16384x16384 is 268435456 pixels, above the limit of 67108864 (8192x8192) that the render "
            "targets of a frame can hold");
  auto side = parse_render_size("20000x16", "screenshot");
  ASSERT_FALSE(side.ok());
  EXPECT_EQ(side.error().message, "screenshot: 20000x16 is outside 16..16384 pixels per side");
  for (const char* bad : {"", "x", "12", "12x", "x12", "-16x16", "16x16x16", "1e3x16", "99999999999x16"}) {
    auto r = parse_render_size(bad, "--size");
    ASSERT_FALSE(r.ok()) << bad;
    EXPECT_EQ(r.error().message.rfind("--size: ", 0), 0u) << r.error().message;
  }
}
