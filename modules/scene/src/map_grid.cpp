#include <sylva/scene/map_grid.hpp>

#include <sylva/core/assert.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace sylva::scene {

TexelRect TexelRect::intersect(const TexelRect& o) const {
  TexelRect r{std::max(x0, o.x0), std::max(y0, o.y0), std::min(x1, o.x1), std::min(y1, o.y1)};
  if (r.empty()) return {};
  return r;
}

TexelRect TexelRect::unite(const TexelRect& o) const {
  if (empty()) return o;
  if (o.empty()) return *this;
  return {std::min(x0, o.x0), std::min(y0, o.y0), std::max(x1, o.x1), std::max(y1, o.y1)};
}

MapGrid::MapGrid(int w, int h, float fill, glm::dvec2 origin, glm::dvec2 size)
    : width(w), height(h), texel_origin(origin), texel_size(size) {
  SYLVA_ASSERT(w > 0 && h > 0, "map grid size {}x{}", w, h);
  SYLVA_ASSERT(size.x > 0.0 && size.y > 0.0, "map texel size {}x{}", size.x, size.y);
  values.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill);
}

std::vector<float> MapGrid::copy_rect(const TexelRect& rect) const {
  const TexelRect r = rect.intersect(bounds());
  std::vector<float> out;
  out.reserve(static_cast<std::size_t>(std::max(r.width(), 0)) * static_cast<std::size_t>(std::max(r.height(), 0)));
  for (int j = r.y0; j < r.y1; ++j) {
    for (int i = r.x0; i < r.x1; ++i) out.push_back(at(i, j));
  }
  return out;
}

void MapGrid::paste_rect(const TexelRect& rect, const std::vector<float>& data) {
  const TexelRect r = rect.intersect(bounds());
  SYLVA_ASSERT(data.size() == static_cast<std::size_t>(std::max(r.width(), 0)) * static_cast<std::size_t>(std::max(r.height(), 0)),
               "paste of {} values into a {}x{} rectangle", data.size(), r.width(), r.height());
  std::size_t k = 0;
  for (int j = r.y0; j < r.y1; ++j) {
    for (int i = r.x0; i < r.x1; ++i) at(i, j) = data[k++];
  }
}

WorldArea changed_world_area(const MapGrid& grid, const TexelRect& rect) {
  const glm::dvec2 a = grid.world(rect.x0 - 1.0, rect.y0 - 1.0);
  const glm::dvec2 b = grid.world(rect.x1, rect.y1);  // (x1 - 1) + 1 texel
  return {glm::min(a, b), glm::max(a, b)};
}

namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace

Result<MapGrid> read_map_image(const std::filesystem::path& file, float file_scale, float file_offset,
                               glm::dvec2 texel_origin, glm::dvec2 texel_size) {
  auto image = read_image(file, ImageReadOptions{.allow_non_finite = false});
  if (!image.ok()) return image.error();
  MapGrid grid(image->width(), image->height(), 0.0f, texel_origin, texel_size);
  for (int j = 0; j < grid.height; ++j) {
    for (int i = 0; i < grid.width; ++i) grid.at(i, j) = image->at(i, j, 0) * file_scale + file_offset;
  }
  return grid;
}

Image map_to_image(const MapGrid& grid, float file_scale, float file_offset, const std::filesystem::path& file) {
  const std::string ext = lower_extension(file);
  const bool float_file = ext == ".exr" || ext == ".tif" || ext == ".tiff" || ext == ".hdr";
  Image image(grid.width, grid.height, 1, float_file ? PixelFormat::kF32 : PixelFormat::kU16);
  const float inv = file_scale != 0.0f ? 1.0f / file_scale : 1.0f;
  for (int j = 0; j < grid.height; ++j) {
    for (int i = 0; i < grid.width; ++i) {
      // Identity units (the common case) copy the bits exactly.
      const float v = grid.at(i, j);
      image.at(i, j, 0) = (file_scale == 1.0f && file_offset == 0.0f) ? v : (v - file_offset) * inv;
    }
  }
  return image;
}

Status write_map_image(const std::filesystem::path& file, const MapGrid& grid, float file_scale, float file_offset) {
  if (grid.empty()) return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: the map is empty", file.string()));
  const Image image = map_to_image(grid, file_scale, file_offset, file);
  return write_image(file, image, image.format());
}

}  // namespace sylva::scene
