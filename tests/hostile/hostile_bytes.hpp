#pragma once
// Generators of hostile file contents for tests/hostile: every byte string is built at test
// time (nothing binary is checked in), deterministic, and small unless a case is about size.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace sylva::hostile {

// A PNG whose IHDR says `width` x `height` (8-bit grey) and whose image data holds the rows
// `row(y)` returns (each `width` bytes, without the filter byte). Rows are compressed as they
// come, so a 16384^2 picture costs a row of memory, not the picture.
std::string png_gray8(std::uint32_t width, std::uint32_t height, const std::function<std::string(std::uint32_t)>& row);
// A PNG of one colour: `channels` (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA) 8-bit samples `value`
// (its first `channels` bytes) in every pixel.
std::string png_solid(std::uint32_t width, std::uint32_t height, int channels, const std::string& value);
// A PNG that claims `width` x `height` but carries a few bytes of image data: the lying header.
std::string png_lying_header(std::uint32_t width, std::uint32_t height, int bit_depth = 8, int color_type = 0);

// Netpbm: "P5" with the given header fields, then `pixels` (raw bytes, possibly too few).
std::string pgm(const std::string& width, const std::string& height, const std::string& maxval, const std::string& pixels);
// Portable float map (grey, little-endian) holding `values` row by row.
std::string pfm(int width, int height, const std::vector<float>& values);
// A little-endian TIFF whose first directory claims `width` x `height` 8-bit grey pixels in one
// strip of `strip_bytes` bytes that follow (so the file is far too short for the claim).
std::string tiff_lying_header(std::uint32_t width, std::uint32_t height, std::uint32_t strip_bytes = 16);
// A float image written through OpenImageIO to a format picked by `extension` (".exr",
// ".tif"), read back as bytes: for files whose values (NaN, Inf) are the hostile part.
std::string float_image(const std::string& extension, int width, int height, const std::vector<float>& values);

// `bytes` cut to its first `keep` bytes (or to half when keep is larger than the input).
std::string truncated(const std::string& bytes, std::size_t keep);
// `count` pseudo-random bytes (fixed seed: the same junk every run).
std::string junk(std::size_t count, std::uint32_t seed = 1);
// `depth` nested JSON arrays: "[[[...]]]".
std::string nested_json(std::size_t depth);

}  // namespace sylva::hostile
