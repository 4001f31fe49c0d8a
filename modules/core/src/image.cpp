#include <sylva/core/image.hpp>

#include <sylva/core/assert.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace sylva {

const char* to_string(PixelFormat format) {
  switch (format) {
    case PixelFormat::kU8: return "8-bit";
    case PixelFormat::kU16: return "16-bit";
    case PixelFormat::kF16: return "half float";
    case PixelFormat::kF32: return "float";
  }
  return "unknown";
}

namespace {
constexpr int kMaxChannels = 4;

Status validate_size(int width, int height, int channels) {
  if (width <= 0 || height <= 0) {
    return make_error(ErrorCode::kLimit, fmt::format("image size {}x{} is empty", width, height));
  }
  if (channels < 1 || channels > kMaxChannels) {
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("image has {} channels; 1 to {} are supported", channels, kMaxChannels));
  }
  // Guard the element count against overflow (and absurd allocations) before allocating.
  constexpr std::size_t kMaxElements = std::size_t{1} << 34;
  if (static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels) >
      kMaxElements) {
    return make_error(ErrorCode::kLimit, fmt::format("image size {}x{}x{} is too large", width, height, channels));
  }
  return ok_status();
}
}  // namespace

Image::Image(int width, int height, int channels, PixelFormat format)
    : width_(width), height_(height), channels_(channels), format_(format) {
  Status valid = validate_size(width, height, channels);
  SYLVA_ASSERT(valid.ok(), "{}", valid.ok() ? "" : valid.error().message);
  pixels_.assign(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(channels),
                 0.0f);
}

Result<Image> Image::create(int width, int height, int channels, PixelFormat format) {
  Status valid = validate_size(width, height, channels);
  if (!valid.ok()) return valid.error();
  return Image(width, height, channels, format);
}

std::size_t Image::index(int x, int y, int c) const {
  SYLVA_ASSERT(x >= 0 && x < width_ && y >= 0 && y < height_ && c >= 0 && c < channels_,
               "pixel ({}, {}, {}) outside {}x{}x{}", x, y, c, width_, height_, channels_);
  return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) *
             static_cast<std::size_t>(channels_) +
         static_cast<std::size_t>(c);
}

float Image::at_clamped(int x, int y, int c) const {
  return at(std::clamp(x, 0, width_ - 1), std::clamp(y, 0, height_ - 1), c);
}

Image Image::channel(int c) const {
  SYLVA_ASSERT(c >= 0 && c < channels_, "channel {} of a {}-channel image", c, channels_);
  Image out(width_, height_, 1, format_);
  for (std::size_t i = 0; i < pixel_count(); ++i) {
    out.pixels_[i] = pixels_[i * static_cast<std::size_t>(channels_) + static_cast<std::size_t>(c)];
  }
  return out;
}

NonFiniteReport find_non_finite(const Image& image) {
  NonFiniteReport report;
  const auto data = image.data();
  for (std::size_t i = 0; i < data.size(); ++i) {
    if (!std::isfinite(data[i])) {
      if (report.count == 0) {
        const std::size_t pixel = i / static_cast<std::size_t>(image.channels());
        report.first_x = static_cast<int>(pixel % static_cast<std::size_t>(image.width()));
        report.first_y = static_cast<int>(pixel / static_cast<std::size_t>(image.width()));
      }
      ++report.count;
    }
  }
  return report;
}

}  // namespace sylva
