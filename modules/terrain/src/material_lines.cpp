// Altitude lines of the terrain material for a latitude and a season (material.hpp states the
// model and the measured lines it follows).
#include <sylva/terrain/material.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva::terrain {

float latitude_factor(float latitude_deg) {
  const float phi = glm::radians(std::clamp(latitude_deg, -90.0f, 90.0f));
  return 1.0f + std::cos(2.0f * phi);
}

MaterialLines material_lines(const MaterialSettings& s, const Climate& climate) {
  const Climate defaults;
  const float latitude = std::isfinite(climate.latitude_deg) ? std::clamp(climate.latitude_deg, -90.0f, 90.0f)
                                                             : defaults.latitude_deg;
  float season = std::isfinite(climate.season) ? climate.season : defaults.season;
  if (latitude < 0.0f) season += 0.5f;  // the southern winter is the northern summer
  const float f = latitude_factor(latitude);
  // 0 at the end of summer (season 0.4), 1 at the end of winter (0.9): seasonal snow lags the sun
  // by about seven weeks in the Alps.
  const float winter = 0.5f * (1.0f - std::cos(2.0f * std::numbers::pi_v<float> * (season - 0.4f)));
  // Seasons grow with latitude: none at the equator, the full drop at 45, snow to the sea at 60.
  const float reach = std::abs(std::sin(glm::radians(latitude))) / std::sin(glm::radians(45.0f));
  const float drop = std::clamp(s.winter_snow_drop * reach, 0.0f, 1.0f);
  MaterialLines lines;
  lines.snow = s.snow_line_m * f * (1.0f - drop * winter) - s.base_altitude_m;
  lines.rock = s.rock_line_m * f - s.base_altitude_m;
  lines.tree = s.tree_line_m * f - s.base_altitude_m;
  lines.water = s.water_level_m - s.base_altitude_m;
  return lines;
}

}  // namespace sylva::terrain
