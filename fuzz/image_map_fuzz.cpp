// Image maps (height and density maps of a scene) through the project's own checks: core
// read_image (size limit before any pixel is read, decoding errors), the scene's map reader
// (NaN/Inf refused) and the terrain's height-field loader (NaN/Inf refused or repaired). The
// first input byte picks the file type (its low two bits) and the repair option (bit 2); the rest
// is the file, written to a temporary path with that extension because OpenImageIO picks its
// reader by name.
#include "support/fuzz_support.hpp"

#include <sylva/scene/map_grid.hpp>
#include <sylva/terrain/height_source.hpp>

#include <array>
#include <cmath>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static constexpr std::array<const char*, 4> kExtensions{".png", ".exr", ".tif", ".pgm"};
  const auto path = sylva::fuzz::write_temp_file({data + 1, size - 1}, kExtensions[data[0] & 3u]);
  auto grid = sylva::scene::read_map_image(path, 1.0f, 0.0f, {0.0, 0.0}, {1.0, 1.0});
  if (!grid.ok()) sylva::fuzz::require_message(grid.error());
  sylva::terrain::HeightImageSettings settings;
  settings.repair_non_finite = (data[0] & 4u) != 0;
  auto field = sylva::terrain::load_height_field(path, settings);
  if (!field.ok()) {
    sylva::fuzz::require_message(field.error());
    return 0;
  }
  for (float h : field->samples()) sylva::fuzz::require(std::isfinite(h), "a non-finite height passed the checks");
  return 0;
}
