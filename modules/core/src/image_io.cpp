// Image reading and writing through OpenImageIO (the only place core touches OIIO).
#include <sylva/core/image.hpp>

#include <sylva/core/atomic_file.hpp>

#include "exr_header_check.hpp"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <system_error>

namespace sylva {
namespace {

namespace fs = std::filesystem;

PixelFormat format_from(const OIIO::TypeDesc& type) {
  switch (type.basetype) {
    case OIIO::TypeDesc::UINT8:
    case OIIO::TypeDesc::INT8: return PixelFormat::kU8;
    case OIIO::TypeDesc::UINT16:
    case OIIO::TypeDesc::INT16: return PixelFormat::kU16;
    case OIIO::TypeDesc::HALF: return PixelFormat::kF16;
    default: return PixelFormat::kF32;
  }
}

OIIO::TypeDesc type_from(PixelFormat format) {
  switch (format) {
    case PixelFormat::kU8: return OIIO::TypeDesc::UINT8;
    case PixelFormat::kU16: return OIIO::TypeDesc::UINT16;
    case PixelFormat::kF16: return OIIO::TypeDesc::HALF;
    case PixelFormat::kF32: return OIIO::TypeDesc::FLOAT;
  }
  return OIIO::TypeDesc::FLOAT;
}

// OIIO keeps a per-thread error string; fetch it so it does not leak into a later message.
// A reader's error text can hold one line per damaged row (thousands for a truncated TIFF):
// the message keeps the first and says how many followed.
std::string first_line_and_count(const std::string& text) {
  const auto end = text.find('\n');
  if (end == std::string::npos) return text;
  const auto more = std::count(text.begin() + static_cast<std::ptrdiff_t>(end), text.end(), '\n') +
                    (text.back() == '\n' ? 0 : 1);
  return more == 0 ? text.substr(0, end) : fmt::format("{}; and {} more like it", text.substr(0, end), more);
}

std::string oiio_error(const OIIO::ImageInput* in) {
  std::string message = in ? in->geterror() : std::string();
  const std::string global = OIIO::geterror();
  if (message.empty()) message = global;
  if (message.empty()) message = "no details from OpenImageIO";
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message;
}

}  // namespace

Result<Image> read_image(const fs::path& path, const ImageReadOptions& options) {
  const std::string name = path.string();
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    return make_error(ErrorCode::kNotFound, fmt::format("{}: no such file", name));
  }
  if (fs::is_directory(path, ec)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: is a folder, not an image", name));
  }
  // OpenEXR allocates whatever its header declares before it checks the file holds it.
  SYLVA_TRY(detail::check_exr_header(path, name, options.max_side));
  // Keep stored values as they are: no premultiplication by alpha (PNG would otherwise
  // associate alpha on read), since our alpha channels are masks and coverage, not opacity.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(name, &config);
  if (!in) {
    const std::string why = oiio_error(nullptr);
    const bool unknown_format = why.find("format") != std::string::npos && why.find("not") != std::string::npos;
    return make_error(unknown_format ? ErrorCode::kUnsupported : ErrorCode::kCorrupt,
                      fmt::format("{}: cannot open as an image ({})", name, why));
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: image is {}x{} (empty)", name, spec.width, spec.height));
  }
  if (spec.width > options.max_side || spec.height > options.max_side) {
    return make_error(ErrorCode::kLimit, fmt::format("{}: image is {}x{}, larger than the limit of {} per side",
                                                     name, spec.width, spec.height, options.max_side));
  }
  // Samples are held as 32-bit floats: a header may claim a size whose pixels would not fit in
  // memory, so the cost is checked before anything is allocated.
  const std::uint64_t bytes = static_cast<std::uint64_t>(spec.width) * static_cast<std::uint64_t>(spec.height) *
                              static_cast<std::uint64_t>(std::max(spec.nchannels, 1)) * sizeof(float);
  if (bytes > options.max_bytes) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("{}: image is {}x{} with {} channels, {} MiB as floats, above the limit of {} MiB", name,
                                  spec.width, spec.height, spec.nchannels, bytes >> 20, options.max_bytes >> 20));
  }
  // A header can claim any size, and the pixels are allocated before they are decoded. Real
  // pixel data shrinks by at most a few thousand to one (deflate 1032:1, LZW about 2700:1, then
  // up to 4x as floats), so a file claiming more than kMaxExpansion float bytes per stored byte is
  // corrupt or a decompression bomb: refused before the allocation (found by the image_map fuzz
  // target: 456 MB for a file of a few hundred bytes).
  constexpr std::uint64_t kMaxExpansion = 65536, kAlwaysAllowed = 64ull << 20;
  const auto stored = static_cast<std::uint64_t>(fs::file_size(path, ec));
  if (!ec && bytes > kAlwaysAllowed && bytes / kMaxExpansion > stored) {
    return make_error(ErrorCode::kCorrupt,
                      fmt::format("{}: header claims {}x{} with {} channels ({} MiB as floats) but the file holds only {} "
                                  "bytes (corrupt or a decompression bomb)",
                                  name, spec.width, spec.height, spec.nchannels, bytes >> 20, stored));
  }
  if (spec.depth > 1) {
    return make_error(ErrorCode::kUnsupported, fmt::format("{}: volume images (depth {}) are not supported", name,
                                                           spec.depth));
  }
  if (spec.nchannels < 1 || spec.nchannels > 4) {
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: image has {} channels; 1 to 4 are supported", name, spec.nchannels));
  }
  auto image = Image::create(spec.width, spec.height, spec.nchannels, format_from(spec.format));
  if (!image.ok()) return make_error(image.error().code, fmt::format("{}: {}", name, image.error().message));
  const bool read = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image->data().data());
  // The TIFF reader reports strips shorter than the header promises but still returns success,
  // with the missing rows zero-filled: a pending error fails the read as much as `false` does.
  std::string damage = in->geterror();
  if (!read || !damage.empty()) {
    if (damage.empty()) damage = oiio_error(nullptr);
    return make_error(ErrorCode::kCorrupt,
                      fmt::format("{}: truncated or corrupt image data ({})", name, first_line_and_count(damage)));
  }
  in->close();
  if (!options.allow_non_finite) {
    const NonFiniteReport bad = find_non_finite(*image);
    if (bad.count > 0) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: {} NaN/Inf values, the first at pixel ({}, {})", name, bad.count,
                                    bad.first_x, bad.first_y));
    }
  }
  return image;
}

Status write_image(const fs::path& path, const Image& image) { return write_image(path, image, image.format()); }

Status write_image_file(const fs::path& file, const Image& image, PixelFormat format, const fs::path& display) {
  const std::string name = display.string();
  if (image.empty()) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: refusing to write an empty image", name));
  }
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) {
    const std::string ext = display.extension().string();
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: no image format is known for the extension \"{}\" (use .png, .exr, .tif, .jpg)",
                                  name, ext));
  }
  OIIO::ImageSpec spec(image.width(), image.height(), image.channels(), type_from(format));
  spec.attribute("oiio:UnassociatedAlpha", 1);
  if (!out->open(file.string(), spec)) {
    // OpenImageIO names the temporary file it was given; the user knows only their own path.
    std::string why = out->geterror();
    for (auto at = why.find(file.string()); at != std::string::npos; at = why.find(file.string(), at + name.size())) {
      why.replace(at, file.string().size(), name);
    }
    return make_error(ErrorCode::kIo, fmt::format("{}: cannot create the file ({})", name, why));
  }
  const bool written = out->write_image(OIIO::TypeDesc::FLOAT, image.data().data());
  const bool closed = out->close();
  if (!written || !closed) {
    std::string why = out->geterror();
    std::error_code ec;
    fs::remove(file, ec);
    return make_error(ErrorCode::kIo, fmt::format("{}: write failed ({}); the old file is untouched", name, why));
  }
  return ok_status();
}

Status write_image(const fs::path& path, const Image& image, PixelFormat format) {
  SYLVA_TRY(check_replaceable(path));
  const fs::path temp = temp_path_beside(path);  // keeps the extension, so OIIO picks the plugin
  SYLVA_TRY(write_image_file(temp, image, format, path));
  return replace_with_temp(temp, path);
}

}  // namespace sylva
