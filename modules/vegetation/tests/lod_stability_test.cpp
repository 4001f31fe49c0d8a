// Stability of the LOD selection under extreme parameters and distances. Invariants checked:
// the LOD coordinate stays finite in [0, 2], every visible instance is drawn at least once with one
// fully opaque level and fades in [0, 1], and nothing is NaN for v1 = v2, v1 = v2 = 0, huge or
// non-finite thresholds, zero or huge bands, distances from 0 to 1e12 m, NaN positions.
#include <sylva/vegetation/lod_selection.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva::vegetation {
namespace {

void check_draws(float l) {
  ASSERT_TRUE(std::isfinite(l));
  ASSERT_GE(l, 0.0f);
  ASSERT_LE(l, 2.0f);
  const LodDraws d = lod_draws(l);
  ASSERT_GE(d.count, 1);
  float best = 0.0f;
  for (int k = 0; k < d.count; ++k) {
    const LodDraw& x = d.draw[static_cast<std::size_t>(k)];
    ASSERT_GE(x.level, 0);
    ASSERT_LT(x.level, kLodLevels);
    ASSERT_GE(x.fade, 0.0f);
    ASSERT_LE(x.fade, 1.0f);
    best = std::max(best, x.fade);
  }
  ASSERT_EQ(best, 1.0f);
}

// Invariant: finite coordinate in [0, 2] and an opaque level for every threshold setting and distance.
TEST(LodStability, ExtremeThresholdsAndDistancesGiveValidLevels) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float values[] = {0.0f, 1.0e-6f, 1.0f, 50.0f, 1.0e7f, 3.0e38f, inf, nan, -5.0f};
  const double distances[] = {0.0, 1.0e-9, 0.5, 50.0, 1.0e4, 1.0e12, std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::quiet_NaN()};
  for (LodCriterion c : {LodCriterion::kDistance, LodCriterion::kHorizontalDistance, LodCriterion::kScreenSize})
    for (float v1 : values)
      for (float v2 : values)
        for (float band : {0.0f, 0.15f, 4.0f, nan}) {
          LodSettings s;
          s.criterion = c;
          s.v1 = v1;
          s.v2 = v2;
          s.s1 = v2;
          s.s2 = v1;
          s.band = band;
          const LodRamps r = lod_ramps(s, 12.0, 600.0);
          double prev = std::numeric_limits<double>::quiet_NaN();
          for (double d : distances) {
            const float t = lod_target(r, d);
            ASSERT_TRUE(std::isfinite(t)) << v1 << " " << v2 << " " << d;
            check_draws(t);
            for (float h : {0.0f, 0.05f, 1.0f, nan, inf}) check_draws(lod_target(r, lod_follow(prev, d, h)));
            prev = lod_follow(prev, d, 0.05f);
          }
        }
}

// Invariant: v1 = v2 passes LOD0 -> LOD2 continuously (both ramps at once) and monotonically.
TEST(LodStability, EqualThresholdsRampBothLevelsTogether) {
  LodSettings s;
  s.v1 = 60.0f;
  s.v2 = 60.0f;
  s.band = 0.1f;
  const LodRamps r = lod_ramps(s, 10.0, 600.0);
  float prev = 0.0f;
  for (double d = 50.0; d < 80.0; d += 0.05) {
    const float l = lod_target(r, d);
    ASSERT_GE(l, prev);
    ASSERT_LE(l - prev, 0.05f / 6.0f * 2.0f + 1e-5f);
    prev = l;
  }
  EXPECT_EQ(prev, 2.0f);
  // v2 < v1 is treated as v2 = v1.
  s.v2 = 10.0f;
  EXPECT_EQ(lod_ramps(s, 10.0, 600.0).start[1], 60.0);
}

// Invariant: non-finite instance positions and radii never produce NaN coordinates or crash the
// selection; every queued fade is in [0, 1].
TEST(LodStability, HostileInstancesAreHandled) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<render::Sphere> spheres = {{glm::dvec3(nan, 0.0, 0.0), 5.0},     {glm::dvec3(inf, 0.0, 0.0), 5.0},
                                         {glm::dvec3(0.0, 0.0, -1.0e12), 5.0}, {glm::dvec3(0.0, 0.0, 0.0), 0.0},
                                         {glm::dvec3(1.0, 0.0, -30.0), inf},  {glm::dvec3(0.0, 0.0, -60.0), nan}};
  const std::vector<float> heights = {10.0f, 10.0f, 10.0f, 0.0f, 10.0f, std::numeric_limits<float>::quiet_NaN()};
  for (LodCriterion c : {LodCriterion::kDistance, LodCriterion::kScreenSize}) {
    LodSettings s;
    s.criterion = c;
    LodState state;
    LodQueues q;
    for (double maxd : {1.0e30, 100.0, 0.0, nan}) {
      const LodView view{glm::dvec3(0.0), nullptr, 600.0, maxd};
      select_lods(s, view, spheres, heights, state, q);
      for (float l : state.level)
        if (!std::isnan(l)) check_draws(l);
      for (const auto& lvl : q.level)
        for (const LodQueueEntry& e : lvl) {
          ASSERT_LT(e.instance, spheres.size());
          ASSERT_GE(e.fade, 0.0f);
          ASSERT_LE(e.fade, 1.0f);
        }
    }
  }
}

}  // namespace
}  // namespace sylva::vegetation
