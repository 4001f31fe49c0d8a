#pragma once
// Image: typed pixels with 1-4 channels, read and written through OpenImageIO.
//
// Storage is always 32-bit float per channel, row-major, top row first (y = 0 is the top of
// the picture, as in PNG). Integer formats are normalised on read: u8 / 255, u16 / 65535, so a
// 16-bit height map keeps every one of its 65536 levels exactly. `format()` remembers the file's
// pixel format and is the default format for writing it back.

#include <sylva/core/result.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace sylva {

enum class PixelFormat { kU8, kU16, kF16, kF32 };

const char* to_string(PixelFormat format);

class Image {
 public:
  Image() = default;
  // Zero-filled image. Asserts on invalid sizes (programming error); for sizes that come from
  // users call create(), which returns an error naming the bad value.
  Image(int width, int height, int channels, PixelFormat format = PixelFormat::kF32);
  static Result<Image> create(int width, int height, int channels, PixelFormat format = PixelFormat::kF32);

  int width() const { return width_; }
  int height() const { return height_; }
  int channels() const { return channels_; }
  PixelFormat format() const { return format_; }
  void set_format(PixelFormat format) { format_ = format; }
  bool empty() const { return pixels_.empty(); }
  std::size_t pixel_count() const { return static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_); }

  // Channel c of pixel (x, y); x in [0, width), y in [0, height), c in [0, channels).
  float& at(int x, int y, int c = 0) { return pixels_[index(x, y, c)]; }
  float at(int x, int y, int c = 0) const { return pixels_[index(x, y, c)]; }
  // Clamped-to-edge access, for filters.
  float at_clamped(int x, int y, int c = 0) const;

  std::span<float> data() { return pixels_; }
  std::span<const float> data() const { return pixels_; }

  // Copies channel c into a new one-channel image.
  Image channel(int c) const;

 private:
  std::size_t index(int x, int y, int c) const;

  int width_ = 0;
  int height_ = 0;
  int channels_ = 0;
  PixelFormat format_ = PixelFormat::kF32;
  std::vector<float> pixels_;
};

struct ImageReadOptions {
  int max_side = 32768;          // larger files are refused (kLimit) before any pixel is read
  // So are files whose samples, held as 32-bit floats, take more [bytes]: 2 GiB holds one channel
  // of up to 23170^2 (a 16385^2 height map fits); a lying 30000^2 header is refused unread.
  std::uint64_t max_bytes = 2ull << 30;
  bool allow_non_finite = true;  // false: NaN/Inf samples are an error naming count and position
};

// Reads PNG, EXR, TIFF, JPEG and anything else OpenImageIO reads. Errors name the file and say
// what is wrong: missing (kNotFound), truncated or undecodable (kCorrupt), 0x0, > max_side or
// > max_bytes as floats (kLimit), more than 4 channels or an unknown format (kUnsupported).
Result<Image> read_image(const std::filesystem::path& path, const ImageReadOptions& options = {});

// Writes through a temporary file in the same folder and renames it over `path`, so a failed
// write never destroys an existing file. Float values are clamped to [0, 1] for integer formats.
Status write_image(const std::filesystem::path& path, const Image& image);
Status write_image(const std::filesystem::path& path, const Image& image, PixelFormat format);
// Writes straight to `file` (no temporary, no rename): for a temporary that a FileTransaction
// renames later. The format follows `file`'s extension; errors name `display`, the user's path.
Status write_image_file(const std::filesystem::path& file, const Image& image, PixelFormat format,
                        const std::filesystem::path& display);

// Counts NaN/Inf values; first_x/first_y give the first one in row-major order (-1 if none).
struct NonFiniteReport {
  std::size_t count = 0;
  int first_x = -1;
  int first_y = -1;
};
NonFiniteReport find_non_finite(const Image& image);

}  // namespace sylva
