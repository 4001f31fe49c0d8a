// Sun and sky from the time of day; see time_of_day.hpp.
#include <sylva/render/time_of_day.hpp>

#include <sylva/render/sky.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

constexpr float kPi = 3.14159265358979f;
// Optical depth per air mass for R, G, B: Rayleigh-like (~lambda^-4) plus a little haze.
constexpr glm::vec3 kExtinction{0.06f, 0.13f, 0.30f};

float smoothstep01(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace

float time_of_day_elevation(const TimeOfDaySettings& s) {
  const float h = std::isfinite(s.hours) ? std::fmod(std::fmod(s.hours, 24.0f) + 24.0f, 24.0f) : 12.0f;
  const float noon = std::clamp(std::isfinite(s.noon_elevation_deg) ? s.noon_elevation_deg : 60.0f, 0.0f, 90.0f) * kPi / 180.0f;
  // Rises at 6 h, culminates at 12 h, sets at 18 h; the night half mirrors it below the horizon.
  return std::asin(std::sin(noon) * std::sin(kPi * (h - 6.0f) / 12.0f));
}

float air_mass(float elevation) {
  const float deg = std::max(elevation * 180.0f / kPi, -1.0f);
  const float e = std::max(deg, 0.0f);
  // Kasten & Young 1989: 1 / (sin(h) + 0.50572 (h + 6.07995 deg)^-1.6364), h in degrees.
  const float m = 1.0f / (std::sin(e * kPi / 180.0f) + 0.50572f * std::pow(e + 6.07995f, -1.6364f));
  return std::min(m, 40.0f);
}

Lighting lighting_for_time_of_day(const TimeOfDaySettings& s, const Lighting& base) {
  Lighting out = base;
  const float h = std::isfinite(s.hours) ? std::fmod(std::fmod(s.hours, 24.0f) + 24.0f, 24.0f) : 12.0f;
  const float elevation = time_of_day_elevation(s);
  // Azimuth: east (+x, pi/2) at 6 h, south (+z, pi) at noon, west (3 pi / 2) at 18 h.
  const float azimuth = kPi * 0.5f + kPi * (h - 6.0f) / 12.0f;
  out.sun_direction = sun_direction(azimuth, elevation);

  const float turbidity = std::clamp(std::isfinite(s.turbidity) ? s.turbidity : 1.0f, 0.1f, 10.0f);
  const float m = air_mass(elevation);
  const glm::vec3 transmittance = glm::exp(-kExtinction * (turbidity * m));
  // Daylight fades in over the last 2 degrees below the horizon (the disk and twilight).
  const float day = smoothstep01(-0.035f, 0.02f, elevation);
  const float intensity = std::clamp(std::isfinite(s.sun_intensity) ? s.sun_intensity : 3.0f, 0.0f, 100.0f);
  out.sun_color = transmittance / std::max(transmittance.x, 1e-6f);  // hue only, red channel = 1
  out.sun_intensity = intensity * transmittance.x * day;

  // Sky, ambient and fog from the atmosphere lit by the same sun, with a dim night floor.
  derive_sky_lighting(out);
  const glm::vec3 night{0.004f, 0.006f, 0.012f};
  out.zenith_color = glm::max(out.zenith_color, night);
  out.horizon_color = glm::max(out.horizon_color, night);
  out.ambient = glm::max(out.ambient, night);
  out.fog_color = out.horizon_color;
  return out;
}

}  // namespace sylva::render
