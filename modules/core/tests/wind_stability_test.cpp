// Wind under extreme inputs. Invariants checked (one per test):
//  - NoNanForAnyInput: finite velocity for NaN/Inf/huge positions and times.
//  - LongRunsStaySmooth: at t = 1e7 s and 1e6 m the wind changes between 60 Hz frames no more
//    than at t = 0 (no float stair-steps) and still varies (no freeze), thanks to the double split.
//  - HurricaneStaysBounded: 100 m/s wind with 100 m/s gusts and turbulence, tiny eddies and
//    short gust periods stays within max_speed and finite.
//  - OutOfRangeSettingsAreClamped: NaN, negative and zero settings give a working field.
//  - ContinuousAcrossPhaseWrap: crossing the noise period (65536 cells) in the gust phase and in
//    the turbulence offset does not jump.
//  - TimeStepsFromZeroToOneSecond: the change over a step dt is bounded by rate * dt for dt in
//    {0, 1e-4, 1/60, 0.1, 1} s.
#include <sylva/core/rng.hpp>
#include <sylva/core/wind.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace sylva {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

WindSettings lively() {
  WindSettings s;
  s.strength = 8.0f;
  s.gust_amplitude = 5.0f;
  s.gust_period = 4.0f;
  s.turbulence_amplitude = 2.0f;
  s.turbulence_scale = 3.0f;
  return s;
}

// Largest and mean frame-to-frame change at 60 Hz over 10 s starting at t0, at position p.
struct Steps {
  double max = 0.0;
  double mean = 0.0;
};
Steps frame_steps(const WindField& wind, glm::dvec3 p, double t0) {
  Steps s;
  glm::vec3 prev = wind.evaluate(p, t0);
  for (int i = 1; i <= 600; ++i) {
    const glm::vec3 v = wind.evaluate(p, t0 + i / 60.0);
    const double d = glm::length(v - prev);
    s.max = std::max(s.max, d);
    s.mean += d / 600.0;
    prev = v;
  }
  return s;
}

TEST(WindStability, NoNanForAnyInput) {
  const WindField wind(lively());
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> coords = {0.0f, -1e6f, 1e6f, 3e9f, -1e30f, std::numeric_limits<float>::max(), inf, -inf, nan};
  const std::vector<double> times = {0.0, -1.0, 1e-9, 1e7, 1e12, -1e300, std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::quiet_NaN()};
  for (float x : coords) {
    for (float z : coords) {
      for (double t : times) {
        ASSERT_TRUE(finite(wind.evaluate(glm::vec3(x, 1.0f, z), t))) << x << ", " << z << " at " << t;
        ASSERT_TRUE(finite(wind.evaluate(glm::dvec3(x, 1.0, z), t))) << x << ", " << z << " at " << t;
        const WindFrame f = wind.frame(t, glm::dvec3(x, 0.0, z));
        ASSERT_TRUE(finite(WindField::evaluate(f, glm::vec3(z, x, 2.0f)))) << x << ", " << z << " at " << t;
      }
    }
  }
}

TEST(WindStability, LongRunsStaySmooth) {
  const WindField wind(lively());
  const Steps early = frame_steps(wind, {10.0, 1.0, 20.0}, 0.0);
  const Steps late = frame_steps(wind, {10.0, 1.0, 20.0}, 1e7);
  const Steps far = frame_steps(wind, {1e6, 1.0, -1e6}, 1e7);
  // Float stair-steps would show as a max step far above the mean; a freeze as a zero mean.
  for (const Steps& s : {early, late, far}) {
    EXPECT_GT(s.mean, 0.01);
    EXPECT_LT(s.max, 6.0 * s.mean + 0.05);
  }
  EXPECT_LT(late.max, 3.0 * early.max + 0.05);
  EXPECT_LT(far.max, 3.0 * early.max + 0.05);
  RecordProperty("frame_step_t0_max_mean", std::to_string(early.max) + " " + std::to_string(early.mean));
  RecordProperty("frame_step_t1e7_max_mean", std::to_string(late.max) + " " + std::to_string(late.mean));
  RecordProperty("frame_step_1e6m_t1e7_max_mean", std::to_string(far.max) + " " + std::to_string(far.mean));

  // The float position overload at 1e6 m agrees with the double one to the float rounding of the
  // position (1/16 m there), far below the turbulence scale of 3 m.
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 p(1e6f + i * 0.5f, 2.0f, -1e6f);
    EXPECT_LT(glm::length(wind.evaluate(p, 1e7 + i) - wind.evaluate(glm::dvec3(p), 1e7 + i)), 1e-3f);
  }
}

TEST(WindStability, HurricaneStaysBounded) {
  WindSettings s;
  s.strength = 100.0f;
  s.gust_amplitude = 100.0f;
  s.gust_period = 0.1f;
  s.turbulence_amplitude = 100.0f;
  s.turbulence_scale = 0.05f;
  s.turbulence_evolution = 100.0f;
  s.turbulence_vertical = 1.0f;
  s.turbulence_octaves = 4;
  const WindField wind(s);
  Pcg32 rng(2u);
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 p(rng.uniform(-1e4f, 1e4f), rng.uniform(-10.0f, 500.0f), rng.uniform(-1e4f, 1e4f));
    const glm::vec3 v = wind.evaluate(p, rng.next_double() * 1e7);
    ASSERT_TRUE(finite(v));
    ASSERT_LE(glm::length(v), wind.max_speed() * 1.0001f);
  }
}

TEST(WindStability, OutOfRangeSettingsAreClamped) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::vector<WindSettings> cases(6);
  cases[0].strength = nan;
  cases[0].direction_deg = nan;
  cases[1].gust_period = 0.0f;
  cases[1].turbulence_scale = 0.0f;
  cases[2].gust_period = -5.0f;
  cases[2].turbulence_scale = -1.0f;
  cases[2].turbulence_octaves = -3;
  cases[3].strength = 1e30f;
  cases[3].gust_amplitude = std::numeric_limits<float>::infinity();
  cases[4].turbulence_octaves = 100;
  cases[4].turbulence_vertical = 50.0f;
  cases[5].direction_deg = 1e20f;
  for (std::size_t c = 0; c < cases.size(); ++c) {
    EXPECT_FALSE(WindField::validate(cases[c]).ok()) << "case " << c << " should be reported";
    const WindField wind(cases[c]);
    EXPECT_TRUE(WindField::validate(wind.settings()).ok()) << "case " << c << " not clamped into range";
    for (int i = 0; i < 200; ++i) {
      const glm::vec3 v = wind.evaluate(glm::vec3(i * 0.3f, 1.0f, -i * 0.2f), i * 0.05);
      ASSERT_TRUE(finite(v)) << "case " << c;
      ASSERT_LE(glm::length(v), wind.max_speed() * 1.0001f) << "case " << c;
    }
  }
}

TEST(WindStability, ContinuousAcrossPhaseWrap) {
  // Gust phase s = t / T reaches the noise period 65536 at t = 65536 T.
  WindSettings s = lively();
  s.turbulence_amplitude = 0.0f;
  s.gust_period = 0.5f;
  const WindField gusts(s);
  const double t_wrap = 65536.0 * 0.5;
  const glm::vec3 before = gusts.evaluate(glm::vec3(0.0f), t_wrap - 1e-3);
  const glm::vec3 at = gusts.evaluate(glm::vec3(0.0f), t_wrap);
  const glm::vec3 after = gusts.evaluate(glm::vec3(0.0f), t_wrap + 1e-3);
  EXPECT_LT(glm::length(at - before), 0.02f);
  EXPECT_LT(glm::length(after - at), 0.02f);

  // Turbulence offset (p - d strength t) / scale crosses 65536 cells at t = 65536 scale / strength.
  WindSettings u = lively();
  u.gust_amplitude = 0.0f;
  u.turbulence_evolution = 0.0f;
  u.direction_deg = 180.0f;  // offset grows in +x
  const WindField turb(u);
  const double t_cross = 65536.0 * u.turbulence_scale / u.strength;
  const glm::vec3 b = turb.evaluate(glm::vec3(0.0f, 1.0f, 0.0f), t_cross - 1e-3);
  const glm::vec3 a = turb.evaluate(glm::vec3(0.0f, 1.0f, 0.0f), t_cross + 1e-3);
  EXPECT_LT(glm::length(a - b), 0.05f);
}

TEST(WindStability, TimeStepsFromZeroToOneSecond) {
  const WindField wind(lively());
  Pcg32 rng(4u);
  for (double dt : {0.0, 1e-4, 1.0 / 60.0, 0.1, 1.0}) {
    double worst = 0.0;
    for (int i = 0; i < 2000; ++i) {
      const glm::vec3 p(rng.uniform(-200.0f, 200.0f), rng.uniform(0.0f, 30.0f), rng.uniform(-200.0f, 200.0f));
      const double t = rng.next_double() * 1e4;
      worst = std::max(worst, static_cast<double>(glm::length(wind.evaluate(p, t + dt) - wind.evaluate(p, t))));
    }
    if (dt == 0.0) {
      EXPECT_EQ(worst, 0.0) << "dt = 0 must not change the wind";
    } else {
      // Never more than the full range of the variable part, and small for small steps.
      EXPECT_LE(worst, 2.0 * (wind.max_speed() - wind.settings().strength)) << "dt = " << dt;
      if (dt <= 1e-4) {
        EXPECT_LT(worst, 0.05) << "dt = " << dt;
      }
    }
  }
}

}  // namespace
}  // namespace sylva
