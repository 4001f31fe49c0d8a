#pragma once
// Small georeferenced rasters written through the GDAL API, for the elevation tests (issue 15):
// the tests make their own GeoTIFFs instead of shipping binary fixtures; and the log lines the
// reader writes about them. Header-only so the scene tests can include it too (they add this
// folder to their include path).

#include <sylva/core/log.hpp>

#include <cpl_conv.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sylva::test {

// Every info and warning line logged while alive.
struct LogCapture {
  std::vector<std::string> info, warnings;
  LogCapture() {
    set_log_sink([this](LogLevel level, std::string_view m) {
      if (level == LogLevel::kWarn) warnings.emplace_back(m);
      if (level == LogLevel::kInfo) info.emplace_back(m);
    });
  }
  ~LogCapture() { set_log_sink(nullptr); }
  LogCapture(const LogCapture&) = delete;
  LogCapture& operator=(const LogCapture&) = delete;
  // A line holding both a and b.
  static bool any(const std::vector<std::string>& lines, const std::string& a, const std::string& b = "") {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) {
      return l.find(a) != std::string::npos && l.find(b) != std::string::npos;
    });
  }
};

struct GeoTiffSpec {
  int columns = 0;
  int rows = 0;
  GDALDataType type = GDT_Int16;
  int epsg = 32632;                 // WGS 84 / UTM zone 32N; 4326 = geographic WGS 84; 0 = none
  double left = 500000.0;           // x (or longitude) of the raster's west edge
  double top = 5200000.0;           // y (or latitude) of its north edge
  double pixel_x = 30.0;            // column spacing in CRS units
  double pixel_y = 30.0;            // row spacing in CRS units (written north-up, negative)
  std::optional<double> nodata;
  std::string unit;                 // band unit type ("", "m", "ft", ...)
  std::vector<double> values;       // row-major, north row first; columns * rows
  std::vector<std::string> options; // creation options, e.g. "TILED=YES", "COMPRESS=DEFLATE"
  bool write_values = true;         // false: header only (a sparse file of any claimed size)
};

inline void write_geotiff(const std::filesystem::path& file, const GeoTiffSpec& spec) {
  GDALAllRegister();
  GDALDriverH driver = GDALGetDriverByName("GTiff");
  if (!driver) throw std::runtime_error("GDAL has no GTiff driver");
  char** options = nullptr;
  for (const auto& o : spec.options) options = CSLAddString(options, o.c_str());
  if (!spec.write_values) options = CSLAddString(options, "SPARSE_OK=TRUE");
  GDALDatasetH ds = GDALCreate(driver, file.string().c_str(), spec.columns, spec.rows, 1, spec.type, options);
  CSLDestroy(options);
  if (!ds) throw std::runtime_error("cannot create " + file.string() + ": " + CPLGetLastErrorMsg());
  double gt[6] = {spec.left, spec.pixel_x, 0.0, spec.top, 0.0, -spec.pixel_y};
  GDALSetGeoTransform(ds, gt);
  if (spec.epsg != 0) {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, spec.epsg);
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
  }
  GDALRasterBandH band = GDALGetRasterBand(ds, 1);
  if (spec.nodata) GDALSetRasterNoDataValue(band, *spec.nodata);
  if (!spec.unit.empty()) GDALSetRasterUnitType(band, spec.unit.c_str());
  if (spec.write_values) {
    std::vector<double> values = spec.values;
    if (GDALRasterIO(band, GF_Write, 0, 0, spec.columns, spec.rows, values.data(), spec.columns, spec.rows, GDT_Float64,
                     0, 0) != CE_None) {
      GDALClose(ds);
      throw std::runtime_error("cannot write " + file.string());
    }
  }
  GDALClose(ds);
}

}  // namespace sylva::test
