#pragma once
// Where a terrain's height field comes from: an image file (through core's OpenImageIO reader)
// or a generated fBm / ridged fBm field (seed 002 §3.1: Perlin noise with -seed and -size; the
// thesis gives no octave parameters, so they are exposed here).

#include <sylva/core/height_field.hpp>
#include <sylva/core/noise.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

namespace sylva::terrain {

enum class FieldNoise : std::uint8_t { kFbm, kRidged };
constexpr std::array<EnumName<FieldNoise>, 2> enum_names(FieldNoise) {
  return {{{FieldNoise::kFbm, "fbm"}, {FieldNoise::kRidged, "ridged"}}};
}

struct GeneratedFieldSettings {
  int size = 513;                // samples per side (the seed's -size); non-square via rows
  int rows = 0;                  // 0 = size (square)
  double spacing = 1.0;          // metres per sample
  float height_scale = 200.0f;   // metres between the lowest and the highest possible value
  float height_offset = 0.0f;    // metres added
  float feature_size = 256.0f;   // metres per lattice cell of the first octave
  FieldNoise noise = FieldNoise::kFbm;
  FbmSettings fbm;               // octaves, persistence, lacunarity, seed (the seed's -seed)

  template <class V>
  void visit(V& v) {
    v(size, "size", {.min = 1, .max = 32768, .help = "Samples per side (x)", .rebuild = Rebuild::kOffline});
    v(rows, "rows", {.min = 0, .max = 32768, .help = "Samples along z (0 = square)", .rebuild = Rebuild::kOffline});
    v(spacing, "spacing", {.min = 1e-3, .max = 1e4, .unit = "m", .help = "Metres per sample",
      .rebuild = Rebuild::kOffline, .log_scale = true});
    v(height_scale, "height_scale", {.min = 0.0, .max = 1e5, .unit = "m", .help = "Height range",
      .rebuild = Rebuild::kOffline});
    v(height_offset, "height_offset", {.min = -1e5, .max = 1e5, .unit = "m", .rebuild = Rebuild::kOffline});
    v(feature_size, "feature_size", {.min = 1e-3, .max = 1e6, .unit = "m",
      .help = "Size of the largest noise features", .rebuild = Rebuild::kOffline, .log_scale = true});
    v(noise, "noise", {.help = "fbm or ridged", .rebuild = Rebuild::kOffline});
    v(fbm, "fbm");
  }
};

// Deterministic for the settings; rows in parallel. Errors: invalid settings (message names the
// parameter, prefixed "terrain.field.").
Result<HeightField> generate_height_field(const GeneratedFieldSettings& settings);

struct HeightImageSettings {
  double spacing = 1.0;          // metres per pixel
  double height_scale = 100.0;   // metres per normalised unit (16-bit 65535 -> 1.0)
  double height_offset = 0.0;
  bool repair_non_finite = false;  // replace NaN/Inf samples instead of refusing the file
  int channel = 0;

  template <class V>
  void visit(V& v) {
    v(spacing, "spacing", {.min = 1e-3, .max = 1e4, .unit = "m", .help = "Metres per pixel",
      .rebuild = Rebuild::kOffline, .log_scale = true});
    v(height_scale, "height_scale", {.min = 0.0, .max = 1e5, .unit = "m", .help = "Metres per normalised unit",
      .rebuild = Rebuild::kOffline});
    v(height_offset, "height_offset", {.min = -1e5, .max = 1e5, .unit = "m", .rebuild = Rebuild::kOffline});
    v(repair_non_finite, "repair_non_finite", {.help = "Replace NaN/Inf samples by their neighbours' mean",
      .rebuild = Rebuild::kOffline});
    v(channel, "channel", {.min = 0, .max = 3, .help = "Image channel holding the height", .rebuild = Rebuild::kOffline});
  }
};

// Any image core reads (16-bit PNG, float EXR/TIFF, ...). An 8-bit image loads with a warning
// about its 256 height levels. Errors name the file: missing, corrupt, too large, NaN/Inf samples
// (count and first pixel) unless repair_non_finite.
Result<HeightField> load_height_field(const std::filesystem::path& path, const HeightImageSettings& settings);

}  // namespace sylva::terrain
