// LOD selection and transitions (lod_selection.hpp): thresholds, ramps, hysteresis, the
// fade-in-background weights (one level always opaque), queues ordered near to far, culling.
#include <sylva/vegetation/lod_selection.hpp>

#include <sylva/core/timer.hpp>
#include <sylva/render/camera.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

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
