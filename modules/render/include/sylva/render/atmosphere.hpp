#pragma once
// A clear-sky atmosphere over a spherical planet (issue 19): single scattering by air molecules
// (Rayleigh), aerosols (Mie, Cornette-Shanks phase) and absorption by ozone, as in Bruneton &
// Neyret 2008, "Precomputed Atmospheric Scattering", and Hillaire 2020, "A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique" (whose Earth coefficients are the
// defaults). GL-free.
//
// The sky is precomputed on the CPU into a SkyTable (16 view elevations x 5 azimuths from the
// sun, the Rayleigh and Mie in-scattering integrals without their phase functions, in the
// units the shaders light with) whenever the sun changes; shaders look it up per pixel and
// apply the phase functions exactly (render/lib/sky.glsl), so the Mie glow around the sun stays
// sharp although the table is coarse. Below the horizon the table's horizon row is used: the
// sky's lower half is the atmosphere's own haze colour, never a dark band.
//
// Units: lengths in metres, coefficients per metre, colours linear RGB (~680, 550, 440 nm).
// "Engine radiance": a white Lambertian surface facing a sun of radiance S shades to S (the
// modules' shading has no 1/pi), so the sky radiance is pi * S_top * integral and the ambient
// light of a surface is the cosine-weighted mean of the sky radiance over its hemisphere.

#include <sylva/core/params.hpp>

#include <glm/glm.hpp>

#include <array>

namespace sylva::render {

struct AtmosphereSettings {
  glm::vec3 rayleigh_scattering{5.802e-6f, 13.558e-6f, 33.1e-6f};  // [1/m] at sea level
  float rayleigh_scale_height = 8000.0f;                            // [m]
  float mie_scattering = 3.996e-6f;                                 // [1/m] at sea level
  float mie_absorption = 0.444e-6f;                                 // [1/m] at sea level
  float mie_scale_height = 1200.0f;                                 // [m]
  float mie_g = 0.8f;                                               // phase asymmetry, (-1, 1)
  glm::vec3 ozone_absorption{0.650e-6f, 1.881e-6f, 0.085e-6f};      // [1/m] at the layer's peak (25 km)
  float ground_albedo = 0.3f;  // light bounced up by the ground (ambient of downward faces)

  template <class V>
  void visit(V& v) {
    v(rayleigh_scattering, "rayleigh_scattering", {.min = 0.0, .max = 1.0e-3, .unit = "1/m", .help = "Air scattering at sea level (R, G, B)"});
    v(rayleigh_scale_height, "rayleigh_scale_height", {.min = 100.0, .max = 1.0e5, .unit = "m", .help = "Air density scale height"});
    v(mie_scattering, "mie_scattering", {.min = 0.0, .max = 1.0e-2, .unit = "1/m", .help = "Aerosol (haze) scattering at sea level", .log_scale = true});
    v(mie_absorption, "mie_absorption", {.min = 0.0, .max = 1.0e-2, .unit = "1/m", .help = "Aerosol absorption at sea level"});
    v(mie_scale_height, "mie_scale_height", {.min = 10.0, .max = 1.0e5, .unit = "m", .help = "Aerosol scale height"});
    v(mie_g, "mie_g", {.min = -0.99, .max = 0.99, .help = "Aerosol forward scattering (glow around the sun)"});
    v(ozone_absorption, "ozone_absorption", {.min = 0.0, .max = 1.0e-4, .unit = "1/m", .help = "Ozone absorption at its peak (R, G, B)"});
    v(ground_albedo, "ground_albedo", {.min = 0.0, .max = 1.0, .help = "Ground reflectance for bounce light"});
  }
};

// Transmittance from a point `altitude` metres above sea level along the unit `direction`
// (world, y up) to the top of the atmosphere, per channel in [0, 1]; 0 when the ray hits the
// planet. Numerically integrated (64 steps); finite for any finite input.
glm::vec3 atmosphere_transmittance(const AtmosphereSettings& a, float altitude, const glm::vec3& direction);

// Phase functions [1/sr] of the cosine between the view and the sun directions.
float rayleigh_phase(float cos_theta);
float mie_phase(float cos_theta, float g);  // Cornette-Shanks

// The precomputed sky for one sun (see the header comment). Cell (row, col): row r views at
// sin(elevation) = (r / (kRows - 1))^2 (denser near the horizon), column c at the azimuth phi
// from the sun's azimuth with (1 - cos phi) / 2 = c / (kCols - 1) (0, 60, 90, 120, 180 deg):
// shaders find the cell without inverse trigonometry. Each cell holds two vec4: Rayleigh rgb
// and Mie rgb in-scattering, already multiplied by pi * sun_top (w unused).
struct SkyTable {
  static constexpr int kRows = 16;
  static constexpr int kCols = 5;
  // Below the horizon the look-up is the horizon's in the view's azimuth, undefined straight
  // down: for horizontal lengths of the view direction under this (30 degrees from the nadir)
  // the azimuth fades out (sky.glsl's SYLVA_SKY_NADIR_FADE).
  static constexpr float kNadirFade = 0.5f;
  std::array<glm::vec4, kRows * kCols * 2> cells{};
};

// Integrates the table for a viewer at sea level (64 quadratic steps per view ray, 24 per
// sun ray), then adds the higher scattering orders and the ground's bounce as one isotropic
// term (Hillaire 2020 sec. 5.5, evaluated at sea level). sun_direction: toward the sun (made
// unit; zero -> straight up; may be below the horizon: the planet's shadow is taken into
// account); sun_top: the sun's engine radiance above the atmosphere (negative or non-finite
// channels count as 0, capped at 1e6).
SkyTable compute_sky_table(const AtmosphereSettings& a, const glm::vec3& sun_direction, const glm::vec3& sun_top);

// CPU twin of sky.glsl's atmosphere_radiance(): bilinear table look-up plus the phase
// functions, for a unit view direction (below the horizon: the horizon's value; within 30
// degrees of the nadir blended toward an azimuth-free value, continuous at the nadir).
glm::vec3 sky_table_radiance(const SkyTable& table, float mie_g, const glm::vec3& sun_direction, const glm::vec3& direction);

// Ambient light of an upward-facing surface: (1/pi) * integral of the sky radiance * cos over
// the upper hemisphere (engine units, see the header comment).
glm::vec3 sky_table_irradiance(const SkyTable& table, float mie_g, const glm::vec3& sun_direction);

}  // namespace sylva::render
