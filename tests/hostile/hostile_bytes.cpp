#include "hostile_bytes.hpp"

#include <sylva/core/atomic_file.hpp>
#include <sylva/core/image.hpp>

#include <zlib.h>

#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace sylva::hostile {
namespace {

void put_be32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>((v >> shift) & 0xffu));
}
void put_le(std::string& out, std::uint32_t v, int bytes) {
  for (int k = 0; k < bytes; ++k) out.push_back(static_cast<char>((v >> (8 * k)) & 0xffu));
}

// One PNG chunk: length, type, data, CRC over type + data (valid, so only the claim lies).
void png_chunk(std::string& out, const char* type, const std::string& data) {
  put_be32(out, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out += body;
  put_be32(out, static_cast<std::uint32_t>(
                    ::crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size()))));
}

std::string png_ihdr(std::uint32_t width, std::uint32_t height, int bit_depth, int color_type) {
  std::string ihdr;
  put_be32(ihdr, width);
  put_be32(ihdr, height);
  ihdr += {static_cast<char>(bit_depth), static_cast<char>(color_type), 0, 0, 0};
  return ihdr;
}

const char kPngSignature[] = "\x89PNG\r\n\x1a\n";

// zlib stream of `rows` (each prefixed with filter byte 0), fed one row at a time.
std::string deflate_rows(std::uint32_t height, const std::function<std::string(std::uint32_t)>& row) {
  z_stream z{};
  if (deflateInit(&z, 1) != Z_OK) throw std::runtime_error("deflateInit failed");
  std::string out;
  std::string in;
  char buffer[1 << 16];
  for (std::uint32_t y = 0; y <= height; ++y) {
    const bool last = y == height;
    in = last ? std::string() : '\0' + row(y);
    z.next_in = reinterpret_cast<Bytef*>(in.data());
    z.avail_in = static_cast<uInt>(in.size());
    do {
      z.next_out = reinterpret_cast<Bytef*>(buffer);
      z.avail_out = sizeof buffer;
      deflate(&z, last ? Z_FINISH : Z_NO_FLUSH);
      out.append(buffer, sizeof buffer - z.avail_out);
    } while (z.avail_out == 0);
  }
  deflateEnd(&z);
  return out;
}

}  // namespace

std::string png_gray8(std::uint32_t width, std::uint32_t height, const std::function<std::string(std::uint32_t)>& row) {
  std::string out(kPngSignature, 8);
  png_chunk(out, "IHDR", png_ihdr(width, height, 8, 0));
  png_chunk(out, "IDAT", deflate_rows(height, row));
  png_chunk(out, "IEND", "");
  return out;
}

std::string png_solid(std::uint32_t width, std::uint32_t height, int channels, const std::string& value) {
  static constexpr int kColorType[] = {0, 0, 4, 2, 6};  // PNG colour type by channel count
  std::string pixel = value.substr(0, static_cast<std::size_t>(channels));
  pixel.resize(static_cast<std::size_t>(channels), '\xff');
  std::string row;
  for (std::uint32_t x = 0; x < width; ++x) row += pixel;
  std::string out(kPngSignature, 8);
  png_chunk(out, "IHDR", png_ihdr(width, height, 8, kColorType[channels]));
  png_chunk(out, "IDAT", deflate_rows(height, [&row](std::uint32_t) { return row; }));
  png_chunk(out, "IEND", "");
  return out;
}

std::string png_lying_header(std::uint32_t width, std::uint32_t height, int bit_depth, int color_type) {
  std::string out(kPngSignature, 8);
  png_chunk(out, "IHDR", png_ihdr(width, height, bit_depth, color_type));
  // Two rows' worth of zeros at most: far fewer than the header promises.
  png_chunk(out, "IDAT", deflate_rows(2, [](std::uint32_t) { return std::string(64, '\0'); }));
  png_chunk(out, "IEND", "");
  return out;
}

std::string pgm(const std::string& width, const std::string& height, const std::string& maxval, const std::string& pixels) {
  return "P5\n" + width + " " + height + "\n" + maxval + "\n" + pixels;
}

std::string pfm(int width, int height, const std::vector<float>& values) {
  std::string out = "Pf\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";  // < 0: little-endian
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
  return out;
}

std::string tiff_lying_header(std::uint32_t width, std::uint32_t height, std::uint32_t strip_bytes) {
  // Header (8 bytes), then one directory of 8 entries at offset 8, then the strip.
  constexpr std::uint32_t kEntries = 8;
  const std::uint32_t strip_offset = 8 + 2 + kEntries * 12 + 4;
  std::string out = "II*";
  out.push_back('\0');
  put_le(out, 8, 4);
  put_le(out, kEntries, 2);
  auto entry = [&out](std::uint32_t tag, std::uint32_t type, std::uint32_t value) {
    put_le(out, tag, 2);
    put_le(out, type, 2);
    put_le(out, 1, 4);  // one value, stored in the entry
    put_le(out, value, 4);
  };
  constexpr std::uint32_t kShort = 3, kLong = 4;
  entry(256, kLong, width);         // ImageWidth
  entry(257, kLong, height);        // ImageLength
  entry(258, kShort, 8);            // BitsPerSample
  entry(259, kShort, 1);            // Compression: none
  entry(262, kShort, 1);            // Photometric: black is zero
  entry(273, kLong, strip_offset);  // StripOffsets
  entry(278, kLong, height);        // RowsPerStrip: one strip
  entry(279, kLong, strip_bytes);   // StripByteCounts
  put_le(out, 0, 4);                // no next directory
  out.append(strip_bytes, '\x40');
  return out;
}

std::string float_image(const std::string& extension, int width, int height, const std::vector<float>& values) {
  Image image(width, height, 1, PixelFormat::kF32);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) image.at(x, y) = values[static_cast<std::size_t>(y * width + x)];
  const auto scratch = std::filesystem::temp_directory_path() /
                       ("sylva_hostile_float_" + std::to_string(::getpid()) + extension);
  if (!write_image(scratch, image, PixelFormat::kF32).ok()) throw std::runtime_error("cannot write " + scratch.string());
  auto bytes = read_file(scratch);
  std::filesystem::remove(scratch);
  if (!bytes.ok()) throw std::runtime_error(bytes.error().message);
  return *bytes;
}

std::string truncated(const std::string& bytes, std::size_t keep) {
  return bytes.substr(0, keep < bytes.size() ? keep : bytes.size() / 2);
}

std::string junk(std::size_t count, std::uint32_t seed) {
  std::string out(count, '\0');
  std::uint32_t x = seed * 2654435761u + 1u;
  for (char& c : out) {
    x ^= x << 13;  // xorshift32
    x ^= x >> 17;
    x ^= x << 5;
    c = static_cast<char>(x & 0xffu);
  }
  return out;
}

std::string nested_json(std::size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

}  // namespace sylva::hostile
