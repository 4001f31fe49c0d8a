#include "elevation_georef.hpp"

#include <sylva/core/assert.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <string>

namespace sylva::detail {

std::optional<double> vertical_unit_metres(std::string_view unit) {
  std::string u(unit);
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (u.empty() || u == "m" || u == "metre" || u == "meter" || u == "metres" || u == "meters") return 1.0;
  if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return 0.3048;
  if (u == "us survey foot" || u == "us-ft" || u == "ft-us" || u == "foot_us" || u == "us_survey_foot") {
    return 1200.0 / 3937.0;
  }
  return std::nullopt;
}

MetricSpacing geographic_spacing(double dlon_deg, double dlat_deg, double lat_deg, double a, double inv_f) {
  const double f = inv_f > 0.0 ? 1.0 / inv_f : 0.0;
  const double e2 = f * (2.0 - f);
  const double phi = lat_deg * std::numbers::pi / 180.0;
  const double s = std::sin(phi);
  const double w = std::sqrt(1.0 - e2 * s * s);
  const double prime_vertical = a / w;                       // N
  const double meridional = a * (1.0 - e2) / (w * w * w);    // M
  const double rad = std::numbers::pi / 180.0;
  return {std::abs(dlon_deg) * rad * prime_vertical * std::cos(phi), std::abs(dlat_deg) * rad * meridional};
}

void resampled_size(int columns, int rows, double sx, double sz, double spacing, int& out_columns, int& out_rows) {
  out_columns = static_cast<int>(std::lround((columns - 1) * sx / spacing)) + 1;
  out_rows = static_cast<int>(std::lround((rows - 1) * sz / spacing)) + 1;
}

void resample_square(const std::vector<float>& values, int columns, int rows, double sx, double sz, double spacing,
                     int out_columns, int out_rows, std::vector<float>& out) {
  SYLVA_ASSERT(out.size() == static_cast<std::size_t>(out_columns) * static_cast<std::size_t>(out_rows),
               "resample_square: {} values for {}x{}", out.size(), out_columns, out_rows);
  auto at = [&](int i, int j) {
    return values[static_cast<std::size_t>(j) * static_cast<std::size_t>(columns) + static_cast<std::size_t>(i)];
  };
  for (int j = 0; j < out_rows; ++j) {
    const double v = std::clamp(j * spacing / sz, 0.0, static_cast<double>(rows - 1));
    const int j0 = std::min(static_cast<int>(v), rows - 2 < 0 ? 0 : rows - 2);
    const double fz = v - j0;
    const int j1 = std::min(j0 + 1, rows - 1);
    for (int i = 0; i < out_columns; ++i) {
      const double u = std::clamp(i * spacing / sx, 0.0, static_cast<double>(columns - 1));
      const int i0 = std::min(static_cast<int>(u), columns - 2 < 0 ? 0 : columns - 2);
      const double fx = u - i0;
      const int i1 = std::min(i0 + 1, columns - 1);
      const double top = at(i0, j0) * (1.0 - fx) + at(i1, j0) * fx;
      const double bottom = at(i0, j1) * (1.0 - fx) + at(i1, j1) * fx;
      out[static_cast<std::size_t>(j) * static_cast<std::size_t>(out_columns) + static_cast<std::size_t>(i)] =
          static_cast<float>(top * (1.0 - fz) + bottom * fz);
    }
  }
}

}  // namespace sylva::detail
