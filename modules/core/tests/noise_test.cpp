// Gradient noise, fBm and ridged fBm: determinism, documented ranges, continuity (a Lipschitz
// bound on small steps), seeds, periodicity, and agreement of the float, double and split forms.
#include <sylva/core/noise.hpp>
#include <sylva/core/params.hpp>
#include <sylva/core/rng.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace sylva {
namespace {

// Sample statistics of a field over random points.
struct Stats {
  float min = 1e30f;
  float max = -1e30f;
  double mean = 0.0;
  double stddev = 0.0;
};

template <class F>
Stats sample_stats(F f, int n, std::uint64_t seed, float extent) {
  Pcg32 rng(seed);
  Stats s;
  double sum = 0.0;
  double sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 p(rng.uniform(-extent, extent), rng.uniform(-extent, extent), rng.uniform(-extent, extent));
    const float v = f(p);
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
    sum += v;
    sum2 += static_cast<double>(v) * v;
  }
  s.mean = sum / n;
  s.stddev = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean));
  return s;
}

// Deterministic: a value depends on (position, seed) alone, not on what was evaluated before it
// (no hidden cache or state), so a second pass in reverse order, interleaved with other seeds,
// gives the same bits; and the seed does select a different field.
TEST(Noise, IsDeterministic) {
  auto point = [](int i) { return glm::vec3(i * 0.731f, i * -1.37f, i * 0.19f); };
  std::vector<glm::vec3> first;
  for (int i = 0; i < 100; ++i) {
    const glm::vec3 p = point(i);
    first.emplace_back(gradient_noise3(p, 17u), gradient_noise2(glm::vec2(p), 17u), gradient_noise1(p.x, 17u));
  }
  int seed_changes = 0;
  for (int i = 99; i >= 0; --i) {
    const glm::vec3 p = point(i);
    const float other = gradient_noise3(p, 18u);
    EXPECT_EQ(gradient_noise3(p, 17u), first[static_cast<std::size_t>(i)].x) << i;
    EXPECT_EQ(gradient_noise2(glm::vec2(p), 17u), first[static_cast<std::size_t>(i)].y) << i;
    EXPECT_EQ(gradient_noise1(p.x, 17u), first[static_cast<std::size_t>(i)].z) << i;
    seed_changes += other != first[static_cast<std::size_t>(i)].x;
  }
  EXPECT_GT(seed_changes, 90) << "seed 18 must give another field than seed 17";
}

TEST(Noise, MatchesAnIndependentFloat32Reference) {
  // Values from a separate Python model of the documented algorithm (PCG hash chain, gradient
  // sets, quintic fade, scale factors) that rounds every operation to float32. They pin the
  // exact field: a change to the hash, gradients or scaling breaks this test, the GLSL twin and
  // every stored generated terrain. Tolerance: a few float ulps (the compiler may reorder).
  struct Case {
    glm::vec3 p;
    std::uint32_t seed;
    float n2;
    float n3;
  };
  const Case cases[] = {
      {{0.5f, 0.25f, 0.75f}, 0u, 0.163518161f, 0.127259508f},
      {{-3.125f, 7.75f, 1.5f}, 1u, 0.107283689f, -0.107967034f},
      {{12.3f, -0.7f, 100.01f}, 42u, -0.0175393187f, 0.387705564f},
      {{-1000.37f, 2500.5f, -0.001f}, 7u, 0.433452874f, -0.383298248f},
  };
  for (const Case& c : cases) {
    EXPECT_NEAR(gradient_noise2(glm::vec2(c.p), c.seed), c.n2, 1e-6f);
    EXPECT_NEAR(gradient_noise3(c.p, c.seed), c.n3, 1e-6f);
  }
}

TEST(Noise, ValuesStayInTheDocumentedRangeAndUseIt) {
  const Stats s1 = sample_stats([](glm::vec3 p) { return gradient_noise1(p.x, 3u); }, 200000, 1, 300.0f);
  const Stats s2 = sample_stats([](glm::vec3 p) { return gradient_noise2(glm::vec2(p), 3u); }, 200000, 2, 300.0f);
  const Stats s3 = sample_stats([](glm::vec3 p) { return gradient_noise3(p, 3u); }, 200000, 3, 300.0f);
  for (const Stats& s : {s1, s2, s3}) {
    EXPECT_GE(s.min, -1.0f);
    EXPECT_LE(s.max, 1.0f);
    EXPECT_LT(s.min, -0.6f) << "range barely used";
    EXPECT_GT(s.max, 0.6f) << "range barely used";
    EXPECT_NEAR(s.mean, 0.0, 0.01);
    EXPECT_GT(s.stddev, 0.15);
    EXPECT_LT(s.stddev, 0.45);
  }
  RecordProperty("noise1_range", testing::PrintToString(std::vector<float>{s1.min, s1.max}));
  RecordProperty("noise2_range", testing::PrintToString(std::vector<float>{s2.min, s2.max}));
  RecordProperty("noise3_range", testing::PrintToString(std::vector<float>{s3.min, s3.max}));
}

TEST(Noise, WorstCaseCellCentresStayInRange) {
  // The analytic maximum is at a cell centre with every gradient pointing at it; scan many
  // centres (and points near them) where the extremes concentrate.
  for (int i = -200; i < 200; ++i) {
    for (int j = -200; j < 200; ++j) {
      const glm::vec2 c(i + 0.5f, j + 0.5f);
      ASSERT_LE(std::abs(gradient_noise2(c, 9u)), 1.0f);
      ASSERT_LE(std::abs(gradient_noise3(glm::vec3(c, 0.5f + (i ^ j) % 7), 9u)), 1.0f);
      ASSERT_LE(std::abs(gradient_noise1(c.x + j * 0.001f, static_cast<std::uint32_t>(j))), 1.0f);
    }
  }
}

TEST(Noise, IsZeroAtLatticePoints) {
  for (int i = -20; i < 20; ++i) {
    EXPECT_EQ(gradient_noise1(static_cast<float>(i), 4u), 0.0f);
    EXPECT_EQ(gradient_noise2(glm::vec2(i, 3 * i), 4u), 0.0f);
    EXPECT_EQ(gradient_noise3(glm::vec3(i, -i, 7), 4u), 0.0f);
  }
}

// Largest |f(p + d) - f(p)| / |d| over random points and directions with |d| = step.
template <class F>
double max_slope(F f, double step, int n, std::uint64_t seed) {
  Pcg32 rng(seed);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 p(rng.uniform(-50.0f, 50.0f), rng.uniform(-50.0f, 50.0f), rng.uniform(-50.0f, 50.0f));
    glm::vec3 d(rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f), rng.uniform(-1.0f, 1.0f));
    d = glm::normalize(d) * static_cast<float>(step);
    const glm::vec3 q = p + d;
    const double len = glm::length(glm::dvec3(q) - glm::dvec3(p));
    worst = std::max(worst, std::abs(static_cast<double>(f(q)) - f(p)) / len);
  }
  return worst;
}

TEST(Noise, IsLipschitzContinuous) {
  // Analytic slope bound of the scaled noise: the quintic fade has |fade'| <= 1.875 and every
  // corner term is bounded by its gradient length times the in-cell distance, giving well under
  // 4 per lattice unit in 1-3D. A discontinuity (a wrong corner hash, a wrap error) would show
  // as a jump of ~0.1 over a 1e-3 step, i.e. a slope of ~100.
  constexpr double kBound = 4.0;
  const double s1 = max_slope([](glm::vec3 p) { return gradient_noise1(p.x, 5u); }, 1e-3, 100000, 10);
  const double s2 = max_slope([](glm::vec3 p) { return gradient_noise2(glm::vec2(p), 5u); }, 1e-3, 100000, 11);
  const double s3 = max_slope([](glm::vec3 p) { return gradient_noise3(p, 5u); }, 1e-3, 100000, 12);
  EXPECT_LT(s1, kBound);
  EXPECT_LT(s2, kBound);
  EXPECT_LT(s3, kBound);
  RecordProperty("max_slope_1d_2d_3d", testing::PrintToString(std::vector<double>{s1, s2, s3}));
}

TEST(Noise, IsContinuousAcrossCellBorders) {
  for (int i = -10; i <= 10; ++i) {
    const float b = static_cast<float>(i);
    for (float y : {0.1f, 0.37f, 0.9f}) {
      const float below = gradient_noise2(glm::vec2(b - 1e-4f, y), 8u);
      const float above = gradient_noise2(glm::vec2(b + 1e-4f, y), 8u);
      EXPECT_LT(std::abs(above - below), 1e-3f) << "jump at x = " << b;
      const float below3 = gradient_noise3(glm::vec3(y, b - 1e-4f, 0.3f), 8u);
      const float above3 = gradient_noise3(glm::vec3(y, b + 1e-4f, 0.3f), 8u);
      EXPECT_LT(std::abs(above3 - below3), 1e-3f) << "jump at y = " << b;
    }
  }
}

TEST(Noise, IsPeriodicWithTheDocumentedPeriod) {
  const float period = static_cast<float>(kNoisePeriod);
  for (int i = 0; i < 64; ++i) {
    // Dyadic fractions, so p + period is exact in float.
    const glm::vec3 p(i * 0.25f - 3.0f, i * 0.125f, -i * 0.5f);
    EXPECT_EQ(gradient_noise3(p, 2u), gradient_noise3(p + glm::vec3(period, 0, 0), 2u));
    EXPECT_EQ(gradient_noise3(p, 2u), gradient_noise3(p - glm::vec3(0, period, 2 * period), 2u));
    EXPECT_EQ(gradient_noise2(glm::vec2(p), 2u), gradient_noise2(glm::vec2(p) + glm::vec2(-period, period), 2u));
    EXPECT_EQ(gradient_noise1(p.x, 2u), gradient_noise1(p.x + 3 * period, 2u));
  }
  // And continuous across the wrap point itself.
  EXPECT_EQ(gradient_noise2(glm::vec2(period - 0.00390625f, 0.3f), 2u), gradient_noise2(glm::vec2(-0.00390625f, 0.3f), 2u));
}

TEST(Noise, DifferentSeedsGiveUncorrelatedFields) {
  double dot = 0.0;
  double na = 0.0;
  double nb = 0.0;
  double diff = 0.0;
  int n = 0;
  for (int y = 0; y < 64; ++y) {
    for (int x = 0; x < 64; ++x) {
      const glm::vec2 p(x * 0.37f, y * 0.41f);
      const float a = gradient_noise2(p, 100u);
      const float b = gradient_noise2(p, 101u);
      dot += a * b;
      na += a * a;
      nb += b * b;
      diff += std::abs(a - b);
      ++n;
    }
  }
  EXPECT_LT(std::abs(dot / std::sqrt(na * nb)), 0.1) << "seeds 100 and 101 are correlated";
  EXPECT_GT(diff / n, 0.1);
  EXPECT_NE(gradient_noise3(glm::vec3(0.5f), 0u), gradient_noise3(glm::vec3(0.5f), 1u));
}

TEST(Noise, FloatDoubleAndSplitFormsAgree) {
  Pcg32 rng(77u);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 p(rng.uniform(-1000.0f, 1000.0f), rng.uniform(-1000.0f, 1000.0f), rng.uniform(-1000.0f, 1000.0f));
    const float f3 = gradient_noise3(p, 6u);
    EXPECT_NEAR(f3, gradient_noise3(glm::dvec3(p), 6u), 2e-5f);
    EXPECT_NEAR(gradient_noise2(glm::vec2(p), 6u), gradient_noise2(glm::dvec2(glm::vec2(p)), 6u), 2e-5f);
    // cell + offset with a whole-number cell part moved into the integer.
    const glm::ivec3 cell(static_cast<int>(std::floor(p.x)) - 5, static_cast<int>(std::floor(p.y)) + 9, -3);
    const glm::vec3 offset = p - glm::vec3(cell);
    EXPECT_NEAR(f3, gradient_noise3(cell, offset, 6u), 2e-4f);
    const NoiseCoord3 split = split_noise_coord(glm::dvec3(p));
    EXPECT_NEAR(f3, gradient_noise3(split.cell, split.offset, 6u), 2e-5f);
    EXPECT_GE(split.cell.x, 0);
    EXPECT_LT(split.cell.x, kNoisePeriod);
    const NoiseCoord1 s1 = split_noise_coord(static_cast<double>(p.x));
    EXPECT_NEAR(gradient_noise1(p.x, 6u), gradient_noise1(s1.cell, s1.offset, 6u), 2e-5f);
  }
}

TEST(Fbm, RangesAndDeterminism) {
  FbmSettings s;
  s.octaves = 8;
  s.frequency = 0.05f;
  s.seed = 42u;
  const Stats f2 = sample_stats([&](glm::vec3 p) { return fbm2(glm::vec2(p), s); }, 50000, 4, 500.0f);
  const Stats f3 = sample_stats([&](glm::vec3 p) { return fbm3(p, s); }, 50000, 5, 500.0f);
  const Stats r2 = sample_stats([&](glm::vec3 p) { return ridged2(glm::vec2(p), s); }, 50000, 6, 500.0f);
  const Stats r3 = sample_stats([&](glm::vec3 p) { return ridged3(p, s); }, 50000, 7, 500.0f);
  for (const Stats& f : {f2, f3}) {
    EXPECT_GE(f.min, -1.0f);
    EXPECT_LE(f.max, 1.0f);
    EXPECT_NEAR(f.mean, 0.0, 0.03);
    EXPECT_GT(f.stddev, 0.1);
  }
  for (const Stats& r : {r2, r3}) {
    EXPECT_GE(r.min, 0.0f);
    EXPECT_LE(r.max, 1.0f);
    EXPECT_GT(r.max, 0.5f);
    EXPECT_GT(r.stddev, 0.05);
  }
  // Determinism is Noise.IsDeterministic's; here: the seed reaches every octave sum.
  const glm::vec2 p(12.5f, -7.25f);
  FbmSettings reseeded = s;
  reseeded.seed = 43u;
  EXPECT_NE(fbm2(p, reseeded), fbm2(p, s));
  EXPECT_NE(ridged3(glm::vec3(p, 1.0f), reseeded), ridged3(glm::vec3(p, 1.0f), s));
}

TEST(Fbm, OneOctaveIsScaledNoiseAndOctavesAddDetail) {
  FbmSettings s;
  s.octaves = 1;
  s.frequency = 0.3f;
  s.seed = 9u;
  const glm::vec3 p(3.3f, -1.2f, 8.8f);
  EXPECT_EQ(fbm3(p, s), gradient_noise3(p * 0.3f, octave_seed(9u, 0)));
  EXPECT_EQ(fbm2(glm::vec2(p), s), gradient_noise2(glm::vec2(p) * 0.3f, octave_seed(9u, 0)));
  // persistence 0: only the first octave counts, whatever the octave count.
  FbmSettings flat = s;
  flat.octaves = 8;
  flat.persistence = 0.0f;
  EXPECT_EQ(fbm3(p, flat), fbm3(p, s));
  // More octaves make the field rougher: with persistence * lacunarity > 1 the small-step slope
  // grows with every octave.
  FbmSettings rough = s;
  rough.octaves = 6;
  rough.persistence = 0.7f;
  const double slope1 = max_slope([&](glm::vec3 q) { return fbm2(glm::vec2(q), s); }, 1e-3, 20000, 20);
  const double slope6 = max_slope([&](glm::vec3 q) { return fbm2(glm::vec2(q), rough); }, 1e-3, 20000, 20);
  EXPECT_GT(slope6, slope1 * 1.5);
}

TEST(Fbm, IsLipschitzContinuous) {
  // Octave k has slope <= 4 * frequency * lacunarity^k with weight persistence^k / norm, so the
  // fBm slope is bounded by 4 * frequency * sum_k (p l)^k / sum_k p^k.
  FbmSettings s;
  s.octaves = 5;
  s.frequency = 0.5f;
  double num = 0.0;
  double den = 0.0;
  for (int k = 0; k < s.octaves; ++k) {
    num += std::pow(s.persistence * s.lacunarity, k);
    den += std::pow(s.persistence, k);
  }
  const double bound = 4.0 * s.frequency * num / den;
  EXPECT_LT(max_slope([&](glm::vec3 p) { return fbm2(glm::vec2(p), s); }, 1e-3, 50000, 30), bound);
  EXPECT_LT(max_slope([&](glm::vec3 p) { return fbm3(p, s); }, 1e-3, 50000, 31), bound);
  EXPECT_LT(max_slope([&](glm::vec3 p) { return ridged2(glm::vec2(p), s); }, 1e-3, 50000, 32), 2.0 * bound);
}

TEST(Fbm, DoubleOverloadsMatchFloat) {
  FbmSettings s;
  s.frequency = 0.01f;
  for (int i = 0; i < 200; ++i) {
    const glm::vec2 p(i * 3.25f, i * -1.5f);
    EXPECT_NEAR(fbm2(p, s), fbm2(glm::dvec2(p), s), 1e-4f);
    EXPECT_NEAR(ridged2(p, s), ridged2(glm::dvec2(p), s), 1e-4f);
    EXPECT_NEAR(fbm3(glm::vec3(p, 2.0f), s), fbm3(glm::dvec3(glm::vec3(p, 2.0f)), s), 1e-4f);
    EXPECT_NEAR(ridged3(glm::vec3(p, 2.0f), s), ridged3(glm::dvec3(glm::vec3(p, 2.0f)), s), 1e-4f);
  }
}

TEST(Fbm, SettingsAreReflected) {
  FbmSettings s;
  const auto params = describe_params(s);
  ASSERT_EQ(params.size(), 6u);
  EXPECT_TRUE(validate_params(s).ok());
  EXPECT_TRUE(set_param(s, "octaves", "9").ok());
  EXPECT_EQ(s.octaves, 9);
  const Status bad = set_param(s, "octaves", "40");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("octaves"), std::string::npos) << bad.error().message;
  EXPECT_EQ(s.octaves, 9);
  EXPECT_FALSE(set_param(s, "persistence", "1.5").ok());
}

}  // namespace
}  // namespace sylva
