#pragma once
// GDAL-free pieces of read_elevation (<sylva/core/elevation_raster.hpp>): vertical units, the
// spacing of a geographic raster in metres, and resampling non-square pixels to square ones.

#include <optional>
#include <string_view>
#include <vector>

namespace sylva::detail {

// Metres per vertical unit named by a band's unit type ("m", "metre", "ft", "US survey foot",
// ...; case-insensitive). "" is read as metres (most DEMs leave it empty). nullopt: unknown.
std::optional<double> vertical_unit_metres(std::string_view unit);

// Metres between samples of a geographic raster at latitude `lat_deg`, on an ellipsoid of
// semi-major axis `a` [m] and inverse flattening `inv_f` (0 = sphere): x from the prime-vertical
// radius times cos(latitude), z from the meridional radius.
struct MetricSpacing {
  double x = 0.0;
  double z = 0.0;
};
MetricSpacing geographic_spacing(double dlon_deg, double dlat_deg, double lat_deg, double a, double inv_f);

// Bilinear resampling of a columns x rows grid with spacings (sx, sz) to square samples at
// `spacing`, covering the same extent to within half a sample, into `out` (out_columns x
// out_rows from resampled_size, sized by the caller: the HeightField's own array).
void resample_square(const std::vector<float>& values, int columns, int rows, double sx, double sz, double spacing,
                     int out_columns, int out_rows, std::vector<float>& out);

// Output size of resample_square (for the limit check before allocating).
void resampled_size(int columns, int rows, double sx, double sz, double spacing, int& out_columns, int& out_rows);

}  // namespace sylva::detail
