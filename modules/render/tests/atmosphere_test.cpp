// The single-scattering atmosphere (atmosphere.hpp) behaves like the sky: air is clearer
// straight up than along the horizon, the sun reddens as it sinks, the sky is bluer at the
// zenith than at the horizon, the table look-up below the horizon is the horizon's haze, the
// ambient it gives is positive and grows with the sun, and nothing is NaN for odd input.
#include <sylva/render/atmosphere.hpp>
#include <sylva/render/lighting.hpp>
#include <sylva/render/sky.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva::render {
namespace {

constexpr float kDeg = 3.14159265f / 180.0f;

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TEST(Atmosphere, TransmittanceZenithAboveHorizon) {
  const AtmosphereSettings a;
  const glm::vec3 up = atmosphere_transmittance(a, 0.0f, {0.0f, 1.0f, 0.0f});
  const glm::vec3 low = atmosphere_transmittance(a, 0.0f, sun_direction(0.0f, 2.0f * kDeg));
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(up[c], low[c]) << c;
    EXPECT_GT(up[c], 0.5f) << c;
    EXPECT_LE(up[c], 1.0f) << c;
  }
  // Blue is scattered most (Rayleigh ~ lambda^-4): the transmitted light is red-weighted.
  EXPECT_GT(up.r, up.b);
  // Hillaire 2020's Earth straight up: ~0.9 red, ~0.6-0.8 blue (Rayleigh + ozone + aerosols).
  EXPECT_NEAR(up.r, 0.93f, 0.05f);
  EXPECT_NEAR(up.b, 0.70f, 0.08f);
  // Higher up there is less air above.
  EXPECT_GT(atmosphere_transmittance(a, 3000.0f, {0.0f, 1.0f, 0.0f}).b, up.b);
  // Into the planet: nothing arrives.
  EXPECT_EQ(atmosphere_transmittance(a, 0.0f, {0.0f, -1.0f, 0.0f}), glm::vec3(0.0f));
}

TEST(Atmosphere, SunReddensAtLowElevation) {
  const AtmosphereSettings a;
  float previous_ratio = 0.0f;
  for (const float elevation_deg : {90.0f, 45.0f, 20.0f, 8.0f, 3.0f, 1.0f}) {
    const glm::vec3 t = atmosphere_transmittance(a, 0.0f, sun_direction(0.3f, elevation_deg * kDeg));
    const float ratio = t.r / std::max(t.b, 1.0e-12f);
    EXPECT_GT(ratio, previous_ratio) << elevation_deg << " deg: red/blue grows as the sun sinks";
    previous_ratio = ratio;
  }
  EXPECT_GT(previous_ratio, 5.0f) << "a sun 1 deg up is orange-red";
}

TEST(Atmosphere, SkyBluerAtZenithThanHorizonAndHazeBelow) {
  const AtmosphereSettings a;
  const glm::vec3 sun = sun_direction(0.0f, 40.0f * kDeg);
  const SkyTable table = compute_sky_table(a, sun, glm::vec3(3.0f));
  const glm::vec3 away{0.0f, 0.0f, 1.0f};  // azimuth opposite the sun
  const glm::vec3 zenith = sky_table_radiance(table, a.mie_g, sun, {0.0f, 1.0f, 0.0f});
  const glm::vec3 horizon = sky_table_radiance(table, a.mie_g, sun, away);
  EXPECT_GT(zenith.b, zenith.g);
  EXPECT_GT(zenith.g, zenith.r);
  EXPECT_GT(zenith.b / zenith.r, horizon.b / horizon.r) << "bluer overhead, whiter at the horizon";
  EXPECT_GT(horizon.g, zenith.g) << "the horizon is brighter (longer path)";
  // Below the horizon: exactly the horizon's haze, never darker (no dark band).
  for (const float y : {-0.01f, -0.2f, -0.7f, -1.0f}) {
    const glm::vec3 below = sky_table_radiance(table, a.mie_g, sun, glm::normalize(glm::vec3(0.0f, y, 1.0f)));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(below[c], horizon[c], 1.0e-4f * horizon[c] + 1.0e-7f) << y;
  }
  // The Mie forward peak: brighter toward the sun than at 90 degrees from it.
  const glm::vec3 near_sun = sky_table_radiance(table, a.mie_g, sun, sun_direction(0.0f, 35.0f * kDeg));
  const glm::vec3 side = sky_table_radiance(table, a.mie_g, sun, sun_direction(1.5707963f, 35.0f * kDeg));
  EXPECT_GT(near_sun.r + near_sun.g + near_sun.b, 2.0f * (side.r + side.g + side.b));
  // Linear in the sun.
  const SkyTable twice = compute_sky_table(a, sun, glm::vec3(6.0f));
  EXPECT_NEAR(sky_table_radiance(twice, a.mie_g, sun, away).g, 2.0f * horizon.g, 1.0e-4f);
}

// Below the horizon the sky is the horizon of the view's azimuth, which is undefined straight
// down: the lake seen from above reflected a wedge of the sun-side horizon's glow pointing at the
// nadir. Near the nadir the azimuth dependence fades out, so directions a degree from it agree
// whatever their azimuth (seen red before: red channel 0.40 .. 3.13 on the ring); near the
// zenith the table's top row is one value for every azimuth already. Away from both (more than
// 30 degrees from the nadir) the value is still exactly the horizon's.
TEST(Atmosphere, NearTheNadirAndTheZenithTheSkyDoesNotDependOnTheAzimuth) {
  const AtmosphereSettings a;
  const glm::vec3 sun = sun_direction(0.3f, 12.0f * kDeg);
  const SkyTable table = compute_sky_table(a, sun, glm::vec3(3.0f));
  for (const float y : {-1.0f, 1.0f}) {
    glm::vec3 lo(1.0e30f), hi(0.0f);
    for (int k = 0; k < 32; ++k) {
      const float az = static_cast<float>(k) / 32.0f * 6.2831853f;
      const glm::vec3 d = glm::normalize(glm::vec3(0.0175f * std::sin(az), y, -0.0175f * std::cos(az)));
      const glm::vec3 v = sky_table_radiance(table, a.mie_g, sun, d);
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    for (int c = 0; c < 3; ++c) EXPECT_LT(hi[c], 1.02f * lo[c]) << "y " << y << " channel " << c << ": " << lo[c] << " .. " << hi[c];
  }
  const glm::vec3 steep = glm::normalize(glm::vec3(0.6f, -0.8f, 0.0f));  // 53 degrees down, 37 from the nadir
  const glm::vec3 horizon = sky_table_radiance(table, a.mie_g, sun, {1.0f, 0.0f, 0.0f});
  EXPECT_EQ(sky_table_radiance(table, a.mie_g, sun, steep), horizon);
}

TEST(Atmosphere, DerivedLightingFollowsTheSun) {
  Lighting high;
  high.sun_direction = sun_direction(0.5f, 60.0f * kDeg);
  Lighting low = high;
  low.sun_direction = sun_direction(0.5f, 3.0f * kDeg);
  // The same sun above the atmosphere: less of it reaches the viewer when low (sun_color is
  // the light at the viewer, as the scene's make_lighting sets it).
  const glm::vec3 t_high = atmosphere_transmittance(high.atmosphere, 0.0f, high.sun_direction);
  const glm::vec3 t_low = atmosphere_transmittance(high.atmosphere, 0.0f, low.sun_direction);
  low.sun_color = high.sun_color * t_low / t_high;
  derive_sky_lighting(high);
  derive_sky_lighting(low);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(high.ambient[c], 0.0f);
    EXPECT_GT(high.ground_color[c], 0.0f);
    EXPECT_GT(high.ambient[c], low.ambient[c]) << "more sky light with a high sun";
  }
  EXPECT_EQ(high.fog_color, high.horizon_color);
  EXPECT_GT(high.zenith_color.b, high.zenith_color.r);
  // Sky light is a modest share of the sun's (clear sky: ~10-25 % on a horizontal face).
  const float sun_on_ground = 3.0f * 0.95f * std::sin(60.0f * kDeg);
  EXPECT_GT(high.ambient.g, 0.03f * sun_on_ground);
  EXPECT_LT(high.ambient.g, 0.5f * sun_on_ground);
  // CPU twin entry points agree with the table they wrap.
  const glm::vec3 d = glm::normalize(glm::vec3(0.3f, 0.4f, -0.2f));
  EXPECT_EQ(sky_radiance(high, d), sky_table_radiance(sky_table(high), high.atmosphere.mie_g,
                                                      glm::normalize(high.sun_direction), d));
  // Scaled ambient.
  Lighting half = high;
  derive_sky_lighting(half, 0.5f);
  EXPECT_NEAR(half.ambient.g, 0.5f * high.ambient.g, 1.0e-6f);
}

TEST(Atmosphere, OddInputStaysFinite) {
  const AtmosphereSettings a;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(finite3(atmosphere_transmittance(a, nan, {0.0f, 1.0f, 0.0f})));
  EXPECT_TRUE(finite3(atmosphere_transmittance(a, 1.0e9f, {nan, 0.0f, 0.0f})));
  EXPECT_TRUE(finite3(atmosphere_transmittance(a, -5.0f, {0.0f, 0.0f, 0.0f})));
  for (const glm::vec3& sun : {glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.0f, -1.0f, 0.0f), glm::vec3(0.0f),
                               glm::vec3(1.0f, -0.05f, 0.0f)}) {
    const SkyTable t = compute_sky_table(a, sun, glm::vec3(3.0f, inf, -1.0f));
    for (const glm::vec4& cell : t.cells) ASSERT_TRUE(finite3(glm::vec3(cell)));
    EXPECT_TRUE(finite3(sky_table_irradiance(t, a.mie_g, glm::vec3(0.0f, 1.0f, 0.0f))));
  }
  Lighting night;
  night.sun_direction = {0.0f, -1.0f, 0.0f};
  derive_sky_lighting(night);
  EXPECT_TRUE(finite3(night.ambient) && finite3(night.horizon_color) && finite3(night.ground_color));
}

}  // namespace
}  // namespace sylva::render
