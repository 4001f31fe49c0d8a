// OpenEXR header walk (file layout: OpenEXR "File Layout" document, section "Header"): magic,
// version with flags, then per part a list of attributes (name\0 type\0 int32 size, value) closed
// by an empty name; a multi-part file closes its list of headers with one more empty header.
#include "exr_header_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

namespace sylva::detail {
namespace {

namespace fs = std::filesystem;

constexpr std::array<unsigned char, 4> kMagic{0x76, 0x2f, 0x31, 0x01};
constexpr std::uint32_t kLongNamesFlag = 0x400, kMultiPartFlag = 0x1000;
constexpr int kMaxParts = 1024;            // far above any real file; bounds the walk
constexpr int kMaxAttributesPerPart = 4096;

std::int64_t little_endian(const unsigned char* p, int bytes) {
  std::uint64_t v = 0;
  for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | p[i];
  if (bytes == 4) return static_cast<std::int32_t>(static_cast<std::uint32_t>(v));
  return static_cast<std::int64_t>(v);
}

// Reads a NUL-terminated string of at most `max_length` characters; false at the end of the
// file or when no NUL comes in time.
bool read_name(std::ifstream& in, std::size_t max_length, std::string& out) {
  out.clear();
  for (char c; in.get(c);) {
    if (c == '\0') return true;
    if (out.size() == max_length) return false;
    out.push_back(c);
  }
  return false;
}

// OpenEXR reads a value of a known fixed-size type with that type's own reader and ignores the
// declared size, so a declared size that differs would make the library read the rest of the
// header out of step with this walk: such a file is refused. Types read by the declared size
// (string, vectors, opaque ones) need nothing here; "chlist" and "preview" are checked apart.
int fixed_value_size(const std::string& type) {
  static const struct {
    const char* type;
    int bytes;
  } kFixed[] = {{"box2i", 16},  {"box2f", 16},   {"compression", 1}, {"lineOrder", 1}, {"envmap", 1},
                {"deepImageState", 1}, {"int", 4}, {"float", 4},  {"double", 8},  {"v2i", 8},
                {"v2f", 8},     {"v2d", 16},     {"v3i", 12},        {"v3f", 12},      {"v3d", 24},
                {"m33f", 36},   {"m33d", 72},    {"m44f", 64},       {"m44d", 128},    {"rational", 8},
                {"tiledesc", 9}, {"timecode", 8}, {"keycode", 28},   {"chromaticities", 32}};
  for (const auto& f : kFixed) {
    if (type == f.type) return f.bytes;
  }
  return -1;
}

// Bytes a channel list occupies as OpenEXR reads it (per channel: name, 16 bytes of type,
// linearity and sampling; an empty name ends it, and the library reads up to that end whatever
// size the header declared); -1 when the list does not end within `limit` bytes.
std::int64_t channel_list_bytes(std::ifstream& in, std::int64_t limit) {
  const std::streampos start = in.tellg();
  std::string channel;
  std::int64_t used = 0;
  std::int64_t result = -1;
  while (read_name(in, 255, channel)) {
    used += static_cast<std::int64_t>(channel.size()) + 1;
    if (used > limit) break;
    if (channel.empty()) {
      result = used;
      break;
    }
    used += 16;
    if (used > limit) break;
    in.seekg(16, std::ios::cur);
  }
  in.clear();
  in.seekg(start);
  return result;
}

// What one part's header says about the size of its offset table.
struct PartShape {
  std::int64_t width = 0, height = 0;  // data window; 0 = not seen
  std::int64_t tile_x = 0, tile_y = 0; // tiles attribute; 0 = scan lines
  std::int64_t chunk_count = -1;       // chunkCount attribute (multi-part); -1 = not given
};

}  // namespace

Status check_exr_header(const fs::path& path, std::string_view display, int max_side) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 8> start{};
  const bool whole_start = static_cast<bool>(in.read(reinterpret_cast<char*>(start.data()), start.size()));
  if (in.gcount() < 4 || !std::equal(kMagic.begin(), kMagic.end(), start.begin())) return {};  // not an EXR
  std::error_code ec;
  const auto file_size = static_cast<std::int64_t>(fs::file_size(path, ec));
  if (ec) return make_error(ErrorCode::kNotFound, fmt::format("{}: cannot read ({})", display, ec.message()));
  if (!whole_start) {
    return make_error(ErrorCode::kCorrupt, fmt::format("{}: truncated OpenEXR file ({} bytes)", display, file_size));
  }
  const auto flags = static_cast<std::uint32_t>(little_endian(start.data() + 4, 4));
  const std::size_t max_name = (flags & kLongNamesFlag) != 0 ? 255 : 31;
  const bool multi_part = (flags & kMultiPartFlag) != 0;

  std::string name, type;
  for (int part = 0; part < kMaxParts; ++part) {
    PartShape shape;
    int attributes = 0;
    for (;; ++attributes) {
      if (attributes == kMaxAttributesPerPart) {
        return make_error(ErrorCode::kLimit, fmt::format("{}: OpenEXR header of part {} has more than {} attributes",
                                                         display, part, kMaxAttributesPerPart));
      }
      if (!read_name(in, max_name, name)) {
        return make_error(ErrorCode::kCorrupt,
                          fmt::format("{}: OpenEXR header of part {} ends early or holds a name longer than {} characters",
                                      display, part, max_name));
      }
      if (name.empty()) break;  // end of this header
      std::array<unsigned char, 4> size_bytes{};
      if (!read_name(in, max_name, type) || !in.read(reinterpret_cast<char*>(size_bytes.data()), 4)) {
        return make_error(ErrorCode::kCorrupt, fmt::format("{}: OpenEXR attribute \"{}\" is cut off", display, name));
      }
      const std::int64_t size = little_endian(size_bytes.data(), 4);
      const std::int64_t left = file_size - static_cast<std::int64_t>(in.tellg());
      if (size < 0 || size > left) {
        return make_error(ErrorCode::kCorrupt,
                          fmt::format("{}: OpenEXR attribute \"{}\" declares {} bytes but the file has {} left", display,
                                      name, size, left));
      }
      const int fixed = fixed_value_size(type);
      if (fixed >= 0 && size != fixed) {
        return make_error(ErrorCode::kCorrupt, fmt::format("{}: OpenEXR attribute \"{}\" of type {} declares {} bytes "
                                                           "instead of {}",
                                                           display, name, type, size, fixed));
      }
      if (type == "chlist" && channel_list_bytes(in, size) != size) {
        return make_error(ErrorCode::kCorrupt,
                          fmt::format("{}: OpenEXR channel list \"{}\" does not fill its {} bytes", display, name, size));
      }
      if (type == "preview") {
        // Width and height, then 4 bytes per pixel: the library allocates width * height * 4.
        std::array<unsigned char, 8> dims{};
        if (size < 8 || !in.read(reinterpret_cast<char*>(dims.data()), 8)) {
          return make_error(ErrorCode::kCorrupt, fmt::format("{}: OpenEXR preview \"{}\" is cut off", display, name));
        }
        in.seekg(-8, std::ios::cur);
        const auto w = static_cast<std::uint64_t>(static_cast<std::uint32_t>(little_endian(dims.data(), 4)));
        const auto h = static_cast<std::uint64_t>(static_cast<std::uint32_t>(little_endian(dims.data() + 4, 4)));
        if (8 + 4 * w * h != static_cast<std::uint64_t>(size)) {
          return make_error(ErrorCode::kCorrupt, fmt::format("{}: OpenEXR preview \"{}\" of {}x{} does not fill its {} "
                                                             "bytes",
                                                             display, name, w, h, size));
        }
      }
      // The few values that size the offset table; everything else is skipped unread.
      std::array<unsigned char, 16> value{};
      const bool wanted = (name == "dataWindow" && type == "box2i" && size == 16) ||
                          (name == "tiles" && type == "tiledesc" && size == 9) ||
                          (name == "chunkCount" && type == "int" && size == 4);
      if (wanted) {
        if (!in.read(reinterpret_cast<char*>(value.data()), size)) {
          return make_error(ErrorCode::kCorrupt, fmt::format("{}: OpenEXR attribute \"{}\" is cut off", display, name));
        }
        if (name == "dataWindow") {
          shape.width = little_endian(value.data() + 8, 4) - little_endian(value.data(), 4) + 1;
          shape.height = little_endian(value.data() + 12, 4) - little_endian(value.data() + 4, 4) + 1;
        } else if (name == "tiles") {
          shape.tile_x = static_cast<std::uint32_t>(little_endian(value.data(), 4));
          shape.tile_y = static_cast<std::uint32_t>(little_endian(value.data() + 4, 4));
        } else {
          shape.chunk_count = little_endian(value.data(), 4);
        }
      } else {
        in.seekg(size, std::ios::cur);
      }
    }
    if (attributes == 0) {
      if (multi_part && part > 0) return {};  // the empty header closing a multi-part list
      return make_error(ErrorCode::kCorrupt, fmt::format("{}: OpenEXR header of part {} is empty", display, part));
    }
    if (shape.width > max_side || shape.height > max_side || shape.width < 0 || shape.height < 0) {
      return make_error(ErrorCode::kLimit,
                        fmt::format("{}: image is {}x{}, larger than the limit of {} per side (OpenEXR data window)",
                                    display, shape.width, shape.height, max_side));
    }
    // The offset table holds 8 bytes per chunk and lies in the file. At least: one chunk per 256
    // scan lines (the largest block, DWAB), or one per level-0 tile.
    std::int64_t min_chunks = (shape.height + 255) / 256;
    if (shape.tile_x > 0 && shape.tile_y > 0) {
      min_chunks = ((shape.width + shape.tile_x - 1) / shape.tile_x) * ((shape.height + shape.tile_y - 1) / shape.tile_y);
    }
    if (shape.chunk_count >= 0) min_chunks = std::max(min_chunks, shape.chunk_count);
    if (min_chunks * 8 > file_size) {
      return make_error(ErrorCode::kCorrupt,
                        fmt::format("{}: OpenEXR part {} needs {} chunks but the file has only {} bytes", display, part,
                                    min_chunks, file_size));
    }
    if (!multi_part) return {};
  }
  return make_error(ErrorCode::kLimit, fmt::format("{}: OpenEXR file has more than {} parts", display, kMaxParts));
}

}  // namespace sylva::detail
