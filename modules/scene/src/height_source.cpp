#include <sylva/scene/height_source.hpp>

#include "baked_edits.hpp"
#include "baked_ground.hpp"

#include <sylva/core/assert.hpp>
#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>

#include <fmt/format.h>

#include <algorithm>

namespace sylva::scene {

double height_spacing(const HeightSourceSettings& settings, int columns) {
  return static_cast<double>(settings.size) / std::max(columns - 1, 1);
}

void place_height_grid(MapGrid& grid, const HeightSourceSettings& s, double spacing) {
  grid.texel_size = {spacing, spacing};
  grid.texel_origin = s.center - 0.5 * glm::dvec2(grid.width - 1, grid.height - 1) * spacing;
}

namespace {

Result<MapGrid> read_elevation_grid(const HeightSourceSettings& s, const std::filesystem::path& file) {
  ElevationReadOptions options = s.elevation.read;
  options.plain_extent = s.size;
  auto raster = read_elevation(file, options);
  if (!raster.ok()) return raster.error();
  HeightField& field = raster->field;
  MapGrid grid;
  grid.width = field.columns();
  grid.height = field.rows();
  grid.values = std::move(field.samples());
  place_height_grid(grid, s, field.spacing());
  log_info("{}: {}x{} samples {:.3f} m apart ({:.0f} x {:.0f} m), heights {:.2f} to {:.2f} m, read by {}{}",
           file.string(), grid.width, grid.height, field.spacing(), field.extent().x, field.extent().y,
           field.min_height(), field.max_height(), raster->reader, raster->crs.empty() ? "" : " in " + raster->crs);
  return grid;
}

// Seed 001 §3.2: the terrain from one channel of the control texture, y = scale * (1 - B) + offset.
Result<MapGrid> read_control_grid(const HeightSourceSettings& s, const std::filesystem::path& file) {
  auto image = read_image(file, ImageReadOptions{.allow_non_finite = false});
  if (!image.ok()) return image.error();
  const int channel = static_cast<int>(s.control.channel);
  if (image->channels() <= channel) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: control.channel \"{}\" needs {} channel(s), the image has {}", file.string(),
                                  "rgba"[channel], channel + 1, image->channels()));
  }
  if (image->width() < 2 || image->height() < 2) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: a height map needs at least 2x2 samples, got {}x{}",
                                                               file.string(), image->width(), image->height()));
  }
  MapGrid grid(image->width(), image->height(), 0.0f, {0.0, 0.0}, {1.0, 1.0});
  for (int j = 0; j < grid.height; ++j) {
    for (int i = 0; i < grid.width; ++i) {
      const float v = image->at(i, j, channel);
      grid.at(i, j) = (s.control.inverted ? 1.0f - v : v) * s.map_scale + s.map_offset;
    }
  }
  place_height_grid(grid, s, height_spacing(s, grid.width));
  return grid;
}

}  // namespace

Result<MapGrid> make_height_grid(const HeightSourceSettings& s, const std::optional<std::filesystem::path>& map_file,
                                 const std::optional<std::filesystem::path>& elevation_file,
                                 const std::optional<std::filesystem::path>& control_file) {
  const std::optional<std::filesystem::path>& source_file = control_file ? control_file : elevation_file;
  if (map_file && source_file && !is_edit_layer_file(*map_file)) {
    log_info("{}: the painted height map is used; {} is not read", map_file->string(), source_file->string());
  } else if (control_file && elevation_file) {
    log_info("{}: the control texture's heights are used; the elevation raster {} is not read", control_file->string(),
             elevation_file->string());
  }
  if (elevation_file && (is_chunk_file(*elevation_file) || elevation_file->extension() == ".sylvaterrain")) {
    // terrain.baked_file (terrain_module.cpp names it as the elevation source): the ground the
    // chunks were baked from wins over every other height key.
    auto grid = read_baked_ground(*elevation_file);
    if (!grid.ok()) return make_error(grid.error().code, grid.error().message + " (the ground of terrain.baked_file)");
    // Its painted heights: the scene's edit layer (baked_edits.hpp); a bad layer is a warning.
    if (map_file && is_edit_layer_file(*map_file)) apply_edit_layer_file(*grid, *map_file);
    return grid;
  }
  if (!map_file && control_file) return read_control_grid(s, *control_file);
  if (!map_file && elevation_file) return read_elevation_grid(s, *elevation_file);
  if (map_file) {
    // Placement needs the sample count, known only after reading: read with a unit placement,
    // then place.
    auto grid = read_map_image(*map_file, s.map_scale, s.map_offset, {0.0, 0.0}, {1.0, 1.0});
    if (!grid.ok()) return grid.error();
    if (grid->width < 2 || grid->height < 2) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("{}: a height map needs at least 2x2 samples, got {}x{}", map_file->string(),
                                    grid->width, grid->height));
    }
    place_height_grid(*grid, s, height_spacing(s, grid->width));
    return grid;
  }
  const int n = s.resolution;
  const double spacing = height_spacing(s, n);
  const glm::dvec2 origin = s.center - 0.5 * glm::dvec2(n - 1) * spacing;
  MapGrid grid(n, n, 0.0f, origin, {spacing, spacing});
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const glm::dvec2 p = grid.world(i, j);
      float h = 0.0f;
      switch (s.generator) {
        case HeightGenerator::kFlat:
          h = 0.0f;
          break;
        case HeightGenerator::kFbm:
          h = s.height * fbm2(p, s.noise);
          break;
        case HeightGenerator::kRidged:
          h = s.height * ridged2(p, s.noise);
          break;
        case HeightGenerator::kHillsAndRidges: {
          // Ridged mountains blended over rolling fBm hills (the player's first ground).
          const float hills = fbm2(p, s.noise);
          const float ridges = ridged2(p * 0.8, s.noise);
          h = s.height * (0.45f * hills + 0.75f * ridges * ridges);
          break;
        }
        case HeightGenerator::kValley: {
          // Same hills and ridges, scaled by the distance from the centre: a few metres of
          // rolling relief in the meadow, the full mountain relief toward the edges.
          const double r = glm::length(p - s.center) / std::max(0.5 * double(s.size), 1.0);
          const float w = static_cast<float>(glm::smoothstep(0.12, 0.55, r));
          const float hills = fbm2(p, s.noise);
          const float ridges = ridged2(p * 0.8, s.noise);
          // Swells of a few metres at four times the frequency keep the meadow from looking planed.
          const float swells = fbm2(p * 4.0, s.noise);
          h = s.height * ((0.05f + 0.4f * w) * hills + w * 0.9f * ridges * ridges + 0.015f * swells);
          break;
        }
      }
      grid.at(i, j) = h;
    }
  }
  return grid;
}

HeightField height_field_from_grid(const MapGrid& grid) {
  SYLVA_ASSERT(grid.texel_size.x == grid.texel_size.y, "height samples must be square, got {} x {}", grid.texel_size.x,
               grid.texel_size.y);
  HeightField field(grid.width, grid.height, grid.texel_size.x, grid.texel_origin);
  field.samples() = grid.values;
  field.update_range();
  return field;
}

void update_height_field(HeightField& field, const MapGrid& grid, const TexelRect& rect) {
  SYLVA_ASSERT(field.columns() == grid.width && field.rows() == grid.height, "field {}x{} vs grid {}x{}",
               field.columns(), field.rows(), grid.width, grid.height);
  const TexelRect r = rect.intersect(grid.bounds());
  for (int j = r.y0; j < r.y1; ++j) {
    for (int i = r.x0; i < r.x1; ++i) field.sample(i, j) = grid.at(i, j);
  }
  field.update_range();
}

}  // namespace sylva::scene
