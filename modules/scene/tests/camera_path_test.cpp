// Camera paths: interpolation through the keys, C1 continuity of Catmull-Rom, yaw unwrapping,
// looping and clamping; and the solar position of the environment.
#include <sylva/scene/camera_path.hpp>
#include <sylva/scene/environment.hpp>

#include <gtest/gtest.h>

#include <cmath>

using namespace sylva::scene;

namespace {

CameraKey key(double t, glm::dvec3 p, float yaw = 0.0f, float pitch = 0.0f, float fov = 60.0f) {
  CameraKey k;
  k.time_s = t;
  k.view.position = p;
  k.view.yaw_deg = yaw;
  k.view.pitch_deg = pitch;
  k.view.fov_deg = fov;
  return k;
}

CameraPath path(PathInterpolation interpolation, std::vector<CameraKey> keys, bool loop = false) {
  CameraPath p;
  p.settings.interpolation = interpolation;
  p.settings.loop = loop;
  p.keys = std::move(keys);
  return p;
}

}  // namespace

TEST(CameraPath, PassesThroughEveryKey) {
  for (PathInterpolation mode : {PathInterpolation::kLinear, PathInterpolation::kCatmullRom}) {
    const CameraPath p = path(mode, {key(0, {0, 1, 0}, 10), key(1, {5, 2, 0}, 40, -10), key(3, {5, 2, 9}, 80, 5, 40),
                                     key(4, {-3, 0, 1}, 100)});
    ASSERT_TRUE(p.validate("p").ok());
    for (const CameraKey& k : p.keys) {
      const CameraView v = p.evaluate(k.time_s);
      EXPECT_NEAR(glm::distance(v.position, k.view.position), 0.0, 1e-9);
      EXPECT_NEAR(v.yaw_deg, k.view.yaw_deg, 1e-4);
      EXPECT_NEAR(v.pitch_deg, k.view.pitch_deg, 1e-4);
      EXPECT_NEAR(v.fov_deg, k.view.fov_deg, 1e-4);
    }
  }
}

TEST(CameraPath, LinearIsLinearAndEndsClamp) {
  const CameraPath p = path(PathInterpolation::kLinear, {key(0, {0, 0, 0}, 0, 0, 40), key(2, {10, 4, -2}, 20, 10, 80)});
  const CameraView mid = p.evaluate(0.5);
  EXPECT_NEAR(mid.position.x, 2.5, 1e-12);
  EXPECT_NEAR(mid.position.y, 1.0, 1e-12);
  EXPECT_NEAR(mid.yaw_deg, 5.0f, 1e-5);
  EXPECT_NEAR(mid.fov_deg, 50.0f, 1e-5);
  EXPECT_EQ(p.evaluate(-5).position, glm::dvec3(0, 0, 0));
  EXPECT_EQ(p.evaluate(99).position, glm::dvec3(10, 4, -2));
  EXPECT_EQ(p.evaluate(std::nan("")).position, glm::dvec3(0, 0, 0));
}

TEST(CameraPath, CatmullRomIsC1AtKeysEvenWithUnevenTimes) {
  const CameraPath p = path(PathInterpolation::kCatmullRom,
                            {key(0, {0, 0, 0}), key(1, {4, 1, 0}), key(4, {6, 3, 8}), key(4.5, {0, 0, 9}), key(9, {-5, 2, 0})});
  const double h = 1e-5;
  for (std::size_t i = 1; i + 1 < p.keys.size(); ++i) {
    const double t = p.keys[i].time_s;
    const glm::dvec3 left = (p.evaluate(t).position - p.evaluate(t - h).position) / h;
    const glm::dvec3 right = (p.evaluate(t + h).position - p.evaluate(t).position) / h;
    EXPECT_LT(glm::length(left - right), 1e-3 * (1.0 + glm::length(left))) << "velocity jumps at key " << i;
  }
  // Positions change continuously everywhere (no jumps between samples).
  glm::dvec3 prev = p.evaluate(0).position;
  for (double t = 0.01; t <= 9.0; t += 0.01) {
    const glm::dvec3 cur = p.evaluate(t).position;
    EXPECT_LT(glm::distance(cur, prev), 0.5) << t;
    prev = cur;
  }
}

TEST(CameraPath, YawTurnsTheShortWay) {
  EXPECT_FLOAT_EQ(unwrap_degrees(-170.0f, 170.0f), 190.0f);
  EXPECT_FLOAT_EQ(unwrap_degrees(350.0f, 0.0f), -10.0f);
  const CameraPath p = path(PathInterpolation::kLinear, {key(0, {0, 0, 0}, 170), key(1, {0, 0, 0}, -170)});
  const CameraView mid = p.evaluate(0.5);
  EXPECT_NEAR(std::fabs(mid.yaw_deg), 180.0f, 1e-3) << "170 -> -170 passes through 180, not 0";
}

TEST(CameraPath, LoopWrapsTime) {
  const CameraPath p = path(PathInterpolation::kCatmullRom,
                            {key(0, {0, 0, 0}), key(1, {1, 0, 0}), key(2, {1, 0, 1}), key(3, {0, 0, 0})}, true);
  EXPECT_NEAR(glm::distance(p.evaluate(1.25).position, p.evaluate(4.25).position), 0.0, 1e-9);
  EXPECT_NEAR(glm::distance(p.evaluate(-0.75).position, p.evaluate(2.25).position), 0.0, 1e-9);
  // Smooth through the seam: velocity just before the end equals velocity just after the start.
  const double h = 1e-5;
  const glm::dvec3 v_end = (p.evaluate(3.0 - h).position - p.evaluate(3.0 - 2 * h).position) / h;
  const glm::dvec3 v_start = (p.evaluate(2 * h).position - p.evaluate(h).position) / h;
  EXPECT_LT(glm::length(v_end - v_start), 1e-3);
}

TEST(CameraPath, OvershootIsClampedAndValidationNamesTheKey) {
  const CameraPath p = path(PathInterpolation::kCatmullRom, {key(0, {0, 0, 0}, 0, 0), key(0.1, {0, 0, 0}, 0, 89.9f),
                                                             key(10, {0, 0, 0}, 0, 89.9f)});
  for (double t = 0; t < 10; t += 0.05) EXPECT_LE(p.evaluate(t).pitch_deg, 89.9f);
  CameraPath bad = path(PathInterpolation::kLinear, {key(0, {0, 0, 0}), key(0, {1, 0, 0})});
  auto s = bad.validate("camera_paths.x");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("camera_paths.x.keys[1].time_s"), std::string::npos) << s.error().message;
  EXPECT_FALSE(CameraPath{}.validate("camera_paths.empty").ok());
}

TEST(Environment, SunFollowsTheClock) {
  // Equinox at 45 N: noon due south at 45 degrees, sunrise due east on the horizon.
  const SunPosition noon = sun_from_clock(12.0f, 0.0f, 45.0f);
  EXPECT_NEAR(noon.azimuth_deg, 180.0f, 1e-3);
  EXPECT_NEAR(noon.elevation_deg, 45.0f, 1e-3);
  const SunPosition sunrise = sun_from_clock(6.0f, 0.0f, 45.0f);
  EXPECT_NEAR(sunrise.azimuth_deg, 90.0f, 1e-3);
  EXPECT_NEAR(sunrise.elevation_deg, 0.0f, 1e-3);
  const SunPosition evening = sun_from_clock(18.0f, 0.0f, 45.0f);
  EXPECT_NEAR(evening.azimuth_deg, 270.0f, 1e-3);
  // Midsummer noon: 90 - 45 + 23.44.
  EXPECT_NEAR(sun_from_clock(12.0f, 0.25f, 45.0f).elevation_deg, 68.44f, 1e-2);
  // Southern hemisphere: noon sun in the north.
  const SunPosition south = sun_from_clock(12.0f, 0.0f, -30.0f);
  EXPECT_NEAR(std::fmod(south.azimuth_deg + 360.0f, 360.0f), 0.0f, 1e-3);
  // Night: below the horizon, and the lighting goes dark but stays finite.
  const SunPosition night = sun_from_clock(0.0f, 0.0f, 45.0f);
  EXPECT_LT(night.elevation_deg, -30.0f);
  SunSettings sun;
  sun.follow_clock = true;
  EnvironmentSettings env;
  env.time_of_day_h = 0.0f;
  const sylva::render::Lighting dark = make_lighting(sun, env);
  env.time_of_day_h = 12.0f;
  const sylva::render::Lighting day = make_lighting(sun, env);
  EXPECT_EQ(dark.sun_intensity, 0.0f);
  EXPECT_GT(day.sun_intensity, 2.0f);
  EXPECT_GT(dark.sun_direction.y, 0.0f) << "light never comes from below the horizon";
  EXPECT_LT(dark.zenith_color.b, day.zenith_color.b);
  // Fixed sun ignores the clock.
  sun.follow_clock = false;
  sun.azimuth_deg = 10.0f;
  EXPECT_EQ(sun_position(sun, env).azimuth_deg, 10.0f);
}
