// Textures from core images: orientation (Image row 0 = top), exact texel values, mip chains,
// 2D arrays, samplers, and clear errors for bad input.
#include "support/render_test_support.hpp"

#include <sylva/render/readback.hpp>
#include <sylva/render/sampler.hpp>
#include <sylva/render/testing.hpp>
#include <sylva/render/texture.hpp>
#include <sylva/render/vertex_array.hpp>

#include <gtest/gtest.h>

#include <vector>

namespace sylva::render {
namespace {

class TextureTest : public GlTest {
 protected:
  void SetUp() override {
    GlTest::SetUp();
    register_shader_source("rtest/fs.vert",
                           "#version 450 core\n"
                           "void main() {\n"
                           "  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2)) * 2.0 - 1.0;\n"
                           "  gl_Position = vec4(p, 0.5, 1.0);\n"
                           "}\n");
    register_shader_source("rtest/fetch.frag",
                           "#version 450 core\n"
                           "layout(binding = 0) uniform sampler2D u_tex;\n"
                           "out vec4 o;\n"
                           "void main() { o = texelFetch(u_tex, ivec2(gl_FragCoord.xy), 0); }\n");
    register_shader_source("rtest/fetch_array.frag",
                           "#version 450 core\n"
                           "layout(binding = 0) uniform sampler2DArray u_tex;\n"
                           "uniform int u_layer;\n"
                           "out vec4 o;\n"
                           "void main() { o = texelFetch(u_tex, ivec3(ivec2(gl_FragCoord.xy), u_layer), 0); }\n");
    register_shader_source("rtest/sample.frag",
                           "#version 450 core\n"
                           "layout(binding = 0) uniform sampler2D u_tex;\n"
                           "uniform vec2 u_uv;\n"
                           "out vec4 o;\n"
                           "void main() { o = texture(u_tex, u_uv); }\n");
    vao_ = VertexArray::create();
  }

  Image pattern(int w, int h, int channels, float seed) {
    Image im(w, h, channels);
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        for (int c = 0; c < channels; ++c) {
          im.at(x, y, c) = static_cast<float>((x * 37 + y * 101 + c * 53 + static_cast<int>(seed * 7)) % 256) / 255.0f;
        }
      }
    }
    return im;
  }

  Image draw_fullscreen(const Program& p, int w, int h) {
    Result<Framebuffer> fb = Framebuffer::create({.width = w, .height = h, .color_formats = {GL_RGBA32F}});
    EXPECT_TRUE(fb.ok());
    fb->bind();
    glDisable(GL_DEPTH_TEST);
    p.use();
    vao_.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    Result<Image> image = read_color(*fb);
    return image.ok() ? std::move(image).value() : Image();
  }

  VertexArray vao_;
};

TEST_F(TextureTest, ImageRoundTripsThroughTextureAndFramebuffer) {
  const Image src = pattern(13, 7, 4, 1.0f);  // odd sizes: alignment and orientation bugs show
  Result<Texture> tex = Texture::from_image(src, {.mipmaps = false});
  ASSERT_TRUE(tex.ok()) << tex.error().describe();
  EXPECT_EQ(tex->levels(), 1);
  EXPECT_EQ(tex->format(), static_cast<GLenum>(GL_RGBA8));
  Program p = test::build_or_fail({"rtest/fs.vert", "rtest/fetch.frag"});
  tex->bind(0);
  const Image out = draw_fullscreen(p, 13, 7);
  // Texture upload flips rows and read-back flips them again: the image comes back unchanged.
  EXPECT_LT(test::max_abs_diff(out, src), 1.0e-6f);
}

TEST_F(TextureTest, ChannelCountsAndEncodings) {
  for (int channels = 1; channels <= 4; ++channels) {
    const Image src = pattern(8, 5, channels, static_cast<float>(channels));
    for (TextureEncoding enc : {TextureEncoding::kUnorm8, TextureEncoding::kUnorm16, TextureEncoding::kFloat32}) {
      Result<Texture> tex = Texture::from_image(src, {.encoding = enc, .mipmaps = false});
      ASSERT_TRUE(tex.ok());
      EXPECT_EQ(tex->format(), internal_format(channels, enc));
      Program p = test::build_or_fail({"rtest/fs.vert", "rtest/fetch.frag"});
      tex->bind(0);
      const Image out = draw_fullscreen(p, 8, 5);
      for (int y = 0; y < 5; ++y) {
        for (int x = 0; x < 8; ++x) {
          for (int c = 0; c < channels; ++c) ASSERT_NEAR(out.at(x, y, c), src.at(x, y, c), 1.0e-6f);
        }
      }
    }
  }
}

TEST_F(TextureTest, MipChainAveragesDown) {
  Image checker(64, 32, 1);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) checker.at(x, y) = ((x + y) % 2 == 0) ? 1.0f : 0.0f;
  }
  Result<Texture> tex = Texture::from_image(checker, {.encoding = TextureEncoding::kFloat32});
  ASSERT_TRUE(tex.ok());
  EXPECT_EQ(tex->levels(), 7);  // 64 -> 1
  EXPECT_EQ(mip_levels(64, 32), 7);
  EXPECT_EQ(mip_levels(1, 1), 1);
  EXPECT_EQ(mip_levels(1000, 3), 10);
  float top = -1.0f;
  glGetTextureImage(tex->id(), 6, GL_RED, GL_FLOAT, sizeof(float), &top);
  EXPECT_NEAR(top, 0.5f, 1.0e-5f);
}

TEST_F(TextureTest, ArrayLayersAreIndependent) {
  std::vector<Image> layers;
  for (int i = 0; i < 3; ++i) layers.push_back(pattern(9, 6, 4, static_cast<float>(i * 3)));
  Result<Texture> tex = Texture::from_images(layers, {.mipmaps = false});
  ASSERT_TRUE(tex.ok()) << tex.error().describe();
  EXPECT_EQ(tex->target(), static_cast<GLenum>(GL_TEXTURE_2D_ARRAY));
  EXPECT_EQ(tex->layers(), 3);
  Program p = test::build_or_fail({"rtest/fs.vert", "rtest/fetch_array.frag"});
  tex->bind(0);
  for (int i = 0; i < 3; ++i) {
    p.set("u_layer", i);
    const Image out = draw_fullscreen(p, 9, 6);
    EXPECT_LT(test::max_abs_diff(out, layers[static_cast<std::size_t>(i)]), 1.0e-6f) << "layer " << i;
  }
}

TEST_F(TextureTest, SamplerOverridesTextureFiltering) {
  Image two(2, 1, 1);
  two.at(0, 0) = 0.0f;
  two.at(1, 0) = 1.0f;
  Result<Texture> tex = Texture::from_image(two, {.encoding = TextureEncoding::kFloat32, .mipmaps = false,
                                                  .min_filter = GL_NEAREST, .mag_filter = GL_NEAREST,
                                                  .wrap = GL_CLAMP_TO_EDGE});
  ASSERT_TRUE(tex.ok());
  Program p = test::build_or_fail({"rtest/fs.vert", "rtest/sample.frag"});
  p.set("u_uv", glm::vec2(0.5f, 0.5f));  // exactly between the two texel centres
  tex->bind(0);
  const Image nearest = draw_fullscreen(p, 1, 1);
  EXPECT_TRUE(nearest.at(0, 0) == 0.0f || nearest.at(0, 0) == 1.0f);
  Sampler linear = Sampler::create({.min_filter = GL_LINEAR, .mag_filter = GL_LINEAR, .wrap_s = GL_CLAMP_TO_EDGE,
                                    .wrap_t = GL_CLAMP_TO_EDGE, .max_anisotropy = 4.0f});
  linear.bind(0);
  const Image blended = draw_fullscreen(p, 1, 1);
  EXPECT_NEAR(blended.at(0, 0), 0.5f, 1.0e-3f);
  Sampler::unbind(0);
}

TEST_F(TextureTest, BadInputIsAnError) {
  Result<Texture> empty = Texture::from_image(Image());
  ASSERT_FALSE(empty.ok());
  EXPECT_EQ(empty.error().code, ErrorCode::kInvalidArgument);
  std::vector<Image> mismatched{pattern(4, 4, 4, 0), pattern(4, 5, 4, 0)};
  Result<Texture> bad = Texture::from_images(mismatched);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("layer 1"), std::string::npos) << bad.error().message;
  Result<Texture> none = Texture::from_images({});
  EXPECT_FALSE(none.ok());
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  Result<Texture> huge = Texture::from_image(Image(max_size + 1, 1, 1));
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().code, ErrorCode::kLimit);
}

}  // namespace
}  // namespace sylva::render
