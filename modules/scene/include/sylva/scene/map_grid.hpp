#pragma once
// Editable maps of a scene (GL-free): terrain height, grass density and height, tree density.
//
// A MapGrid is a one-channel float grid laid over the world x/z plane. Texel (i, j) has its
// centre at texel_origin + (i, j) * texel_size; i runs along world +x, j along world +z, and
// row j is picture row j of the map file (row 0 at the top of the picture): the orientation of
// sylva::HeightField::from_image and of grass maps, so maps painted over one another line up.
// For a height field the texel centres are the height samples; for a density map over a
// rectangle they are the centres of its equal cells.
//
// Files: the extension picks the format. .exr/.tif/.tiff keep 32-bit floats (lossless);
// .png is 16-bit (65536 levels of [0, 1], clamped). A height map's values are metres; in a file
// they are (metres - file_offset) / file_scale, so a 16-bit PNG of height_scale 300 m keeps
// 4.6 mm steps. Loading and saving go through core images (atomic writes).

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>
#include <sylva/scene/module_settings.hpp>

#include <glm/glm.hpp>

#include <filesystem>
#include <string>
#include <vector>

namespace sylva::scene {

// Half-open texel rectangle [x0, x1) x [y0, y1).
struct TexelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  TexelRect intersect(const TexelRect& o) const;
  // Smallest rectangle holding both (an empty operand is ignored).
  TexelRect unite(const TexelRect& o) const;
  bool operator==(const TexelRect&) const = default;
};

struct MapGrid {
  int width = 0;
  int height = 0;
  std::vector<float> values;      // row-major, width * height
  glm::dvec2 texel_origin{0.0};   // world x/z of texel (0, 0)'s centre [m]
  glm::dvec2 texel_size{1.0};     // world metres between texel centres (> 0)

  MapGrid() = default;
  MapGrid(int w, int h, float fill, glm::dvec2 origin, glm::dvec2 size);

  bool empty() const { return values.empty(); }
  TexelRect bounds() const { return {0, 0, width, height}; }
  float at(int i, int j) const { return values[index(i, j)]; }
  float& at(int i, int j) { return values[index(i, j)]; }
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(width) + static_cast<std::size_t>(i);
  }
  // World x/z of texel (i, j)'s centre.
  glm::dvec2 world(double i, double j) const { return texel_origin + glm::dvec2(i, j) * texel_size; }
  // Continuous texel coordinates of a world point (inverse of world()).
  glm::dvec2 texel(const glm::dvec2& world_xz) const { return (world_xz - texel_origin) / texel_size; }

  // The values of `rect` (clipped to the grid), row by row.
  std::vector<float> copy_rect(const TexelRect& rect) const;
  // Writes values previously taken by copy_rect(rect) back (bit-exact).
  void paste_rect(const TexelRect& rect, const std::vector<float>& data);
};

// Where a changed texel rectangle shows in the world: the texel centres it spans, grown by one
// texel on each side (bilinear interpolation and normals reach one texel further), in metres.
struct WorldArea {
  glm::dvec2 min{0.0};
  glm::dvec2 max{0.0};
};
WorldArea changed_world_area(const MapGrid& grid, const TexelRect& rect);

// One map of a scene: which module and slot it belongs to, its values and its file.
struct SceneMap {
  std::string module;        // "grass"
  std::string slot;          // "density"
  MapKind kind = MapKind::kUnit;
  MapGrid grid;
  std::string path;          // as written in the scene file (relative to it); "" = the module's
                             // default (generated) map, written only once it is edited
  float file_scale = 1.0f;   // file value = (value - file_offset) / file_scale
  float file_offset = 0.0f;
  std::uint64_t revision = 0;        // bumped by every edit
  std::uint64_t saved_revision = 0;  // revision when last loaded or saved

  std::string id() const { return module + "." + slot; }
  bool unsaved() const { return revision != saved_revision; }
};

// Reads channel 0 of an image file into a grid with the given placement (values converted from
// file units). Errors name the file (missing, unreadable, non-finite samples).
Result<MapGrid> read_map_image(const std::filesystem::path& file, float file_scale, float file_offset,
                               glm::dvec2 texel_origin, glm::dvec2 texel_size);
// The grid in file units as a one-channel image in the format the extension calls for.
Image map_to_image(const MapGrid& grid, float file_scale, float file_offset, const std::filesystem::path& file);
// Writes atomically; errors name the file.
Status write_map_image(const std::filesystem::path& file, const MapGrid& grid, float file_scale, float file_offset);

}  // namespace sylva::scene
