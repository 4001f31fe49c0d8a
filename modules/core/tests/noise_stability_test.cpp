// Noise under extreme inputs and settings. Invariants checked (named in each test):
//  - FiniteEverywhere: no NaN/Inf for any input, including NaN, Inf, 1e30 and denormals.
//  - NoCollapseFarFromOrigin: at 1e6 the field still varies (not a constant), for the float
//    overloads (resolution 1/16 cell there) and the double overloads (full resolution up to 1e12).
//  - ExtremeSettingsStayInRange: octaves, persistence, lacunarity and frequency at and beyond their
//    limits keep fBm in [-1, 1] and ridged in [0, 1].
#include <sylva/core/noise.hpp>
#include <sylva/core/rng.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace sylva {
namespace {

double stddev_of(const std::vector<float>& v) {
  double s = 0.0;
  double s2 = 0.0;
  for (float x : v) {
    s += x;
    s2 += static_cast<double>(x) * x;
  }
  const double m = s / static_cast<double>(v.size());
  return std::sqrt(std::max(0.0, s2 / static_cast<double>(v.size()) - m * m));
}

TEST(NoiseStability, FiniteEverywhere) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float denorm = std::numeric_limits<float>::denorm_min();
  const std::vector<float> inputs = {0.0f, -0.0f, denorm, -denorm, 1e-30f, -1e-30f, 1e6f, -1e6f, 1.6777216e7f,
                                     3e9f, -3e9f, 1e30f, -1e30f, std::numeric_limits<float>::max(),
                                     -std::numeric_limits<float>::max(), inf, -inf, nan};
  FbmSettings s;
  s.octaves = 16;
  for (float a : inputs) {
    for (float b : inputs) {
      const glm::vec3 p(a, b, 0.5f);
      ASSERT_TRUE(std::isfinite(gradient_noise1(a, 1u))) << a;
      ASSERT_TRUE(std::isfinite(gradient_noise2(glm::vec2(a, b), 1u))) << a << ", " << b;
      ASSERT_TRUE(std::isfinite(gradient_noise3(p, 1u))) << a << ", " << b;
      ASSERT_TRUE(std::isfinite(gradient_noise3(glm::dvec3(p), 1u))) << a << ", " << b;
      ASSERT_TRUE(std::isfinite(gradient_noise3(glm::ivec3(2147483647, -2147483647 - 1, 5), p, 1u))) << a << ", " << b;
      ASSERT_TRUE(std::isfinite(fbm3(p, s))) << a << ", " << b;
      ASSERT_TRUE(std::isfinite(ridged2(glm::vec2(a, b), s))) << a << ", " << b;
      ASSERT_TRUE(std::isfinite(fbm2(glm::dvec2(a, b), s))) << a << ", " << b;
    }
  }
  // Non-finite inputs map to 0 as documented.
  EXPECT_EQ(gradient_noise2(glm::vec2(nan, 0.5f), 1u), 0.0f);
  EXPECT_EQ(gradient_noise3(glm::vec3(0.5f, inf, 0.5f), 1u), 0.0f);
  const NoiseCoord3 split = split_noise_coord(glm::dvec3(std::nan(""), 1e300, -1e300));
  EXPECT_TRUE(std::isfinite(split.offset.x) && std::isfinite(split.offset.y) && std::isfinite(split.offset.z));
}

TEST(NoiseStability, NoCollapseFarFromOrigin) {
  // Float overloads at 1e6: steps of 0.3125 (5 float ulps there) still sample a varying field.
  std::vector<float> f2;
  std::vector<float> f3;
  for (int i = 0; i < 400; ++i) {
    const float x = 1e6f + static_cast<float>(i) * 0.3125f;
    f2.push_back(gradient_noise2(glm::vec2(x, -1e6f + static_cast<float>(i % 20) * 0.75f), 3u));
    f3.push_back(gradient_noise3(glm::vec3(x, 1e6f, -x), 3u));
  }
  EXPECT_GT(stddev_of(f2), 0.1);
  EXPECT_GT(stddev_of(f3), 0.1);
  EXPECT_GT(std::set<float>(f2.begin(), f2.end()).size(), 100u);

  // Double overloads far beyond float range keep full sub-cell resolution: at 1e12 a step of
  // 0.01 cells changes the value smoothly (no steps, no constant).
  std::vector<float> d3;
  double worst_jump = 0.0;
  float prev = gradient_noise3(glm::dvec3(1e12, -1e12, 5e11), 3u);
  for (int i = 1; i < 400; ++i) {
    const float v = gradient_noise3(glm::dvec3(1e12 + i * 0.01, -1e12, 5e11 + i * 0.003), 3u);
    d3.push_back(v);
    worst_jump = std::max(worst_jump, static_cast<double>(std::abs(v - prev)));
    prev = v;
  }
  EXPECT_GT(stddev_of(d3), 0.05);
  EXPECT_LT(worst_jump, 0.05) << "double noise is not continuous at 1e12";

  // fBm at 1e6 m with a terrain-like frequency (1 / 200 m) varies too.
  FbmSettings s;
  s.frequency = 1.0f / 200.0f;
  s.octaves = 8;
  std::vector<float> fb;
  for (int i = 0; i < 400; ++i) fb.push_back(fbm2(glm::vec2(1e6f + static_cast<float>(i) * 4.0f, 1e6f), s));
  EXPECT_GT(stddev_of(fb), 0.05);
}

TEST(NoiseStability, ExtremeSettingsStayInRange) {
  Pcg32 rng(1u);
  const std::vector<FbmSettings> cases = {
      {.octaves = 0},                                      // clamped to 1
      {.octaves = 1000},                                   // clamped to 16
      {.octaves = 16, .persistence = 1.0f, .lacunarity = 4.0f},
      {.octaves = 16, .persistence = 0.0f},
      {.octaves = 8, .lacunarity = 1.0f},                  // all octaves on the same lattice
      {.octaves = 8, .frequency = 0.0f},                   // constant 0 / constant ridge
      {.octaves = 8, .frequency = 1e4f},
      {.octaves = 8, .persistence = -0.7f},                // outside the range: still bounded
      {.octaves = 6, .ridge_gain = 0.0f},
      {.octaves = 6, .ridge_gain = 1e6f},
  };
  for (std::size_t c = 0; c < cases.size(); ++c) {
    const FbmSettings& s = cases[c];
    for (int i = 0; i < 5000; ++i) {
      const glm::vec3 p(rng.uniform(-1e3f, 1e3f), rng.uniform(-1e3f, 1e3f), rng.uniform(-1e3f, 1e3f));
      const float f = fbm3(p, s);
      const float g = fbm2(glm::vec2(p), s);
      ASSERT_TRUE(f >= -1.0f && f <= 1.0f) << "case " << c << " fbm3 = " << f;
      ASSERT_TRUE(g >= -1.0f && g <= 1.0f) << "case " << c << " fbm2 = " << g;
      const float r = ridged3(p, s);
      if (s.persistence >= 0.0f) {
        ASSERT_TRUE(r >= 0.0f && r <= 1.0f) << "case " << c << " ridged3 = " << r;
      }
      ASSERT_TRUE(std::isfinite(r));
    }
  }
}

}  // namespace
}  // namespace sylva
