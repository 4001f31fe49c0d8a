// Wind field: the directional part, gusts travelling downwind, turbulence advected with the
// wind, documented bounds, continuity in space and time, the per-frame split and settings.
#include <sylva/core/params.hpp>
#include <sylva/core/rng.hpp>
#include <sylva/core/wind.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace sylva {
namespace {

WindSettings calm_settings() {
  WindSettings s;
  s.strength = 0.0f;
  s.gust_amplitude = 0.0f;
  s.turbulence_amplitude = 0.0f;
  return s;
}

// Slope bound of the scaled gradient noise per lattice unit (noise_test measures ~2.6).
constexpr double kNoiseSlope = 4.0;

// Upper bound of |dv/dt| for the settings: gusts change at most 0.5 A_g * slope / T (plus the
// downwind travel, which does not depend on t); turbulence moves through the field at
// |d strength + (0, evolution, 0)| and every fBm octave k adds 2^k slope with weight 2^-k / norm.
double time_rate_bound(const WindSettings& s) {
  double norm = 0.0;
  double slope = 0.0;
  for (int k = 0; k < s.turbulence_octaves; ++k) {
    norm += std::pow(0.5, k);
    slope += 1.0;
  }
  const double fbm_slope = kNoiseSlope * slope / norm;
  const double advect = std::hypot(static_cast<double>(s.strength), static_cast<double>(s.turbulence_evolution));
  const double turb = s.turbulence_amplitude * std::sqrt(2.0 + s.turbulence_vertical * s.turbulence_vertical) *
                      fbm_slope * advect / s.turbulence_scale;
  return 0.5 * s.gust_amplitude * kNoiseSlope / s.gust_period + turb;
}

double space_rate_bound(const WindSettings& s) {
  double norm = 0.0;
  double slope = 0.0;
  for (int k = 0; k < s.turbulence_octaves; ++k) {
    norm += std::pow(0.5, k);
    slope += 1.0;
  }
  const double c = std::max(1.0, static_cast<double>(s.strength));
  return 0.5 * s.gust_amplitude * kNoiseSlope / (c * s.gust_period) +
         s.turbulence_amplitude * std::sqrt(2.0 + s.turbulence_vertical * s.turbulence_vertical) * kNoiseSlope *
             slope / norm / s.turbulence_scale;
}

TEST(Wind, SteadyWindIsExactlyTheDirectionTimesStrength) {
  WindSettings s = calm_settings();
  s.strength = 7.5f;
  s.direction_deg = 90.0f;  // towards +z
  const WindField wind(s);
  Pcg32 rng(1u);
  for (int i = 0; i < 200; ++i) {
    const glm::vec3 p(rng.uniform(-500.0f, 500.0f), rng.uniform(0.0f, 50.0f), rng.uniform(-500.0f, 500.0f));
    const glm::vec3 v = wind.evaluate(p, rng.uniform(0.0f, 1000.0f));
    EXPECT_NEAR(v.x, 0.0f, 1e-5f);
    EXPECT_EQ(v.y, 0.0f);
    EXPECT_FLOAT_EQ(v.z, 7.5f);
  }
  EXPECT_NEAR(glm::length(wind.direction()), 1.0f, 1e-6f);
  WindSettings west = s;
  west.direction_deg = 180.0f;
  EXPECT_NEAR(WindField(west).evaluate(glm::vec3(1, 2, 3), 4.0).x, -7.5f, 1e-5f);
}

TEST(Wind, GustsStayInTheirBandAndUseIt) {
  WindSettings s = calm_settings();
  s.strength = 4.0f;
  s.gust_amplitude = 6.0f;
  s.gust_period = 5.0f;
  const WindField wind(s);
  float lo = 1e9f;
  float hi = -1e9f;
  double sum = 0.0;
  constexpr int kN = 20000;
  for (int i = 0; i < kN; ++i) {
    const double t = i * 0.37;
    const glm::vec3 v = wind.evaluate(glm::vec3(3.0f, 1.0f, -2.0f), t);
    EXPECT_NEAR(v.z, 0.0f, 1e-5f);
    lo = std::min(lo, v.x);
    hi = std::max(hi, v.x);
    sum += v.x;
  }
  EXPECT_GE(lo, 4.0f);
  EXPECT_LE(hi, 10.0f);
  EXPECT_GT(hi - lo, 3.0f) << "gusts barely vary";
  EXPECT_NEAR(sum / kN, 4.0 + 0.5 * 6.0, 0.4) << "mean of the gust band";
}

TEST(Wind, GustFrontsTravelDownwind) {
  // With turbulence off, v(p + d c tau, t + tau) = v(p, t), c = max(strength, 1).
  WindSettings s = calm_settings();
  s.strength = 6.0f;
  s.gust_amplitude = 3.0f;
  s.direction_deg = 30.0f;
  const WindField wind(s);
  const glm::vec3 d = wind.direction();
  for (int i = 0; i < 50; ++i) {
    const glm::vec3 p(i * 1.7f, 0.0f, -i * 0.9f);
    const double t = 10.0 + i * 0.61;
    const float tau = 2.5f;
    const glm::vec3 a = wind.evaluate(p, t);
    const glm::vec3 b = wind.evaluate(p + d * (6.0f * tau), t + tau);
    EXPECT_NEAR(glm::length(a - b), 0.0f, 1e-4f) << i;
  }
  // And the gust is not uniform in space: two points 20 m apart downwind differ at some time.
  float max_diff = 0.0f;
  for (int i = 0; i < 100; ++i) {
    max_diff = std::max(max_diff, glm::length(wind.evaluate(glm::vec3(0.0f), i * 0.5) -
                                              wind.evaluate(d * 20.0f, i * 0.5)));
  }
  EXPECT_GT(max_diff, 0.3f);
}

TEST(Wind, TurbulenceIsAdvectedWithTheMeanWind) {
  WindSettings s = calm_settings();
  s.strength = 5.0f;
  s.turbulence_amplitude = 2.0f;
  s.turbulence_evolution = 0.0f;
  s.direction_deg = -45.0f;
  const WindField wind(s);
  const glm::vec3 d = wind.direction();
  for (int i = 0; i < 50; ++i) {
    const glm::vec3 p(i * 0.7f, 1.0f + i * 0.1f, i * -1.3f);
    const double t = 3.0 + i * 0.25;
    const float tau = 1.5f;
    EXPECT_NEAR(glm::length(wind.evaluate(p, t) - wind.evaluate(p + d * (5.0f * tau), t + tau)), 0.0f, 1e-4f) << i;
  }
}

TEST(Wind, CalmAirStillMovesThroughEvolution) {
  WindSettings s = calm_settings();
  s.turbulence_amplitude = 1.0f;
  s.turbulence_evolution = 0.5f;
  const WindField wind(s);
  const glm::vec3 p(1.0f, 2.0f, 3.0f);
  float change = 0.0f;
  for (int i = 1; i < 50; ++i) change = std::max(change, glm::length(wind.evaluate(p, i * 1.0) - wind.evaluate(p, 0.0)));
  EXPECT_GT(change, 0.2f);
  // Without evolution and without mean wind the field is frozen.
  s.turbulence_evolution = 0.0f;
  const WindField frozen(s);
  EXPECT_EQ(frozen.evaluate(p, 0.0), frozen.evaluate(p, 123.0));
}

TEST(Wind, StaysWithinTheDocumentedBound) {
  WindSettings s;
  s.strength = 8.0f;
  s.gust_amplitude = 5.0f;
  s.turbulence_amplitude = 3.0f;
  s.turbulence_vertical = 0.5f;
  s.turbulence_octaves = 3;
  const WindField wind(s);
  const float bound = s.gust_amplitude + s.turbulence_amplitude * std::sqrt(2.0f + 0.25f);
  EXPECT_FLOAT_EQ(wind.max_speed(), s.strength + bound);
  Pcg32 rng(5u);
  float worst = 0.0f;
  float worst_vertical = 0.0f;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 p(rng.uniform(-1000.0f, 1000.0f), rng.uniform(0.0f, 100.0f), rng.uniform(-1000.0f, 1000.0f));
    const glm::vec3 v = wind.evaluate(p, rng.uniform(0.0f, 1e4f));
    worst = std::max(worst, glm::length(v - wind.direction() * s.strength));
    worst_vertical = std::max(worst_vertical, std::abs(v.y));
  }
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.5f * bound) << "the bound should not be vacuous";
  EXPECT_LE(worst_vertical, s.turbulence_amplitude * s.turbulence_vertical);
}

TEST(Wind, IsContinuousInTimeAndSpace) {
  WindSettings s;
  s.strength = 6.0f;
  s.gust_amplitude = 4.0f;
  s.gust_period = 3.0f;
  s.turbulence_amplitude = 2.0f;
  s.turbulence_scale = 4.0f;
  const WindField wind(s);
  const double dt = 1e-3;
  const float dx = 1e-2f;
  double worst_t = 0.0;
  double worst_x = 0.0;
  Pcg32 rng(6u);
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 p(rng.uniform(-100.0f, 100.0f), rng.uniform(0.0f, 20.0f), rng.uniform(-100.0f, 100.0f));
    const double t = rng.uniform(0.0f, 500.0f);
    const glm::vec3 v = wind.evaluate(p, t);
    worst_t = std::max(worst_t, static_cast<double>(glm::length(wind.evaluate(p, t + dt) - v)) / dt);
    glm::vec3 dir(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
    dir = glm::normalize(dir) * dx;
    worst_x = std::max(worst_x, static_cast<double>(glm::length(wind.evaluate(p + dir, t) - v)) / dx);
  }
  EXPECT_LT(worst_t, time_rate_bound(s)) << "wind jumps in time";
  EXPECT_LT(worst_x, space_rate_bound(s)) << "wind jumps in space";
  RecordProperty("max_dv_dt", std::to_string(worst_t));
  RecordProperty("max_dv_dx", std::to_string(worst_x));
}

TEST(Wind, IsDeterministicAndSeedsDiffer) {
  WindSettings s;
  const WindField a(s);
  const WindField b(s);
  s.seed = 2;
  const WindField c(s);
  float diff = 0.0f;
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 p(i * 1.3f, 0.5f, i * -0.7f);
    EXPECT_EQ(a.evaluate(p, i * 0.1), b.evaluate(p, i * 0.1));
    diff = std::max(diff, glm::length(a.evaluate(p, i * 0.1) - c.evaluate(p, i * 0.1)));
  }
  EXPECT_GT(diff, 0.3f);
}

TEST(Wind, FrameSplitMatchesDirectEvaluation) {
  // Camera-relative evaluation: origin (double) + local (float) equals the world evaluation.
  WindSettings s;
  s.strength = 9.0f;
  s.gust_amplitude = 4.0f;
  s.turbulence_amplitude = 2.5f;
  const WindField wind(s);
  Pcg32 rng(7u);
  for (int i = 0; i < 500; ++i) {
    const glm::dvec3 origin(rng.uniform(-1e5f, 1e5f), rng.uniform(0.0f, 100.0f), rng.uniform(-1e5f, 1e5f));
    const double t = rng.uniform(0.0f, 1e5f);
    const WindFrame frame = wind.frame(t, origin);
    const glm::vec3 local(rng.uniform(-50.0f, 50.0f), rng.uniform(-5.0f, 5.0f), rng.uniform(-50.0f, 50.0f));
    const glm::vec3 split = WindField::evaluate(frame, local);
    const glm::vec3 direct = wind.evaluate(origin + glm::dvec3(local), t);
    EXPECT_LT(glm::length(split - direct), 2e-3f) << i;
  }
}

TEST(Wind, SettingsAreReflectedAndValidated) {
  WindSettings s;
  EXPECT_EQ(describe_params(s).size(), 10u);
  EXPECT_TRUE(WindField::validate(s).ok());
  s.strength = -1.0f;
  const Status bad = WindField::validate(s);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("wind.strength"), std::string::npos) << bad.error().message;
  // The field itself clamps, so it still works.
  EXPECT_EQ(WindField(s).settings().strength, 0.0f);
  WindSettings t;
  EXPECT_TRUE(set_param(t, "gust_period", "20").ok());
  EXPECT_EQ(t.gust_period, 20.0f);
  EXPECT_FALSE(set_param(t, "turbulence_octaves", "9").ok());
}

}  // namespace
}  // namespace sylva
