// Stability of the blade physics over the whole grid dt 0..1 s x stiffness 0..1e6 x wind
// 0..100 m/s (several directions), plus poisoned inputs. Each test names its invariants:
//   finite        every coordinate of v0, v1, v2 is finite
//   above_ground  dot(up, v2 - v0) >= 0 and dot(up, v1 - v0) > 0 (tip and control above ground)
//   length_1pct   |Bezier arc length - height| <= 1 % of height (we achieve ~1e-6)
#include <sylva/grass/physics.hpp>

#include "support/fields.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace sylva::grass {
namespace {

std::vector<Blade> test_blades() {
  // Upright, leaning and sideways-growing blades (grass on a sphere: up is not +y).
  std::vector<Blade> out;
  const glm::vec3 ups[] = {{0, 1, 0}, glm::normalize(glm::vec3(1, 1, 0)), {1, 0, 0}, {0, -1, 0}, glm::normalize(glm::vec3(-0.3f, 0.2f, 0.9f))};
  int k = 0;
  for (const glm::vec3& up : ups) {
    for (const float lean : {0.0f, 0.4f, 0.9f}) {
      Blade b{};
      const float h = 0.1f + 0.3f * static_cast<float>(k % 4);
      const float orient = 0.7f * static_cast<float>(k);
      const glm::vec3 root(static_cast<float>(k), 0.0f, 0.5f * static_cast<float>(k));
      b.v0 = glm::vec4(root, orient);
      b.v1 = glm::vec4(root + up * h, h);
      b.v2 = glm::vec4(root + h * glm::normalize(up + lean * blade_front_dir(up, orient)), 0.01f);
      b.up = glm::vec4(up, 1.0f);
      validate_blade(b);
      b.rest = glm::vec4(b.tip() - b.root(), 0.0f);
      out.push_back(b);
      ++k;
    }
  }
  return out;
}

void expect_invariants(const Blade& b, const char* what) {
  const BladeInvariants inv = check_blade(b);
  ASSERT_TRUE(inv.finite) << what;
  EXPECT_GE(inv.tip_height, -1e-5f) << what;
  EXPECT_GT(inv.control_height, 0.0f) << what;
  EXPECT_LE(inv.length_error, 0.01f) << what;
}

TEST(GrassPhysicsStability, Invariants_finite_above_ground_length_1pct_over_dt_stiffness_wind_grid) {
  // The grid (dt 0, 1/240, 1/60, 1/5, 1 s; stiffness 0, 1e-3, 1e3, 1e6 /s; wind to
  // 100 m/s) plus points in between.
  const float dts[] = {0.0f, 1e-4f, 1.0f / 240.0f, 1.0f / 60.0f, 0.1f, 0.2f, 0.5f, 1.0f};
  const float stiffnesses[] = {0.0f, 1.0e-3f, 1.0f, 60.0f, 1.0e3f, 1.0e6f};
  const float speeds[] = {0.0f, 1.0f, 10.0f, 30.0f, 100.0f};
  const glm::vec3 dirs[] = {{1, 0, 0}, glm::normalize(glm::vec3(1, -1, 0.3f)), {0, -1, 0}, {0, 1, 0}, glm::normalize(glm::vec3(-0.2f, 0.1f, -1.0f))};
  const PhysicsSettings settings;
  const std::vector<Blade> base = test_blades();
  float worst_length = 0.0f;
  int cases = 0;
  for (const float dt : dts) {
    for (const float s : stiffnesses) {
      for (const float speed : speeds) {
        for (const glm::vec3& dir : dirs) {
          if (speed == 0.0f && dir != dirs[0]) continue;
          std::vector<Blade> blades = base;
          for (Blade& b : blades) b.up.w = s;
          for (int frame = 0; frame < 30; ++frame) {
            // Gusty: the wind flips and changes strength every few frames.
            const float gust = (frame % 7 < 3) ? 1.0f : -0.5f;
            for (Blade& b : blades) simulate_blade(b, dir * speed * gust, dt, settings);
          }
          for (const Blade& b : blades) {
            expect_invariants(b, "grid");
            worst_length = std::max(worst_length, check_blade(b).length_error);
          }
          ++cases;
        }
      }
    }
  }
  EXPECT_GT(cases, 500);
  RecordProperty("worst_length_error", std::to_string(worst_length));
  EXPECT_LT(worst_length, 1e-4f) << "the exact-length projection should do far better than 1 %";
}

TEST(GrassPhysicsStability, Invariants_finite_above_ground_with_poisoned_inputs) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const PhysicsSettings settings;
  std::vector<Blade> blades = test_blades();
  const float dts[] = {nan, inf, -inf, -1.0f, 1.0e30f, 1.0f};
  const glm::vec3 winds[] = {{nan, 0, 0}, {inf, 0, 0}, {1e30f, 1e30f, 0}, {-inf, nan, inf}, {3, 0, 0}};
  for (const float dt : dts)
    for (const glm::vec3& w : winds)
      for (Blade& b : blades) simulate_blade(b, w, dt, settings);
  for (const Blade& b : blades) expect_invariants(b, "poisoned dt/wind");

  // Stiffness NaN/Inf/negative and collision strength NaN in the buffer.
  for (Blade& b : blades) {
    b.up.w = nan;
    simulate_blade(b, glm::vec3(5, 0, 0), 1.0f / 60.0f, settings);
    b.up.w = inf;
    simulate_blade(b, glm::vec3(5, 0, 0), 1.0f / 60.0f, settings);
    b.up.w = -10.0f;
    b.rest.w = nan;
    simulate_blade(b, glm::vec3(5, 0, 0), 1.0f / 60.0f, settings);
    expect_invariants(b, "poisoned stiffness");
  }
  // A corrupted state (tip and control NaN) is reset to the rest pose.
  for (Blade& b : blades) {
    b.v2 = glm::vec4(nan, nan, nan, b.v2.w);
    b.v1 = glm::vec4(inf, 0, 0, b.v1.w);
    simulate_blade(b, glm::vec3(1, 0, 0), 1.0f / 60.0f, settings);
    expect_invariants(b, "corrupted state");
  }
}

TEST(GrassPhysicsStability, Invariants_finite_above_ground_length_1pct_with_extreme_colliders) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PhysicsSettings settings;
  std::vector<Blade> blades = test_blades();
  const CollisionSphere spheres[] = {
      {{0, 0, 0}, 100.0f},                 // swallows everything, root included
      {{0.5f, 0.2f, 0.1f}, 1e-7f},         // tiny
      {{nan, 0, 0}, 1.0f},                 // poisoned: ignored
      {{0, 0, 0}, nan},                    // poisoned: ignored
      {{3, 0.1f, 1.5f}, 0.3f},             // an ordinary foot
  };
  for (int frame = 0; frame < 60; ++frame)
    for (Blade& b : blades) simulate_blade(b, glm::vec3(0, 0, 40), frame % 2 ? 1.0f : 1.0f / 60.0f, settings, spheres);
  for (const Blade& b : blades) expect_invariants(b, "colliders");
}

TEST(GrassPhysicsStability, Invariants_length_1pct_dt_independent_equilibrium) {
  // The same wind for 2 s reaches the same equilibrium whether taken in 120 or 2 frames
  // (a stiff blade: explicit Euler would explode at s*dt = 5e5).
  PhysicsSettings settings;
  Blade a = test_blades()[1], b = a;
  a.up.w = b.up.w = 5.0e5f;
  for (int i = 0; i < 120; ++i) simulate_blade(a, glm::vec3(30, 0, 0), 1.0f / 60.0f, settings);
  for (int i = 0; i < 2; ++i) simulate_blade(b, glm::vec3(30, 0, 0), 1.0f, settings);
  EXPECT_LT(glm::length(a.tip() - b.tip()), 1e-3f);
  expect_invariants(a, "stiff small dt");
  expect_invariants(b, "stiff large dt");
}

}  // namespace
}  // namespace sylva::grass
