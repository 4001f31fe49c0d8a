#pragma once
// Elevation rasters as users have them (issue 15): GeoTIFF (tiled, compressed, BigTIFF; Int16,
// UInt16, Int32, Float32, Float64), SRTM .hgt, Esri ASCII grids and anything else GDAL opens,
// read into the core HeightField with the file's georeferencing applied. GL-free; the only
// place core touches GDAL (src/elevation_raster.cpp), as image_io.cpp is for OpenImageIO.
//
// Which reader (the rule, modules/terrain/README.md "Elevation data"):
//  - GDAL opens the file and reports a geotransform or a coordinate system: GDAL reads band 1
//    and the georeferencing gives the sample spacing and vertical unit.
//  - Otherwise (a PNG/EXR/TIFF without georeferencing, or a file GDAL does not open) the file
//    goes through OpenImageIO (read_image) as today's height maps: integer pixels normalised
//    (a 16-bit 65535 reads 1.0), spacing from `plain_extent`.
//  - Neither opens it: kUnsupported naming the file and both readers' reasons.
//
// Heights in metres = stored value * scale + offset, where scale/offset are
//  - `height_scale` and `height_offset` when height_scale != 0 (the scene wins over the file);
//  - else the band's scale/offset (GDAL metadata, usually 1/0) times its vertical unit
//    (metres; ft and US survey ft are converted; an empty unit is read as metres; any other unit
//    is kUnsupported until height_scale overrides it), plus height_offset.
// Spacing in metres = `spacing` when != 0; else the geotransform's pixel size: a projected
// coordinate system's linear unit converted to metres; a geographic one converted on its
// ellipsoid at the raster's centre latitude (logged, with the east-west spread over the
// raster's latitude range); no coordinate system: the geotransform taken as metres (logged).
// Non-square pixels are resampled (bilinear) to square samples at the finer of the two
// spacings, because HeightField and everything built on it (chunk trees, grass, trees) use one
// spacing; the finer one loses no detail. North-up rasters keep row 0 (north) at -z.
//
// Nodata (the band's nodata value, and NaN/Inf): counted; kFill replaces each such sample by the
// nearest valid one (8-neighbour flood from the valid samples), then smooths only the filled
// samples (kFillSmoothingPasses 3x3 means, valid samples untouched), with a warning naming the
// file and the count; kRefuse makes any nodata an error naming the count and the first sample.
// A raster with no valid sample is always an error naming the file.
//
// Failure (every message starts with the file name): missing (kNotFound); a format neither
// reader knows (kUnsupported); a rotated geotransform or an unknown vertical unit
// (kUnsupported); truncated or undecodable data (kCorrupt); fewer than 2x2 samples, more than
// `max_side` per side or more than `max_bytes` of float samples, checked from the header before
// anything is allocated, and again for the resampled size (kLimit, naming the size); nodata as
// above (kInvalidArgument). Thread-safe (GDAL errors are caught per thread).

#include <sylva/core/height_field.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/result.hpp>

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sylva {

enum class NodataPolicy { kFill, kRefuse };
constexpr std::array<EnumName<NodataPolicy>, 2> enum_names(NodataPolicy) {
  return {{{NodataPolicy::kFill, "fill"}, {NodataPolicy::kRefuse, "refuse"}}};
}

// 3x3 smoothing passes over filled nodata samples: enough to round the corners of the
// nearest-valid (Voronoi) steps without flattening large holes towards their mean.
inline constexpr int kFillSmoothingPasses = 8;

struct ElevationReadOptions {
  double spacing = 0.0;        // metres between samples; 0 = from the file's georeferencing
  double height_scale = 0.0;   // metres per stored value; 0 = from the file (band scale x unit)
  double height_offset = 0.0;  // metres added to every height
  NodataPolicy nodata = NodataPolicy::kFill;
  // Not reflected: set by the caller.
  double plain_extent = 0.0;            // x extent [m] of a raster without georeferencing (> 0)
  int max_side = 65536;                 // samples per side, before and after resampling
  std::uint64_t max_bytes = 4ull << 30; // float samples, before and after resampling [bytes]

  template <class V>
  void visit(V& v) {
    v(spacing, "spacing", {.min = 0.0, .max = 1.0e5, .unit = "m",
      .help = "Metres between samples; 0 = from the raster's georeferencing", .rebuild = Rebuild::kOffline});
    v(height_scale, "height_scale", {.min = -1.0e5, .max = 1.0e5, .unit = "m",
      .help = "Metres per stored value; 0 = from the raster (band scale and vertical unit)", .rebuild = Rebuild::kOffline});
    v(height_offset, "height_offset", {.min = -1.0e6, .max = 1.0e6, .unit = "m",
      .help = "Metres added to every height", .rebuild = Rebuild::kOffline});
    v(nodata, "nodata", {.help = "fill (nearest valid, smoothed; warns with the count) or refuse (error)",
      .rebuild = Rebuild::kOffline});
  }
};

// What was read, for logs, the editor and tests.
struct ElevationRaster {
  HeightField field;                // heights [m], square spacing [m], origin (0, 0)
  bool georeferenced = false;       // read through GDAL with a geotransform or coordinate system
  std::string reader;               // "GDAL GTiff", "GDAL SRTMHGT", "OpenImageIO", ...
  std::string crs;                  // coordinate system name ("" when none)
  double source_spacing_x = 0.0;    // metres between the file's columns (before resampling)
  double source_spacing_z = 0.0;    // metres between the file's rows
  int source_columns = 0;
  int source_rows = 0;
  std::size_t nodata_filled = 0;    // samples replaced under NodataPolicy::kFill
};

Result<ElevationRaster> read_elevation(const std::filesystem::path& file, const ElevationReadOptions& options = {});

// The nodata fill on its own (GL-free, GDAL-free; used by read_elevation): `valid[k] == 0`
// marks values[k] as nodata. columns * rows == values.size() == valid.size() and at least one
// valid sample (asserted). Returns the count filled.
std::size_t fill_nodata(std::vector<float>& values, const std::vector<std::uint8_t>& valid, int columns, int rows);

}  // namespace sylva
