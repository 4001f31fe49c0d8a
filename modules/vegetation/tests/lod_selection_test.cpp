// LOD selection and transitions (lod_selection.hpp): thresholds, ramps, hysteresis, the
// fade-in-background weights (one level always opaque) and the seed's other blends (cross-fade,
// soft, shifted soft; issue 20), queues ordered near to far, culling.
#include <sylva/vegetation/lod_selection.hpp>

#include <sylva/vegetation/forest.hpp>

#include <sylva/core/params.hpp>
#include <sylva/core/params_json.hpp>
#include <sylva/core/timer.hpp>
#include <sylva/render/camera.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace sylva::vegetation {
namespace {

TEST(LodSelection, TargetRisesContinuouslyThroughBothThresholds) {
  LodSettings s;
  s.v1 = 40.0f;
  s.v2 = 100.0f;
  s.band = 0.1f;
  const LodRamps r = lod_ramps(s, 10.0, 500.0);
  EXPECT_EQ(lod_target(r, 0.0), 0.0f);
  EXPECT_EQ(lod_target(r, 39.9), 0.0f);
  EXPECT_NEAR(lod_target(r, 42.0), 0.5f, 1e-6f);
  EXPECT_EQ(lod_target(r, 44.0), 1.0f);
  EXPECT_EQ(lod_target(r, 99.0), 1.0f);
  EXPECT_NEAR(lod_target(r, 105.0), 1.5f, 1e-6f);
  EXPECT_EQ(lod_target(r, 1.0e6), 2.0f);
  // Continuity: no step larger than the slope allows over a fine dolly.
  float prev = 0.0f;
  for (double d = 0.0; d < 150.0; d += 0.01) {
    const float l = lod_target(r, d);
    EXPECT_LE(std::abs(l - prev), 0.01 / 4.0 + 1e-5) << d;
    EXPECT_GE(l, prev);  // monotonic
    prev = l;
  }
}

TEST(LodSelection, FadeInBackgroundKeepsOneLevelOpaque) {
  for (float l = 0.0f; l <= 2.0f; l += 0.001f) {
    const LodDraws d = lod_draws(l);
    ASSERT_GE(d.count, 1);
    float best = 0.0f;
    for (int k = 0; k < d.count; ++k) {
      const LodDraw& x = d.draw[static_cast<std::size_t>(k)];
      EXPECT_GE(x.fade, 0.0f);
      EXPECT_LE(x.fade, 1.0f);
      best = std::max(best, x.fade);
    }
    EXPECT_EQ(best, 1.0f) << "l = " << l;  // seed eq. 3.42: never see-through
    if (d.count == 2) {
      EXPECT_EQ(d.draw[1].level, d.draw[0].level + 1);
      EXPECT_NEAR(d.draw[0].fade, std::min(1.0f, 2.0f * (1.0f - (l - static_cast<float>(d.draw[0].level)))), 1e-5f);
    }
  }
  EXPECT_EQ(lod_draws(0.0f).count, 1);
  EXPECT_EQ(lod_draws(1.0f).draw[0].level, 1);
  EXPECT_EQ(lod_draws(2.0f).draw[0].level, 2);
}

// lod_draws as it was before the transition variants (issue 20), kept verbatim as the reference
// the default must stay bit-identical to.
LodDraws lod_draws_before_variants(float l) {
  LodDraws out;
  if (!(l > 0.0f)) {
    out.draw[0] = {0, 1.0f};
    out.count = 1;
    return out;
  }
  if (l >= 2.0f) {
    out.draw[0] = {2, 1.0f};
    out.count = 1;
    return out;
  }
  const int k = static_cast<int>(std::floor(l));
  const float f = l - static_cast<float>(k);
  if (f == 0.0f) {
    out.draw[0] = {k, 1.0f};
    out.count = 1;
    return out;
  }
  out.draw[0] = {k, std::min(1.0f, 2.0f * (1.0f - f))};
  out.draw[1] = {k + 1, std::min(1.0f, 2.0f * f)};
  out.count = 2;
  return out;
}

void expect_same_draws(const LodDraws& a, const LodDraws& b, float l) {
  ASSERT_EQ(a.count, b.count) << "l = " << l;
  for (int k = 0; k < a.count; ++k) {
    const auto i = static_cast<std::size_t>(k);
    EXPECT_EQ(a.draw[i].level, b.draw[i].level) << "l = " << l;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(a.draw[i].fade), std::bit_cast<std::uint32_t>(b.draw[i].fade)) << "l = " << l;
  }
}

// Invariant: the default blend is today's fade in background, bit for bit, through both entry
// points and whatever transition_shift holds; select_lods with default settings queues the same.
TEST(LodTransitions, FadeInBackgroundIsBitIdenticalToBefore) {
  std::vector<float> ls;
  for (int i = 0; i <= 20000; ++i) ls.push_back(static_cast<float>(i) * 1.0e-4f);
  std::uint32_t h = 99u;
  for (int i = 0; i < 20000; ++i) {  // random float bit patterns in [0, 2]
    h = h * 1664525u + 1013904223u;
    ls.push_back(std::bit_cast<float>(0x3f800000u | (h >> 9)) - 1.0f + ((h & 1u) ? 1.0f : 0.0f));
  }
  for (float l : {0.0f, 1.0e-30f, 0.5f, std::nextafter(1.0f, 0.0f), 1.0f, std::nextafter(1.0f, 2.0f), 1.5f,
                  std::nextafter(2.0f, 0.0f), 2.0f, 3.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()})
    ls.push_back(l);
  const LodSettings defaults;
  ASSERT_EQ(defaults.transition, LodTransition::kFadeInBackground);
  for (float l : ls) {
    const LodDraws before = lod_draws_before_variants(l);
    expect_same_draws(lod_draws(l), before, l);
    expect_same_draws(lod_draws(l, defaults.transition, defaults.transition_shift), before, l);
    expect_same_draws(lod_draws(l, LodTransition::kFadeInBackground, 0.9f), before, l);
  }
}

// The seed's equations written out literally (seed 000 §2.9), for the weights test below.
constexpr double kPi = 3.14159265358979323846;
double seed_smooth(double x) { return x <= 0.0 ? 1.0 : x >= kPi ? -1.0 : std::cos(x); }
// Eq. 3.41 as printed, R = f A' + (1 - f) B': A' has weight f. With the errata's role flip (item 9)
// A' is the level entered, so in eq. 3.42's roles (A = level left, B = entered): A = 1 - f, B = f.
LodWeights seed_cross_fade(double f) { return {static_cast<float>(1.0 - f), static_cast<float>(f)}; }
LodWeights seed_fade_in_background(double f) {
  return {static_cast<float>(std::min(1.0, 2.0 * (1.0 - f))), static_cast<float>(std::min(1.0, 2.0 * f))};
}
LodWeights seed_shifted_soft(double f, double s) {
  return {static_cast<float>(0.5 * (seed_smooth((f - s) / (1.0 - s) * kPi) + 1.0)),
          static_cast<float>(1.0 - 0.5 * (seed_smooth(f / (1.0 - s) * kPi) + 1.0))};
}

// Invariant: each blend's weights at f = 0, s, 0.5, 1 - s, 1 are the seed's equations (plus hand
// values), both levels take part inside the band, and the end points are the pure levels.
TEST(LodTransitions, WeightsMatchTheSeedsEquations) {
  for (float s : {0.0f, 0.25f, 0.5f, 0.8f, 0.95f}) {
    SCOPED_TRACE(s);
    for (float f : {0.0f, s, 0.5f, 1.0f - s, 1.0f}) {
      SCOPED_TRACE(f);
      const auto check = [&](LodTransition t, LodWeights want) {
        const LodWeights got = lod_transition_weights(t, f, s);
        EXPECT_NEAR(got.a, want.a, 1e-6f);
        EXPECT_NEAR(got.b, want.b, 1e-6f);
        EXPECT_GE(got.a + got.b, 1.0f - 1e-6f);  // never both faint
      };
      check(LodTransition::kFadeInBackground, seed_fade_in_background(f));
      check(LodTransition::kCrossFade, seed_cross_fade(f));
      check(LodTransition::kSoft, seed_shifted_soft(f, 0.0));
      check(LodTransition::kShiftedSoft, seed_shifted_soft(f, s));
    }
  }
  // End points: the level left alone at f = 0, the level entered alone at f = 1, for every blend.
  for (LodTransition t : {LodTransition::kFadeInBackground, LodTransition::kCrossFade, LodTransition::kSoft,
                          LodTransition::kShiftedSoft}) {
    EXPECT_EQ(lod_transition_weights(t, 0.0f, 0.5f).a, 1.0f);
    EXPECT_EQ(lod_transition_weights(t, 0.0f, 0.5f).b, 0.0f);
    EXPECT_EQ(lod_transition_weights(t, 1.0f, 0.5f).a, 0.0f);
    EXPECT_EQ(lod_transition_weights(t, 1.0f, 0.5f).b, 1.0f);
  }
  // Hand values. Mid-band: cross-fade and soft are 0.5 / 0.5 (see-through), fade in background and
  // shifted soft with s = 0.5 are opaque on both levels.
  const auto at = [](LodTransition t, float f, float s) { return lod_transition_weights(t, f, s); };
  EXPECT_FLOAT_EQ(at(LodTransition::kCrossFade, 0.5f, 0.0f).a, 0.5f);
  EXPECT_FLOAT_EQ(at(LodTransition::kCrossFade, 0.5f, 0.0f).b, 0.5f);
  EXPECT_FLOAT_EQ(at(LodTransition::kCrossFade, 0.25f, 0.0f).a, 0.75f);
  EXPECT_FLOAT_EQ(at(LodTransition::kCrossFade, 0.25f, 0.0f).b, 0.25f);
  EXPECT_FLOAT_EQ(at(LodTransition::kSoft, 0.5f, 0.7f).a, 0.5f);  // soft ignores the shift
  EXPECT_FLOAT_EQ(at(LodTransition::kSoft, 0.5f, 0.7f).b, 0.5f);
  EXPECT_NEAR(at(LodTransition::kSoft, 0.25f, 0.0f).a, 0.5 * (1.0 + std::sqrt(0.5)), 1e-6);  // (1 + cos 45 deg) / 2
  EXPECT_EQ(at(LodTransition::kFadeInBackground, 0.5f, 0.0f).a, 1.0f);
  EXPECT_EQ(at(LodTransition::kFadeInBackground, 0.5f, 0.0f).b, 1.0f);
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.5f, 0.5f).a, 1.0f);
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.5f, 0.5f).b, 1.0f);
  EXPECT_FLOAT_EQ(at(LodTransition::kShiftedSoft, 0.25f, 0.5f).b, 0.5f);  // (1 - cos 90 deg) / 2
  // s = 0.25: A = 1 up to f = s, B = 1 from f = 1 - s; in between cos(60 deg), cos(120 deg).
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.25f, 0.25f).a, 1.0f);
  EXPECT_FLOAT_EQ(at(LodTransition::kShiftedSoft, 0.25f, 0.25f).b, 0.25f);
  EXPECT_FLOAT_EQ(at(LodTransition::kShiftedSoft, 0.5f, 0.25f).a, 0.75f);
  EXPECT_FLOAT_EQ(at(LodTransition::kShiftedSoft, 0.5f, 0.25f).b, 0.75f);
  EXPECT_FLOAT_EQ(at(LodTransition::kShiftedSoft, 0.75f, 0.25f).a, 0.25f);
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.75f, 0.25f).b, 1.0f);
  // s = 0.8: the opaque ranges overlap on [0.2, 0.8].
  for (float f : {0.2f, 0.5f, 0.8f}) {
    EXPECT_EQ(at(LodTransition::kShiftedSoft, f, 0.8f).a, 1.0f) << f;
    EXPECT_EQ(at(LodTransition::kShiftedSoft, f, 0.8f).b, 1.0f) << f;
  }
  // Shifts out of range are clamped to [0, 0.95] (no division by zero at s = 1), non-finite = 0.
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.5f, 1.0f).a, at(LodTransition::kShiftedSoft, 0.5f, 0.95f).a);
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.96f, 7.0f).b, at(LodTransition::kShiftedSoft, 0.96f, 0.95f).b);
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.3f, -1.0f).a, at(LodTransition::kSoft, 0.3f, 0.0f).a);
  EXPECT_EQ(at(LodTransition::kShiftedSoft, 0.3f, std::nanf("")).b, at(LodTransition::kSoft, 0.3f, 0.0f).b);
  // Monotonic ramps, weights in [0, 1], never both below 1 together beyond rounding.
  for (LodTransition t : {LodTransition::kCrossFade, LodTransition::kSoft, LodTransition::kShiftedSoft}) {
    LodWeights prev = at(t, 0.0f, 0.3f);
    for (int i = 1; i <= 1000; ++i) {
      const LodWeights w = at(t, static_cast<float>(i) * 1.0e-3f, 0.3f);
      EXPECT_LE(w.a, prev.a);
      EXPECT_GE(w.b, prev.b);
      EXPECT_GE(w.a, 0.0f);
      EXPECT_LE(w.b, 1.0f);
      prev = w;
    }
  }
}

// Invariant: lod_draws queues each level with its weight, level k first; a level of weight 0 is
// left out (the far end of a cosine ramp), one of weight 1 is opaque; cross-fade and soft leave
// no level opaque mid-band (the seed's see-through defect), shifted soft with s = 0.5 one.
TEST(LodTransitions, DrawsCarryTheWeights) {
  const LodDraws cross = lod_draws(0.5f, LodTransition::kCrossFade, 0.5f);
  ASSERT_EQ(cross.count, 2);
  EXPECT_EQ(cross.draw[0].level, 0);
  EXPECT_FLOAT_EQ(cross.draw[0].fade, 0.5f);
  EXPECT_EQ(cross.draw[1].level, 1);
  EXPECT_FLOAT_EQ(cross.draw[1].fade, 0.5f);
  const LodDraws cross2 = lod_draws(1.25f, LodTransition::kCrossFade, 0.5f);
  ASSERT_EQ(cross2.count, 2);
  EXPECT_EQ(cross2.draw[0].level, 1);
  EXPECT_FLOAT_EQ(cross2.draw[0].fade, 0.75f);
  EXPECT_EQ(cross2.draw[1].level, 2);
  EXPECT_FLOAT_EQ(cross2.draw[1].fade, 0.25f);
  const LodDraws soft = lod_draws(1.5f, LodTransition::kSoft, 0.5f);
  ASSERT_EQ(soft.count, 2);
  EXPECT_NEAR(soft.draw[0].fade, 0.5f, 1e-6f);
  EXPECT_NEAR(soft.draw[1].fade, 0.5f, 1e-6f);
  const LodDraws shifted = lod_draws(0.5f, LodTransition::kShiftedSoft, 0.5f);
  ASSERT_EQ(shifted.count, 2);
  EXPECT_EQ(shifted.draw[0].fade, 1.0f);
  EXPECT_EQ(shifted.draw[1].fade, 1.0f);
  // Weight 0 is not drawn: soft at a phase whose cosine rounds to 1 (B = 0 exactly).
  const LodDraws tiny = lod_draws(1.0e-30f, LodTransition::kSoft, 0.0f);
  ASSERT_EQ(tiny.count, 1);
  EXPECT_EQ(tiny.draw[0].level, 0);
  EXPECT_EQ(tiny.draw[0].fade, 1.0f);
  const LodDraws tiny_b = lod_draws(std::nextafter(2.0f, 0.0f), LodTransition::kShiftedSoft, 0.95f);
  ASSERT_GE(tiny_b.count, 1);
  EXPECT_EQ(tiny_b.draw[tiny_b.count - 1].level, 2);
  EXPECT_EQ(tiny_b.draw[tiny_b.count - 1].fade, 1.0f);
  // Over every coordinate: fades in (0, 1], consecutive levels, weights as lod_transition_weights.
  for (LodTransition t : {LodTransition::kCrossFade, LodTransition::kSoft, LodTransition::kShiftedSoft}) {
    for (int i = 0; i <= 2000; ++i) {
      const float l = static_cast<float>(i) * 1.0e-3f;
      const LodDraws d = lod_draws(l, t, 0.3f);
      ASSERT_GE(d.count, 1);
      float total = 0.0f;
      for (int k = 0; k < d.count; ++k) {
        const LodDraw& x = d.draw[static_cast<std::size_t>(k)];
        EXPECT_GT(x.fade, 0.0f);
        EXPECT_LE(x.fade, 1.0f);
        total += x.fade;
      }
      EXPECT_GE(total, 1.0f - 1e-6f) << l;
      if (d.count == 2) {
        EXPECT_EQ(d.draw[1].level, d.draw[0].level + 1);
        const float f = l - static_cast<float>(d.draw[0].level);
        const LodWeights w = lod_transition_weights(t, f, 0.3f);
        EXPECT_EQ(d.draw[0].fade, w.a);
        EXPECT_EQ(d.draw[1].fade, w.b);
      }
    }
  }
}

// Invariant: select_lods queues the blend LodSettings::transition names (cross-fade: a tree
// mid-band is in the LOD0 and the LOD1 queue at 0.5 each; the default: 1 and 1).
TEST(LodTransitions, SelectLodsUsesTheSetting) {
  LodSettings s;
  s.v1 = 40.0f;
  s.v2 = 100.0f;
  s.band = 0.1f;
  s.hysteresis = 0.0f;
  const std::vector<render::Sphere> spheres{{glm::dvec3(0.0, 0.0, -42.0), 1.0}};  // l = 0.5
  const std::vector<float> heights{10.0f};
  const LodView view{glm::dvec3(0.0), nullptr, 600.0, 1.0e9};
  const auto queue_fades = [&](LodTransition t, float shift) {
    s.transition = t;
    s.transition_shift = shift;
    LodState state;
    LodQueues q;
    select_lods(s, view, spheres, heights, state, q);
    EXPECT_EQ(q.transitions, 1u);
    EXPECT_EQ(q.level[0].size(), 1u);
    EXPECT_EQ(q.level[1].size(), 1u);
    return std::array<float, 2>{q.level[0].empty() ? -1.0f : q.level[0][0].fade, q.level[1].empty() ? -1.0f : q.level[1][0].fade};
  };
  const auto fib = queue_fades(LodTransition::kFadeInBackground, 0.5f);
  EXPECT_EQ(fib[0], 1.0f);
  EXPECT_EQ(fib[1], 1.0f);
  const auto cross = queue_fades(LodTransition::kCrossFade, 0.5f);
  EXPECT_NEAR(cross[0], 0.5f, 1e-5f);
  EXPECT_NEAR(cross[1], 0.5f, 1e-5f);
  const auto soft = queue_fades(LodTransition::kSoft, 0.5f);
  EXPECT_NEAR(soft[0], 0.5f, 1e-5f);
  EXPECT_NEAR(soft[1], 0.5f, 1e-5f);
  const auto shifted = queue_fades(LodTransition::kShiftedSoft, 0.5f);
  EXPECT_NEAR(shifted[0], 1.0f, 1e-6f);
  EXPECT_NEAR(shifted[1], 1.0f, 1e-6f);
}

// The keys by path and in JSON shaped like a scene's vegetation section
// ("vegetation": {"forest": {"lod": {...}}} reaches ForestSettings as {"lod": {...}}).
TEST(LodTransitions, SettingsByPathAndJson) {
  LodSettings s;
  ASSERT_TRUE(set_param(s, "transition", "cross_fade").ok());
  EXPECT_EQ(s.transition, LodTransition::kCrossFade);
  ASSERT_TRUE(set_param(s, "transition_shift", "0.3").ok());
  EXPECT_FLOAT_EQ(s.transition_shift, 0.3f);
  EXPECT_FALSE(set_param(s, "transition_shift", "0.96").ok());  // s < 1 (range [0, 0.95])
  EXPECT_FALSE(set_param(s, "transition_shift", "-0.1").ok());
  EXPECT_FALSE(set_param(s, "transition", "morph").ok());
  EXPECT_FLOAT_EQ(s.transition_shift, 0.3f);
  bool found = false;
  for (const ParamDescriptor& d : describe_params(s, "vegetation.forest.lod")) found = found || d.path == "vegetation.forest.lod.transition";
  EXPECT_TRUE(found);
  ForestSettings forest;
  std::vector<std::string> warnings;
  ASSERT_TRUE(params_from_json(forest, nlohmann::json::parse(R"({"lod": {"transition": "shifted_soft", "transition_shift": 0.25}})"), warnings).ok());
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(forest.lod.transition, LodTransition::kShiftedSoft);
  EXPECT_FLOAT_EQ(forest.lod.transition_shift, 0.25f);
  EXPECT_TRUE(validate_params(forest).ok());
}

TEST(LodSelection, HysteresisIgnoresJitterButFollowsMotion) {
  const float h = 0.05f;
  double e = lod_follow(std::numeric_limits<double>::quiet_NaN(), 50.0, h);
  EXPECT_EQ(e, 50.0);  // new instances start at their distance
  // Jitter within +-5 % changes nothing.
  for (double d : {48.0, 52.0, 47.7, 52.4}) {
    e = lod_follow(e, d, h);
    EXPECT_EQ(e, 50.0);
  }
  // Motion beyond the backlash drags the effective distance along, continuously.
  e = lod_follow(e, 60.0, h);
  EXPECT_NEAR(e, 60.0 / 1.05, 1e-6);  // h is a float
  e = lod_follow(e, 40.0, h);
  EXPECT_NEAR(e, 42.0, 1e-6);
  // A camera parked inside a ramp band near a threshold settles: repeated frames do not drift.
  LodSettings s;
  const LodRamps r = lod_ramps(s, 10.0, 600.0);
  double eff = std::numeric_limits<double>::quiet_NaN();
  float first = -1.0f;
  for (int frame = 0; frame < 50; ++frame) {
    const double d = 47.0 + ((frame % 2) ? 1.5 : -1.5);  // +-3 % jitter around 47 m
    eff = lod_follow(eff, d, h);
    const float l = lod_target(r, eff);
    // After the first swing the effective distance sits inside the backlash and stays.
    if (frame == 1) first = l;
    if (frame > 1) {
      EXPECT_EQ(l, first) << frame;
    }
  }
  // Between the ramps the coordinate is exactly a level (no lingering transition).
  eff = lod_follow(eff, 80.0, h);
  EXPECT_EQ(lod_target(r, eff), 1.0f);
}

TEST(LodSelection, ScreenSizeCriterionSwitchesAtTheProjectedHeight) {
  LodSettings s;
  s.criterion = LodCriterion::kScreenSize;
  s.s1 = 100.0f;
  s.s2 = 25.0f;
  s.band = 0.0f;
  const double k = 600.0;  // px per radian
  const double h = 10.0;   // tree height
  const LodRamps r = lod_ramps(s, h, k);
  EXPECT_NEAR(r.start[0], k * h / 100.0, 1e-9);
  EXPECT_NEAR(r.start[1], k * h / 25.0, 1e-9);
  EXPECT_EQ(lod_target(r, 59.0), 0.0f);   // 101.7 px tall
  EXPECT_EQ(lod_target(r, 61.0), 1.0f);   // 98.4 px
  EXPECT_EQ(lod_target(r, 241.0), 2.0f);  // 24.9 px
  // A tree twice as tall switches twice as far away.
  EXPECT_NEAR(lod_ramps(s, 2.0 * h, k).start[0], 2.0 * r.start[0], 1e-9);
}

std::vector<render::Sphere> line_of_trees(int n, double spacing) {
  std::vector<render::Sphere> out;
  for (int i = 0; i < n; ++i) out.push_back({glm::dvec3(0.0, 5.0, -spacing * (n - i)), 6.0});
  return out;
}

TEST(LodSelection, QueuesAreOrderedNearToFarAndCulled) {
  LodSettings s;
  s.v1 = 30.0f;
  s.v2 = 80.0f;
  s.band = 0.2f;
  render::Camera cam;
  cam.set_aspect(256, 144);
  cam.set_position({0.0, 5.0, 0.0});
  cam.look_at({0.0, 5.0, -10.0});
  const render::Frustum f = cam.frustum();
  std::vector<render::Sphere> spheres = line_of_trees(60, 3.0);
  // Some behind the camera.
  for (int i = 0; i < 10; ++i) spheres.push_back({glm::dvec3(0.0, 5.0, 20.0 + 3.0 * i), 1.0});
  const std::vector<float> heights(spheres.size(), 10.0f);
  LodState state;
  LodQueues q;
  LodView view{cam.position(), &f, 200.0, 1.0e9};
  select_lods(s, view, spheres, heights, state, q);
  EXPECT_EQ(q.visible, 60u);
  EXPECT_EQ(state.level.size(), spheres.size());
  std::size_t drawn = 0;
  for (int k = 0; k < kLodLevels; ++k) {
    const auto& lvl = q.level[static_cast<std::size_t>(k)];
    drawn += lvl.size();
    double prev = 0.0;
    for (const LodQueueEntry& e : lvl) {
      const double d = glm::length(spheres[e.instance].center - cam.position());
      // Counting sort in 256 buckets: never out of order by more than one bucket width.
      EXPECT_GE(d, prev - 180.0 / 255.0 - 1e-9);
      prev = std::max(prev, d);
      EXPECT_LT(e.instance, 60u);
    }
  }
  EXPECT_EQ(drawn, q.visible + q.transitions);
  EXPECT_GT(q.level[0].size(), 0u);
  EXPECT_GT(q.level[1].size(), 0u);
  EXPECT_GT(q.level[2].size(), 0u);
  EXPECT_GT(q.transitions, 0u);
  // Disabled: everything LOD0, nothing culled by distance thresholds.
  s.enabled = false;
  select_lods(s, view, spheres, heights, state, q);
  EXPECT_EQ(q.level[0].size(), 60u);
  EXPECT_TRUE(q.level[1].empty() && q.level[2].empty());
}

// Forest scale: 100,000 instances in a 3 km square, camera inside; every visible instance is in
// exactly one queue (two while it fades). Its CPU time is printed here and measured by
// bench/lod_bench (BM_Update, select_ms), not asserted: a shared machine makes any bound flaky.
TEST(LodSelection, HundredThousandInstancesSelect) {
  std::vector<render::Sphere> spheres;
  std::uint32_t h = 12345u;
  for (int i = 0; i < 100000; ++i) {
    h = h * 1664525u + 1013904223u;
    const double x = (h >> 8) % 3000;
    h = h * 1664525u + 1013904223u;
    const double z = (h >> 8) % 3000;
    spheres.push_back({glm::dvec3(x - 1500.0, 6.0, z - 1500.0), 7.0});
  }
  const std::vector<float> heights(spheres.size(), 12.0f);
  render::Camera cam;
  cam.set_aspect(1280, 720);
  cam.set_position({0.0, 10.0, 0.0});
  cam.look_at({100.0, 5.0, -100.0});
  const render::Frustum f = cam.frustum();
  LodSettings s;
  LodState state;
  LodQueues q;
  const LodView view{cam.position(), &f, 623.0, 3000.0};
  select_lods(s, view, spheres, heights, state, q);  // warm-up (allocations)
  const Stopwatch wall;
  select_lods(s, view, spheres, heights, state, q);
  std::printf("select_lods: 100000 instances, %zu visible (LOD0 %zu, LOD1 %zu, LOD2 %zu), %.2f ms wall\n",
              q.visible, q.level[0].size(), q.level[1].size(), q.level[2].size(), wall.elapsed_ms());
  EXPECT_GT(q.visible, 5000u);
  EXPECT_LT(q.visible, spheres.size() / 2) << "the frustum must cull";
  EXPECT_EQ(q.level[0].size() + q.level[1].size() + q.level[2].size(), q.visible + q.transitions);
  for (const auto& level : q.level) EXPECT_GT(level.size(), 0u);
}

}  // namespace
}  // namespace sylva::vegetation
