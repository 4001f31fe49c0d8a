#pragma once
// Where a scene's ground comes from (GL-free): a painted/loaded height map, or a field generated
// from core noise. The ground-providing section ("terrain" or "ground") lists these fields; the
// scene turns them into the one sylva::HeightField that grass and trees stand on (DESIGN.md
// §2b: modules exchange the ground only through the core type).
//
// Placement: the field is centred on `center`, `size` metres along x; samples are square, so
// the z extent follows from the sample rows. Generated fields have `resolution` samples per
// side. A height map (the section's maps.height) gives the sample grid instead; its values are
// file units * map_scale + map_offset metres (1.0 = white of a 16-bit PNG).
//
// An elevation raster (`elevation.file`, relative to the scene file: GeoTIFF, SRTM .hgt, ASCII
// grid, ... through core read_elevation, whose header states the rules) gives the grid, its
// spacing and its heights in metres from the file's georeferencing; `elevation.spacing`,
// `height_scale` and `height_offset` override the file, and `size` applies only to a raster
// without georeferencing. The raster is centred on `center` like every other ground. A painted
// map (maps.height) wins over the raster: it holds the user's edits; the raster is never
// written to (edits are saved as a map beside the scene).

#include <sylva/core/elevation_raster.hpp>
#include <sylva/core/height_field.hpp>
#include <sylva/core/noise.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>
#include <sylva/scene/map_grid.hpp>

#include <glm/glm.hpp>

#include <array>
#include <filesystem>
#include <optional>
#include <string>

namespace sylva::scene {

// kValley: a landscape for a vista: gently rolling meadows within about 12 % of the half size
// from `center`, rising into ridged mountains (full height beyond 55 %), so a camera near the
// centre stands in a meadow with mountains on the horizon (the embedded default scene).
enum class HeightGenerator { kFlat, kFbm, kRidged, kHillsAndRidges, kValley };
constexpr std::array<EnumName<HeightGenerator>, 5> enum_names(HeightGenerator) {
  return {{{HeightGenerator::kFlat, "flat"},
           {HeightGenerator::kFbm, "fbm"},
           {HeightGenerator::kRidged, "ridged"},
           {HeightGenerator::kHillsAndRidges, "hills_and_ridges"},
           {HeightGenerator::kValley, "valley"}}};
}

// A channel of an image (the seed-001 control texture's layout is R density, G blade height,
// B terrain height).
enum class ImageChannel { kRed, kGreen, kBlue, kAlpha };
constexpr std::array<EnumName<ImageChannel>, 4> enum_names(ImageChannel) {
  return {{{ImageChannel::kRed, "r"}, {ImageChannel::kGreen, "g"}, {ImageChannel::kBlue, "b"}, {ImageChannel::kAlpha, "a"}}};
}

// Heights from one channel of an image, as seed 001 §3.2 takes its terrain from the blue channel
// of its RGB control texture, inverted (y = max_height * (1 - B), dark = high): "ground.control.
// file" names the image (relative to the scene; the same file `grass.maps.control` may name),
// `channel` and `inverted` say how to read it, and map_scale / map_offset give metres (the seed's
// maxTerrainHeight is map_scale). The file is only read: painted heights are saved as the
// section's own height map beside the scene, which then wins (precedence: maps.height, control,
// elevation raster, generator).
struct HeightControlSource {
  std::string file;                            // "" = none
  ImageChannel channel = ImageChannel::kBlue;  // seed 001 §3.3
  bool inverted = true;                        // seed 001 §3.2: dark = high

  template <class V>
  void visit(V& v) {
    v(file, "file", {.max = 4096.0, .help = "Image whose channel gives the heights (seed 001 control texture), relative to the scene file",
                     .rebuild = Rebuild::kOffline});
    v(channel, "channel", {.help = "Channel of control.file that holds the heights: r, g, b or a (seed 001: b)", .rebuild = Rebuild::kOffline});
    v(inverted, "inverted", {.help = "Height = map_scale * (1 - value) + map_offset (seed 001: dark = high)", .rebuild = Rebuild::kOffline});
  }
};

// The elevation raster of a ground and how to read it ("terrain.elevation.file", ...).
struct ElevationSource {
  std::string file;           // relative to the scene file; "" = none
  ElevationReadOptions read;  // spacing, height_scale, height_offset, nodata (flat in the JSON)

  template <class V>
  void visit(V& v) {
    v(file, "file", {.max = 4096.0, .help = "Elevation raster (GeoTIFF, SRTM .hgt, ASCII grid, ...) relative to the scene file",
                     .rebuild = Rebuild::kOffline});
    read.visit(v);
  }
};

struct HeightSourceSettings {
  glm::dvec2 center{0.0, 0.0};  // world x/z of the field's centre [m]
  float size = 4000.0f;         // x extent [m]
  int resolution = 257;         // samples per side of a generated field
  float height = 220.0f;        // vertical scale of the generator [m]
  HeightGenerator generator = HeightGenerator::kHillsAndRidges;
  FbmSettings noise{.octaves = 7, .persistence = 0.48f, .lacunarity = 2.0f, .frequency = 1.0f / 700.0f,
                    .seed = 7, .ridge_gain = 2.0f};
  float map_scale = 1.0f;       // metres per file unit of a height map
  float map_offset = 0.0f;      // metres added to a height map
  ElevationSource elevation;    // an elevation raster instead of a generated field
  HeightControlSource control;  // one channel of an image (seed 001's control texture)

  template <class V>
  void visit(V& v) {
    v(center, "center", {.min = -1.0e8, .max = 1.0e8, .unit = "m", .help = "World x/z of the ground's centre", .rebuild = Rebuild::kOffline});
    v(size, "size", {.min = 1.0, .max = 1.0e6, .unit = "m", .help = "Side length of the ground along x", .rebuild = Rebuild::kOffline, .log_scale = true});
    v(resolution, "resolution", {.min = 2, .max = 8193, .help = "Samples per side of a generated ground", .rebuild = Rebuild::kOffline});
    v(height, "height", {.min = 0.0, .max = 1.0e4, .unit = "m", .help = "Height scale of the generator", .rebuild = Rebuild::kOffline});
    v(generator, "generator", {.help = "flat, fbm, ridged, hills_and_ridges or valley (used when there is no height map)", .rebuild = Rebuild::kOffline});
    v(noise, "noise");
    v(map_scale, "map_scale", {.min = -1.0e5, .max = 1.0e5, .unit = "m", .help = "Metres per unit of the height map file", .rebuild = Rebuild::kOffline});
    v(map_offset, "map_offset", {.min = -1.0e6, .max = 1.0e6, .unit = "m", .help = "Metres added to the height map", .rebuild = Rebuild::kOffline});
    v(elevation, "elevation");
    v(control, "control");
  }
};

// The height map grid: read from `map_file` when given, else from `control_file` (the resolved
// control.file), else from `elevation_file` (the resolved elevation.file), else generated.
// Errors name the file. Heights in metres; texel centres are the height samples.
Result<MapGrid> make_height_grid(const HeightSourceSettings& settings, const std::optional<std::filesystem::path>& map_file,
                                 const std::optional<std::filesystem::path>& elevation_file = std::nullopt,
                                 const std::optional<std::filesystem::path>& control_file = std::nullopt);

// Sample spacing and origin for a grid of `columns` samples along x.
double height_spacing(const HeightSourceSettings& settings, int columns);
// Square samples `spacing` metres apart, centred on settings.center.
void place_height_grid(MapGrid& grid, const HeightSourceSettings& settings, double spacing);

// A HeightField with the grid's samples and placement (texel size must be square, asserted).
HeightField height_field_from_grid(const MapGrid& grid);
// Copies the samples of `rect` from the grid into the field (same dimensions, asserted) and
// refreshes its height range.
void update_height_field(HeightField& field, const MapGrid& grid, const TexelRect& rect);

}  // namespace sylva::scene
