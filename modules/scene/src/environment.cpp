#include <sylva/scene/environment.hpp>

#include <sylva/render/atmosphere.hpp>
#include <sylva/render/sky.hpp>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::scene {

SunPosition sun_from_clock(float time_of_day_h, float season, float latitude_deg) {
  const double deg = glm::pi<double>() / 180.0;
  const double declination = 23.44 * deg * std::sin(2.0 * glm::pi<double>() * season);
  const double hour_angle = 15.0 * deg * (static_cast<double>(time_of_day_h) - 12.0);
  const double lat = static_cast<double>(latitude_deg) * deg;
  const double sin_el = std::sin(lat) * std::sin(declination) + std::cos(lat) * std::cos(declination) * std::cos(hour_angle);
  const double elevation = std::asin(std::clamp(sin_el, -1.0, 1.0));
  // Azimuth from north toward east: atan2(-sin H cos d, sin d cos lat - cos d sin lat cos H).
  const double y = -std::sin(hour_angle) * std::cos(declination);
  const double x = std::sin(declination) * std::cos(lat) - std::cos(declination) * std::sin(lat) * std::cos(hour_angle);
  double azimuth = std::atan2(y, x) / deg;
  if (azimuth < 0.0) azimuth += 360.0;
  if (azimuth >= 360.0) azimuth -= 360.0;
  return {static_cast<float>(azimuth), static_cast<float>(elevation / deg)};
}

SunPosition sun_position(const SunSettings& sun, const EnvironmentSettings& environment) {
  if (sun.follow_clock) return sun_from_clock(environment.time_of_day_h, environment.season, environment.latitude_deg);
  return {sun.azimuth_deg, sun.elevation_deg};
}

render::Lighting make_lighting(const SunSettings& sun, const EnvironmentSettings& environment) {
  const SunPosition pos = sun_position(sun, environment);
  render::Lighting l;
  // Below the horizon the light still comes from just above it (the sky glow), never from below.
  l.sun_direction = render::sun_direction(glm::radians(pos.azimuth_deg), glm::radians(std::max(pos.elevation_deg, 0.5f)));
  // Twilight: the disk's light fades out between +2 and -4 deg (civil twilight); above that the
  // atmosphere alone dims and reddens it.
  const float day = std::clamp((pos.elevation_deg + 4.0f) / 6.0f, 0.0f, 1.0f);
  // sun.color is the colour straight overhead: scale the transmittance toward the sun by the
  // zenith's (its luminance), so `intensity` is the overhead brightness and a low sun is orange.
  const glm::vec3 toward_sun = render::atmosphere_transmittance(l.atmosphere, 0.0f, l.sun_direction);
  const glm::vec3 overhead = render::atmosphere_transmittance(l.atmosphere, 0.0f, {0.0f, 1.0f, 0.0f});
  const float overhead_luminance = glm::dot(overhead, glm::vec3(0.2126f, 0.7152f, 0.0722f));
  l.sun_color = sun.color * toward_sun / std::max(overhead_luminance, 1.0e-6f);
  l.sun_intensity = sun.intensity * day;
  l.fog_density = sun.fog_density;
  l.fog_height_falloff = sun.fog_height_falloff;
  render::derive_sky_lighting(l, sun.ambient);
  return l;
}

}  // namespace sylva::scene
