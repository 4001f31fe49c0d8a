// Pixels to sylva::Image and screenshots (readback.hpp).
#include <sylva/render/readback.hpp>

#include <epoxy/gl.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sylva::render {
namespace {

// GL rows are bottom-up; Image rows are top-down.
Image to_image_flipped(const std::vector<float>& pixels, int width, int height, int channels) {
  Image image(width, height, channels);
  const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  std::span<float> dst = image.data();
  for (int y = 0; y < height; ++y) {
    const std::size_t from = static_cast<std::size_t>(height - 1 - y) * row;
    std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(from), row,
                dst.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(y) * row));
  }
  return image;
}

// Room for a readback of width x height x channels floats. GL takes the buffer size as a 32-bit
// GLsizei, so a read of 2 GiB or more (w * h >= 2^27 for RGBA floats) would overflow it: refuse
// before allocating.
Result<std::vector<float>> readback_storage(int width, int height, int channels, std::string_view what) {
  const std::uint64_t bytes = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) *
                              static_cast<std::uint64_t>(channels) * sizeof(float);
  if (bytes > static_cast<std::uint64_t>(std::numeric_limits<GLsizei>::max())) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: reading back {}x{} pixels needs {} MiB, above GL's 2 GiB per "
                                                     "read; use a smaller size",
                                                     what, width, height, bytes >> 20));
  }
  return std::vector<float>(static_cast<std::size_t>(bytes / sizeof(float)));
}

}  // namespace

Result<Image> read_color(const Framebuffer& fb, int attachment) {
  if (!fb) return make_error(ErrorCode::kInvalidArgument, "read_color: empty framebuffer");
  if (attachment < 0 || attachment >= static_cast<int>(fb.desc().color_formats.size())) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("read_color: attachment {} of a framebuffer with {} colour attachments", attachment,
                                  fb.desc().color_formats.size()));
  }
  fb.resolve();
  const Texture& tex = fb.color_texture(attachment);
  auto storage = readback_storage(fb.width(), fb.height(), 4, "read_color");
  if (!storage.ok()) return storage.error();
  std::vector<float>& pixels = *storage;
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(tex.id(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pixels.size() * sizeof(float)), pixels.data());
  return to_image_flipped(pixels, fb.width(), fb.height(), 4);
}

Result<Image> read_depth(const Framebuffer& fb) {
  if (!fb || fb.desc().depth_format == GL_NONE) {
    return make_error(ErrorCode::kInvalidArgument, "read_depth: framebuffer has no depth attachment");
  }
  fb.resolve();
  const Texture& tex = fb.depth_texture();
  auto storage = readback_storage(fb.width(), fb.height(), 1, "read_depth");
  if (!storage.ok()) return storage.error();
  std::vector<float>& pixels = *storage;
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(tex.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<GLsizei>(pixels.size() * sizeof(float)),
                    pixels.data());
  return to_image_flipped(pixels, fb.width(), fb.height(), 1);
}

Result<Image> read_bound_framebuffer(int x, int y, int width, int height) {
  if (width < 1 || height < 1) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("read_bound_framebuffer: size {}x{}", width, height));
  }
  auto storage = readback_storage(width, height, 4, "read_bound_framebuffer");
  if (!storage.ok()) return storage.error();
  std::vector<float>& pixels = *storage;
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glReadnPixels(x, y, width, height, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pixels.size() * sizeof(float)),
                pixels.data());
  return to_image_flipped(pixels, width, height, 4);
}

Status save_screenshot(const Framebuffer& fb, const std::filesystem::path& path) {
  Result<Image> rgba = read_color(fb, 0);
  if (!rgba.ok()) return rgba.error();
  // Screenshots are opaque pictures: drop alpha, which holds whatever the passes left there.
  Image rgb(rgba->width(), rgba->height(), 3);
  for (int y = 0; y < rgb.height(); ++y) {
    for (int x = 0; x < rgb.width(); ++x) {
      for (int c = 0; c < 3; ++c) rgb.at(x, y, c) = rgba->at(x, y, c);
    }
  }
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  const PixelFormat format = ext == ".exr" ? PixelFormat::kF16 : (ext == ".tif" || ext == ".tiff") ? PixelFormat::kU16
                                                                                                     : PixelFormat::kU8;
  rgb.set_format(format);
  return write_image(path, rgb, format);
}

}  // namespace sylva::render
