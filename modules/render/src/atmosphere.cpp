// Single-scattering atmosphere on the CPU; see atmosphere.hpp. The table look-up mirrors
// shaders/lib/sky.glsl (atmosphere_radiance); keep the two identical.
#include <sylva/render/atmosphere.hpp>

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPlanetRadius = 6360.0e3;      // [m] (Bruneton 2008)
constexpr double kAtmosphereRadius = 6460.0e3;  // [m], 100 km of air
constexpr double kOzoneCentre = 25.0e3;         // [m], tent profile (Hillaire 2020)
constexpr double kOzoneHalfWidth = 15.0e3;      // [m]

using dvec3 = glm::dvec3;

// Distance along the unit ray from p to the sphere of radius r (the far hit), or -1 if none.
double ray_sphere_far(const dvec3& p, const dvec3& d, double r) {
  const double b = glm::dot(p, d);
  const double c = glm::dot(p, p) - r * r;
  const double disc = b * b - c;
  if (disc < 0.0) return -1.0;
  return -b + std::sqrt(disc);
}

// True if the ray from p (inside the atmosphere) hits the planet.
bool hits_ground(const dvec3& p, const dvec3& d) {
  const double b = glm::dot(p, d);
  if (b >= 0.0) return false;
  const double c = glm::dot(p, p) - kPlanetRadius * kPlanetRadius;
  return b * b - c >= 0.0;
}

struct Media {
  dvec3 rayleigh;    // scattering [1/m] at this point
  double mie;        // scattering [1/m]
  dvec3 extinction;  // total [1/m]
};

Media media_at(const AtmosphereSettings& a, double altitude) {
  const double h = std::max(altitude, 0.0);
  const double rho_r = std::exp(-h / std::max(static_cast<double>(a.rayleigh_scale_height), 1.0));
  const double rho_m = std::exp(-h / std::max(static_cast<double>(a.mie_scale_height), 1.0));
  const double rho_o = std::max(0.0, 1.0 - std::abs(h - kOzoneCentre) / kOzoneHalfWidth);
  Media m;
  m.rayleigh = dvec3(a.rayleigh_scattering) * rho_r;
  m.mie = static_cast<double>(a.mie_scattering) * rho_m;
  m.extinction = m.rayleigh + dvec3((static_cast<double>(a.mie_scattering) + a.mie_absorption) * rho_m) +
                 dvec3(a.ozone_absorption) * rho_o;
  return m;
}

// Optical depth from p to the top of the atmosphere along d, `steps` quadratic steps (denser
// near p, where the air is densest for rays leaving the ground).
dvec3 optical_depth(const AtmosphereSettings& a, const dvec3& p, const dvec3& d, int steps) {
  const double length = std::max(ray_sphere_far(p, d, kAtmosphereRadius), 0.0);
  dvec3 depth(0.0);
  double t_prev = 0.0;
  for (int i = 1; i <= steps; ++i) {
    const double s = static_cast<double>(i) / steps;
    const double t = length * s * s;
    const double mid = 0.5 * (t + t_prev);
    depth += media_at(a, glm::length(p + d * mid) - kPlanetRadius).extinction * (t - t_prev);
    t_prev = t;
  }
  return depth;
}

dvec3 safe_unit(const glm::vec3& v, const dvec3& fallback) {
  const dvec3 d(v);
  const double len = glm::length(d);
  return len > 1.0e-9 && std::isfinite(len) ? d / len : fallback;
}

// In-scattering integrals (without phase) along one view ray from sea level; `isotropic` gets
// the integral of the total scattering coefficient * transmittance over the sunlit part of
// the ray (what an isotropic light field of unit radiance scatters toward the viewer).
void integrate_view_ray(const AtmosphereSettings& a, const dvec3& view, const dvec3& sun, dvec3& rayleigh, dvec3& mie,
                        dvec3& isotropic) {
  constexpr int kSteps = 64;
  constexpr int kSunSteps = 24;
  const dvec3 origin(0.0, kPlanetRadius + 1.0, 0.0);
  const double length = std::max(ray_sphere_far(origin, view, kAtmosphereRadius), 0.0);
  rayleigh = dvec3(0.0);
  mie = dvec3(0.0);
  isotropic = dvec3(0.0);
  dvec3 depth(0.0);  // optical depth from the viewer to the current sample
  double t_prev = 0.0;
  for (int i = 1; i <= kSteps; ++i) {
    const double s = static_cast<double>(i) / kSteps;
    const double t = length * s * s;
    const double dt = t - t_prev;
    const dvec3 p = origin + view * (0.5 * (t + t_prev));
    t_prev = t;
    const Media m = media_at(a, glm::length(p) - kPlanetRadius);
    const dvec3 half = depth + m.extinction * (0.5 * dt);  // to the middle of the step
    depth += m.extinction * dt;
    if (hits_ground(p, sun)) continue;  // in the planet's shadow
    isotropic += (m.rayleigh + dvec3(m.mie)) * glm::exp(-half) * dt;
    const dvec3 light = glm::exp(-(half + optical_depth(a, p, sun, kSunSteps)));
    rayleigh += m.rayleigh * light * dt;
    mie += m.mie * light * dt;
  }
}

// Unit direction at elevation e and azimuth phi measured from the sun's azimuth.
dvec3 direction_from_sun_frame(const dvec3& sun, double elevation, double phi) {
  dvec3 forward(sun.x, 0.0, sun.z);
  const double len = glm::length(forward);
  forward = len > 1.0e-9 ? forward / len : dvec3(0.0, 0.0, -1.0);
  const dvec3 side = glm::cross(dvec3(0.0, 1.0, 0.0), forward);
  const double ce = std::cos(elevation);
  return forward * (ce * std::cos(phi)) + side * (ce * std::sin(phi)) + dvec3(0.0, std::sin(elevation), 0.0);
}

}  // namespace

glm::vec3 atmosphere_transmittance(const AtmosphereSettings& a, float altitude, const glm::vec3& direction) {
  const double h = std::isfinite(altitude) ? std::clamp(static_cast<double>(altitude), 0.0, kAtmosphereRadius - kPlanetRadius) : 0.0;
  const dvec3 p(0.0, kPlanetRadius + h + 1.0, 0.0);
  const dvec3 d = safe_unit(direction, dvec3(0.0, 1.0, 0.0));
  if (hits_ground(p, d)) return glm::vec3(0.0f);
  return glm::vec3(glm::exp(-optical_depth(a, p, d, 64)));
}

float rayleigh_phase(float cos_theta) {
  return static_cast<float>(3.0 / (16.0 * kPi)) * (1.0f + cos_theta * cos_theta);
}

float mie_phase(float cos_theta, float g) {
  const float g2 = g * g;
  const float denom = std::max(1.0f + g2 - 2.0f * g * cos_theta, 1.0e-6f);
  return static_cast<float>(3.0 / (8.0 * kPi)) * ((1.0f - g2) * (1.0f + cos_theta * cos_theta)) /
         ((2.0f + g2) * denom * std::sqrt(denom));
}

SkyTable compute_sky_table(const AtmosphereSettings& a, const glm::vec3& sun_direction, const glm::vec3& sun_top) {
  SkyTable table;
  const dvec3 sun = safe_unit(sun_direction, dvec3(0.0, 1.0, 0.0));
  const glm::vec3 sun_f(sun);
  dvec3 top(0.0);  // non-finite or negative channels count as no light, huge ones are capped
  for (int c = 0; c < 3; ++c) top[c] = std::isfinite(sun_top[c]) ? std::clamp(static_cast<double>(sun_top[c]), 0.0, 1.0e6) : 0.0;
  const dvec3 scale = top * kPi;
  std::array<dvec3, SkyTable::kRows * SkyTable::kCols> isotropic{};
  std::array<double, SkyTable::kRows * SkyTable::kCols> cell_mu{};
  for (int r = 0; r < SkyTable::kRows; ++r) {
    const double u = static_cast<double>(r) / (SkyTable::kRows - 1);
    const double elevation = std::asin(u * u);
    for (int c = 0; c < SkyTable::kCols; ++c) {
      const double phi = std::acos(1.0 - 2.0 * static_cast<double>(c) / (SkyTable::kCols - 1));
      const dvec3 view = direction_from_sun_frame(sun, elevation, phi);
      dvec3 rayleigh, mie;
      const int k = r * SkyTable::kCols + c;
      integrate_view_ray(a, view, sun, rayleigh, mie, isotropic[k]);
      cell_mu[k] = glm::dot(view, sun);
      table.cells[k * 2] = glm::vec4(glm::vec3(rayleigh * scale), 0.0f);
      table.cells[k * 2 + 1] = glm::vec4(glm::vec3(mie * scale), 0.0f);
    }
  }
  // Higher orders (multiple scattering and the ground's bounce), Hillaire 2020 sec. 5.5 in its
  // simplest form: the light field is taken as isotropic with radiance
  // psi = L2 / (1 - f_ms), L2 = the mean single-scattered radiance arriving at the ground level
  // (sky above, sunlit and skylit ground below), f_ms = the share of isotropic light the air
  // scatters again (mean of 1 - transmittance over the sphere, the lower half ~0). Evaluated once
  // at sea level for the whole atmosphere; folded into the Rayleigh column divided by the
  // Rayleigh phase of the cell's own direction, so the shaders need no extra term.
  const glm::vec3 sky_up = sky_table_irradiance(table, a.mie_g, sun_f);
  glm::dvec3 mean_up(0.0), absorbed_up(0.0);
  double weight = 0.0;
  for (int i = 0; i < 8; ++i) {
    const double e = (i + 0.5) / 8.0 * 0.5 * kPi;
    for (int j = 0; j < 16; ++j) {
      const double az = (j + 0.5) / 16.0 * 2.0 * kPi;
      const glm::vec3 dir(static_cast<float>(std::cos(e) * std::sin(az)), static_cast<float>(std::sin(e)),
                          static_cast<float>(-std::cos(e) * std::cos(az)));
      mean_up += dvec3(sky_table_radiance(table, a.mie_g, sun_f, dir)) * std::cos(e);
      if (j == 0) absorbed_up += (dvec3(1.0) - dvec3(atmosphere_transmittance(a, 0.0f, dir))) * std::cos(e) * 16.0;
      weight += std::cos(e);
    }
  }
  mean_up /= weight;
  absorbed_up /= weight;
  const dvec3 sun_at_ground = top * dvec3(atmosphere_transmittance(a, 0.0f, sun_f)) * std::max(sun.y, 0.0);
  const dvec3 ground = std::clamp(static_cast<double>(a.ground_albedo), 0.0, 1.0) * (sun_at_ground + dvec3(sky_up));
  const dvec3 second = 0.5 * (mean_up + ground);
  const dvec3 f_ms = glm::clamp(0.5 * absorbed_up, dvec3(0.0), dvec3(0.9));
  const dvec3 psi = second / (dvec3(1.0) - f_ms);
  for (std::size_t k = 0; k < isotropic.size(); ++k) {
    const double phase = rayleigh_phase(static_cast<float>(cell_mu[k]));
    table.cells[k * 2] += glm::vec4(glm::vec3(isotropic[k] * psi / phase), 0.0f);
  }
  return table;
}

glm::vec3 sky_table_radiance(const SkyTable& table, float mie_g, const glm::vec3& sun_direction, const glm::vec3& direction) {
  // Same steps as sky.glsl: row sqrt(sin elevation), column (1 - cos azimuth) / 2, bilinear.
  glm::vec3 d = glm::normalize(direction);
  const glm::vec3 s = glm::normalize(sun_direction);
  float azimuth_weight = 1.0f;
  if (d.y < 0.0f) {  // below the horizon: the horizon in the same azimuth (phase included)...
    const float h = std::sqrt(d.x * d.x + d.z * d.z);
    const glm::vec3 horizon = h > 1.0e-6f ? glm::vec3(d.x / h, 0.0f, d.z / h) : glm::vec3(0.0f, 0.0f, -1.0f);
    // ...fading out near the nadir, where it is undefined (sky.glsl's atmosphere_radiance).
    const float t = std::clamp(h / SkyTable::kNadirFade, 0.0f, 1.0f);
    azimuth_weight = t * t * (3.0f - 2.0f * t);  // GLSL smoothstep(0, kNadirFade, h)
    d = azimuth_weight < 1.0f ? glm::normalize(glm::mix(d, horizon, azimuth_weight)) : horizon;
  }
  const float row = d.y > 0.0f ? std::sqrt(std::min(d.y, 1.0f)) * (SkyTable::kRows - 1) : 0.0f;
  const glm::vec2 dh(d.x, d.z), sh(s.x, s.z);
  const float lens = glm::length(dh) * glm::length(sh);
  const float cos_phi = (lens > 1.0e-6f ? std::clamp(glm::dot(dh, sh) / lens, -1.0f, 1.0f) : 1.0f) * azimuth_weight;
  const float col = (1.0f - cos_phi) * 0.5f * (SkyTable::kCols - 1);
  const int r0 = std::min(static_cast<int>(row), SkyTable::kRows - 2);
  const int c0 = std::min(static_cast<int>(col), SkyTable::kCols - 2);
  const float fr = std::clamp(row - static_cast<float>(r0), 0.0f, 1.0f);
  const float fc = std::clamp(col - static_cast<float>(c0), 0.0f, 1.0f);
  auto cell = [&](int r, int c, int k) { return glm::vec3(table.cells[(r * SkyTable::kCols + c) * 2 + k]); };
  auto bilinear = [&](int k) {
    const glm::vec3 a = glm::mix(cell(r0, c0, k), cell(r0, c0 + 1, k), fc);
    const glm::vec3 b = glm::mix(cell(r0 + 1, c0, k), cell(r0 + 1, c0 + 1, k), fc);
    return glm::mix(a, b, fr);
  };
  const float mu = glm::dot(d, s);
  return bilinear(0) * rayleigh_phase(mu) + bilinear(1) * mie_phase(mu, mie_g);
}

glm::vec3 sky_table_irradiance(const SkyTable& table, float mie_g, const glm::vec3& sun_direction) {
  // Midpoint rule over elevation x azimuth; the cos * sin(e) weight integrates to pi.
  constexpr int kElevations = 16;
  constexpr int kAzimuths = 32;
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  for (int i = 0; i < kElevations; ++i) {
    const double e = (i + 0.5) / kElevations * 0.5 * kPi;
    const double w = std::sin(e) * std::cos(e);
    for (int j = 0; j < kAzimuths; ++j) {
      const double az = (j + 0.5) / kAzimuths * 2.0 * kPi;
      const glm::vec3 dir(static_cast<float>(std::cos(e) * std::sin(az)), static_cast<float>(std::sin(e)),
                          static_cast<float>(-std::cos(e) * std::cos(az)));
      sum += glm::dvec3(sky_table_radiance(table, mie_g, sun_direction, dir)) * w;
      weight += w;
    }
  }
  // Mean of L cos over the hemisphere = (1/pi) integral L cos d omega.
  return glm::vec3(sum / std::max(weight, 1.0e-12));
}

}  // namespace sylva::render
