// Elevation rasters through GDAL, or OpenImageIO for pictures without georeferencing (contract
// and rules in <sylva/core/elevation_raster.hpp>). The only place core touches GDAL.
#include <sylva/core/elevation_raster.hpp>

#include <sylva/core/image.hpp>
#include <sylva/core/log.hpp>

#include "elevation_georef.hpp"

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <numbers>
#include <system_error>

namespace sylva {
namespace {

namespace fs = std::filesystem;

// GDAL reports through a per-thread error handler; a quiet one keeps its messages out of
// stderr, and the last one is put into ours.
class QuietGdalErrors {
 public:
  QuietGdalErrors() {
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
  }
  ~QuietGdalErrors() { CPLPopErrorHandler(); }
  QuietGdalErrors(const QuietGdalErrors&) = delete;
  QuietGdalErrors& operator=(const QuietGdalErrors&) = delete;
};

std::string gdal_message() {
  const char* m = CPLGetLastErrorMsg();
  return m && *m ? std::string(m) : std::string("no details from GDAL");
}

struct CloseDataset {
  void operator()(void* ds) const { GDALClose(ds); }
};
using Dataset = std::unique_ptr<void, CloseDataset>;

Status check_size(const std::string& name, int columns, int rows, const ElevationReadOptions& o, const char* what) {
  if (columns < 2 || rows < 2) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("{}: {} {}x{} samples; a height field needs at least 2x2", name, what, columns, rows));
  }
  const std::uint64_t bytes = static_cast<std::uint64_t>(columns) * static_cast<std::uint64_t>(rows) * sizeof(float);
  if (columns > o.max_side || rows > o.max_side || bytes > o.max_bytes) {
    return make_error(ErrorCode::kLimit,
                      fmt::format("{}: {} {}x{} samples ({} MiB as floats), above the limit of {} per side and {} MiB",
                                  name, what, columns, rows, bytes >> 20, o.max_side, o.max_bytes >> 20));
  }
  return {};
}

// The samples' description, before heights, nodata and resampling (the samples themselves are
// read straight into their final array: see read_heights).
struct RawGrid {
  int columns = 0;
  int rows = 0;
  bool has_nodata = false;
  float nodata = 0.0f;
  double scale = 1.0;    // metres per stored value
  double offset = 0.0;   // metres
  double spacing_x = 0.0;  // metres; 0 = not known (no geotransform)
  double spacing_z = 0.0;
};

// Fills `values` (columns * rows, row 0 north) with the stored values.
using SampleReader = std::function<Status(std::vector<float>& values)>;

// The HeightField's size and spacing, known from the header before any pixel is read.
struct SquareLayout {
  int columns = 0;
  int rows = 0;
  double spacing = 1.0;
  bool resample = false;  // non-square pixels: read into a second array, resampled into the field
};

Result<SquareLayout> square_layout(const std::string& name, const RawGrid& raw, const ElevationReadOptions& o) {
  SquareLayout layout{raw.columns, raw.rows, o.spacing, false};
  if (layout.spacing <= 0.0 && raw.spacing_x > 0.0) {
    layout.spacing = std::min(raw.spacing_x, raw.spacing_z);
    if (std::abs(raw.spacing_x - raw.spacing_z) > 1e-9 * layout.spacing) {
      // HeightField has one spacing; resample to the finer one so no detail is lost.
      detail::resampled_size(raw.columns, raw.rows, raw.spacing_x, raw.spacing_z, layout.spacing, layout.columns,
                             layout.rows);
      SYLVA_TRY(check_size(name, layout.columns, layout.rows, o, "resampled to square samples is"));
      layout.resample = true;
    }
  } else if (layout.spacing <= 0.0) {
    layout.spacing = o.plain_extent > 0.0 ? o.plain_extent / (raw.columns - 1) : 1.0;
  }
  return layout;
}

// Stored values to heights in metres, in place; then the nodata policy. Returns the count filled.
Result<std::size_t> heights_in_metres(const std::string& name, std::vector<float>& values, const RawGrid& raw,
                                      const ElevationReadOptions& o) {
  // An unusable sample becomes NaN (every usable height is finite), so the mask the fill needs
  // is made only when there is something to fill, and only for as long as the fill runs.
  std::size_t invalid = 0, first_bad = 0;
  for (std::size_t k = 0; k < values.size(); ++k) {
    const float v = values[k];
    const double metres = static_cast<double>(v) * raw.scale + raw.offset;
    // A value that leaves float range once scaled is as unusable as NaN (cf. c901c22).
    if ((raw.has_nodata && v == raw.nodata) || !std::isfinite(static_cast<float>(metres))) {
      if (invalid++ == 0) first_bad = k;
      values[k] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    values[k] = static_cast<float>(metres);
  }
  if (invalid == 0) return std::size_t{0};
  const std::string what_nodata = raw.has_nodata ? fmt::format("nodata ({}) or NaN/Inf", raw.nodata) : "NaN/Inf";
  if (invalid == values.size()) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: all {} samples are {}; there is no height to show", name, invalid, what_nodata));
  }
  const auto cols = static_cast<std::size_t>(raw.columns);
  if (o.nodata == NodataPolicy::kRefuse) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: {} of {} samples are {}, the first at column {} row {} (nodata = refuse; "
                                  "\"fill\" fills them from the nearest valid samples)",
                                  name, invalid, values.size(), what_nodata, first_bad % cols, first_bad / cols));
  }
  std::vector<std::uint8_t> valid(values.size());
  for (std::size_t k = 0; k < values.size(); ++k) valid[k] = std::isnan(values[k]) ? 0 : 1;
  const std::size_t filled = fill_nodata(values, valid, raw.columns, raw.rows);
  log_warn("{}: filled {} {} samples of {} from the nearest valid ones, smoothed", name, filled, what_nodata,
           values.size());
  return filled;
}

// Heights, nodata policy, square spacing, and the HeightField (shared by both readers). Square
// samples are read straight into the HeightField's own array, so a raster is held once (the
// largest allocation of a raster bake, terrain README "Baking"); non-square ones need the
// source array and the resampled field side by side.
Result<ElevationRaster> read_heights(const std::string& name, const RawGrid& raw, ElevationRaster info,
                                     const ElevationReadOptions& o, const SampleReader& read_samples) {
  auto layout = square_layout(name, raw, o);
  if (!layout.ok()) return layout.error();
  info.source_columns = raw.columns;
  info.source_rows = raw.rows;
  info.source_spacing_x = raw.spacing_x;
  info.source_spacing_z = raw.spacing_z;
  if (!layout->resample) {
    info.field = HeightField(layout->columns, layout->rows, layout->spacing);
    SYLVA_TRY(read_samples(info.field.samples()));
    auto filled = heights_in_metres(name, info.field.samples(), raw, o);
    if (!filled.ok()) return filled.error();
    info.nodata_filled = *filled;
  } else {
    std::vector<float> source(static_cast<std::size_t>(raw.columns) * static_cast<std::size_t>(raw.rows));
    SYLVA_TRY(read_samples(source));
    auto filled = heights_in_metres(name, source, raw, o);
    if (!filled.ok()) return filled.error();
    info.nodata_filled = *filled;
    info.field = HeightField(layout->columns, layout->rows, layout->spacing);
    detail::resample_square(source, raw.columns, raw.rows, raw.spacing_x, raw.spacing_z, layout->spacing,
                            layout->columns, layout->rows, info.field.samples());
    log_info("{}: non-square samples ({:.3f} x {:.3f} m) resampled from {}x{} to {}x{} at {:.3f} m", name,
             raw.spacing_x, raw.spacing_z, raw.columns, raw.rows, layout->columns, layout->rows, layout->spacing);
  }
  info.field.update_range();
  return info;
}

// A picture without georeferencing: today's height-map rules (normalised pixels).
Result<ElevationRaster> read_plain(const fs::path& file, const ElevationReadOptions& o, const std::string& gdal_why) {
  const std::string name = file.string();
  ImageReadOptions image_options;
  image_options.max_side = o.max_side;
  image_options.max_bytes = o.max_bytes;
  auto image = read_image(file, image_options);
  if (!image.ok()) {
    if (image.error().code == ErrorCode::kUnsupported && !gdal_why.empty()) {
      return make_error(ErrorCode::kUnsupported,
                        fmt::format("{}: not an elevation raster GDAL or OpenImageIO can read (GDAL: {}; {})", name,
                                    gdal_why, image.error().message));
    }
    return image.error();
  }
  RawGrid raw;
  raw.columns = image->width();
  raw.rows = image->height();
  SYLVA_TRY(check_size(name, raw.columns, raw.rows, o, "image is"));
  raw.scale = o.height_scale != 0.0 ? o.height_scale : 1.0;
  raw.offset = o.height_offset;
  if (o.height_scale == 0.0) {
    log_warn("{}: no georeferencing or vertical unit: heights are the normalised pixel values (1.0 = white) in "
             "metres; set height_scale",
             name);
  }
  ElevationRaster info;
  info.reader = "OpenImageIO";
  return read_heights(name, raw, std::move(info), o, [&](std::vector<float>& values) {
    for (int y = 0; y < raw.rows; ++y) {
      for (int x = 0; x < raw.columns; ++x) values[static_cast<std::size_t>(y) * raw.columns + x] = image->at(x, y, 0);
    }
    return ok_status();
  });
}

// Spacing in metres from the geotransform and coordinate system; logs how it was found.
Status georeferenced_spacing(const std::string& name, const double gt[6], OGRSpatialReferenceH srs, int rows,
                             RawGrid& raw, std::string& crs) {
  if (gt[2] != 0.0 || gt[4] != 0.0) {
    return make_error(ErrorCode::kUnsupported,
                      fmt::format("{}: the geotransform is rotated or sheared ({}, {}); warp the raster north-up "
                                  "first (gdalwarp)",
                                  name, gt[2], gt[4]));
  }
  if (srs) {
    const char* n = OSRGetName(srs);
    crs = n ? n : "";
  }
  if (srs && OSRIsGeographic(srs)) {
    const double deg_per_unit = OSRGetAngularUnits(srs, nullptr) * 180.0 / std::numbers::pi;
    OGRErr err = OGRERR_NONE;
    const double a = OSRGetSemiMajor(srs, &err);
    const double inv_f = OSRGetInvFlattening(srs, &err);
    const double top = gt[3] * deg_per_unit, bottom = (gt[3] + gt[5] * rows) * deg_per_unit;
    const double centre = 0.5 * (top + bottom);
    const auto s = detail::geographic_spacing(gt[1] * deg_per_unit, gt[5] * deg_per_unit, centre, a, inv_f);
    const double n_edge = detail::geographic_spacing(gt[1] * deg_per_unit, 0.0, std::max(top, bottom), a, inv_f).x;
    const double s_edge = detail::geographic_spacing(gt[1] * deg_per_unit, 0.0, std::min(top, bottom), a, inv_f).x;
    raw.spacing_x = s.x;
    raw.spacing_z = s.z;
    log_info("{}: geographic coordinates ({}): spacing converted to metres at the raster's centre latitude {:.4f} deg: "
             "{:.3f} m east-west, {:.3f} m north-south; east-west spacing runs from {:.3f} to {:.3f} m over the "
             "raster's latitudes",
             name, crs, centre, s.x, s.z, std::min(n_edge, s_edge), std::max(n_edge, s_edge));
    return {};
  }
  double metres = 1.0;
  if (srs) {
    metres = OSRGetLinearUnits(srs, nullptr);
  } else {
    log_info("{}: a geotransform without a coordinate system: its units are taken as metres", name);
  }
  raw.spacing_x = std::abs(gt[1]) * metres;
  raw.spacing_z = std::abs(gt[5]) * metres;
  return {};
}

// Band 1 into `values` (row 0 north, column 0 west), one row of blocks at a time, dropping the
// blocks from GDAL's cache after each: GDAL would otherwise keep a second copy of every block it
// read, up to GDAL_CACHEMAX (by default 5 % of the RAM; 1.2 GB on a 24 GB machine), which at
// 16385^2 alone would take a bake past its 2 GiB budget whatever the caller set.
Status read_band(const std::string& name, GDALDatasetH ds, GDALRasterBandH band, int columns, int rows,
                 bool flip_rows, bool flip_columns, std::vector<float>& values) {
  int block_columns = 0, block_rows = 0;
  GDALGetBlockSize(band, &block_columns, &block_rows);
  const int strip = std::clamp(block_rows, 1, rows);
  // Rows run north to south and columns west to east in the file when the pixel size is
  // negative/positive; negative strides keep row 0 north and column 0 west otherwise.
  const auto cols = static_cast<GSpacing>(columns);
  const GSpacing pixel = flip_columns ? -static_cast<GSpacing>(sizeof(float)) : static_cast<GSpacing>(sizeof(float));
  const GSpacing line = (flip_rows ? -cols : cols) * static_cast<GSpacing>(sizeof(float));
  CPLErrorReset();
  for (int y = 0; y < rows; y += strip) {
    const int count = std::min(strip, rows - y);
    float* start = values.data() + (flip_rows ? rows - 1 - y : y) * cols + (flip_columns ? cols - 1 : 0);
    const CPLErr read = GDALRasterIOEx(band, GF_Read, 0, y, columns, count, start, columns, count, GDT_Float32, pixel,
                                       line, nullptr);
    if (read != CE_None || CPLGetLastErrorType() >= CE_Failure) {
      return make_error(ErrorCode::kCorrupt,
                        fmt::format("{}: truncated or corrupt raster data ({})", name, gdal_message()));
    }
    GDALFlushCache(ds);
  }
  return ok_status();
}

Result<ElevationRaster> read_gdal(const std::string& name, GDALDatasetH ds, const double gt[6], bool has_gt,
                                  OGRSpatialReferenceH srs, const ElevationReadOptions& o) {
  RawGrid raw;
  raw.columns = GDALGetRasterXSize(ds);
  raw.rows = GDALGetRasterYSize(ds);
  if (GDALGetRasterCount(ds) < 1) return make_error(ErrorCode::kUnsupported, fmt::format("{}: the raster has no band", name));
  SYLVA_TRY(check_size(name, raw.columns, raw.rows, o, "raster is"));
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  if (GDALDataTypeIsComplex(GDALGetRasterDataType(band))) {
    return make_error(ErrorCode::kUnsupported, fmt::format("{}: complex samples are not heights", name));
  }
  ElevationRaster info;
  info.georeferenced = true;
  info.reader = fmt::format("GDAL {}", GDALGetDriverShortName(GDALGetDatasetDriver(ds)));
  if (has_gt) SYLVA_TRY(georeferenced_spacing(name, gt, srs, raw.rows, raw, info.crs));

  int has_nodata = 0;
  const double nodata = GDALGetRasterNoDataValue(band, &has_nodata);
  raw.has_nodata = has_nodata != 0;
  raw.nodata = static_cast<float>(nodata);
  if (o.height_scale != 0.0) {
    raw.scale = o.height_scale;
    raw.offset = o.height_offset;
  } else {
    const char* unit = GDALGetRasterUnitType(band);
    const auto metres = detail::vertical_unit_metres(unit ? unit : "");
    if (!metres) {
      return make_error(ErrorCode::kUnsupported,
                        fmt::format("{}: unknown vertical unit \"{}\"; set height_scale (metres per stored value)",
                                    name, unit));
    }
    if (*metres != 1.0) log_info("{}: heights in \"{}\", converted to metres (x {})", name, unit, *metres);
    raw.scale = GDALGetRasterScale(band, nullptr) * *metres;
    raw.offset = GDALGetRasterOffset(band, nullptr) * *metres + o.height_offset;
  }

  const bool flip_rows = has_gt && gt[5] > 0.0, flip_columns = has_gt && gt[1] < 0.0;
  return read_heights(name, raw, std::move(info), o, [&](std::vector<float>& values) {
    return read_band(name, ds, band, raw.columns, raw.rows, flip_rows, flip_columns, values);
  });
}

}  // namespace

Result<ElevationRaster> read_elevation(const fs::path& file, const ElevationReadOptions& options) {
  static std::once_flag registered;
  std::call_once(registered, [] { GDALAllRegister(); });
  const std::string name = file.string();
  std::error_code ec;
  if (!fs::exists(file, ec)) return make_error(ErrorCode::kNotFound, fmt::format("{}: no such file", name));
  if (fs::is_directory(file, ec)) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: is a folder, not an elevation raster", name));
  }
  QuietGdalErrors quiet;
  Dataset ds(GDALOpenEx(name.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  if (!ds) return read_plain(file, options, gdal_message());
  double gt[6] = {0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  const bool has_gt = GDALGetGeoTransform(ds.get(), gt) == CE_None;
  OGRSpatialReferenceH srs = GDALGetSpatialRef(ds.get());
  if (!has_gt && !srs) {
    // No georeferencing: a picture, read as today's height maps (the documented rule).
    ds.reset();
    return read_plain(file, options, "");
  }
  return read_gdal(name, ds.get(), gt, has_gt, srs, options);
}

}  // namespace sylva
