// Stability of camera and culling maths under extreme inputs. Invariants checked:
//  - "finite": matrices, frustum planes and positions never contain NaN/Inf for extreme fov,
//    near planes, positions and time steps;
//  - "bounded step": a fly step never moves further than speed * fast * 1 s, whatever dt is;
//  - "ignored garbage": NaN/Inf input leaves the camera unchanged.
#include <sylva/render/camera.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace sylva::render {
namespace {

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 4; ++r) {
      if (!std::isfinite(m[c][r])) return false;
    }
  }
  return true;
}

TEST(CameraStability, FiniteForExtremeProjections) {
  for (float fov : {1.0e-4f, 0.01f, 1.0f, 3.0f, 3.14f}) {
    for (float near_plane : {1.0e-6f, 1.0e-3f, 1.0f, 1.0e4f}) {
      for (float far_plane : {0.0f, std::numeric_limits<float>::infinity(), near_plane * 1.0001f, near_plane * 1.0e6f}) {
        for (float aspect : {1.0e-3f, 1.0f, 1.0e3f}) {
          Camera c;
          c.perspective() = {.fov_y = fov, .aspect = aspect, .near_plane = near_plane, .far_plane = far_plane};
          c.set_position({1.0e12, -1.0e12, 3.0e11});
          c.set_yaw_pitch(2.0f, -1.5f);
          ASSERT_TRUE(finite(c.projection())) << fov << " " << near_plane << " " << far_plane;
          ASSERT_TRUE(finite(c.view_projection()));
          const Frustum frustum = c.frustum();  // keep it alive: planes() returns a reference
          for (const glm::vec4& p : frustum.planes()) {
            ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && std::isfinite(p.w));
          }
          // The point straight ahead between the planes is visible (camera near the origin,
          // where double positions resolve the sub-micrometre offsets of the tiny near planes).
          Camera local = c;
          local.set_position({3.0, -2.0, 1.0});
          const bool infinite = far_plane == 0.0f || std::isinf(far_plane);
          const double distance = infinite ? 2.0 * near_plane : 0.5 * (double(near_plane) + double(far_plane));
          const glm::dvec3 ahead = local.position() + glm::dvec3(local.forward()) * distance;
          EXPECT_TRUE(local.frustum().intersects(Sphere{ahead, 0.0}))
              << fov << " " << near_plane << " " << far_plane << " " << aspect;
        }
      }
    }
  }
}

TEST(CameraStability, FlyStepBoundedForAnyDt) {
  FlySettings s;  // 10 m/s, x10 fast
  for (double dt : {0.0, 1.0e-9, 1.0 / 240.0, 1.0, 5.0, 1.0e9, std::numeric_limits<double>::infinity()}) {
    Camera c;
    c.set_position({1.0e7, 0.0, 0.0});
    fly_step(c, {.forward = true, .right = true, .up = true, .fast = true}, s, dt);
    const double moved = glm::length(c.position() - glm::dvec3(1.0e7, 0.0, 0.0));
    ASSERT_TRUE(std::isfinite(moved));
    EXPECT_LE(moved, 100.0 + 1.0e-6) << "dt=" << dt;
  }
}

TEST(CameraStability, GarbageInputIsIgnored) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Camera c;
  c.set_yaw_pitch(0.5f, 0.25f);
  c.set_yaw_pitch(nan, 0.0f);
  EXPECT_EQ(c.yaw(), 0.5f);
  fly_step(c, {.forward = true, .mouse_delta = {nan, std::numeric_limits<float>::infinity()}}, {}, std::nan(""));
  EXPECT_EQ(c.yaw(), 0.5f);
  EXPECT_EQ(c.pitch(), 0.25f);
  EXPECT_EQ(c.position(), glm::dvec3(0.0));
  c.set_aspect(0, 100);  // ignored
  EXPECT_GT(c.perspective().aspect, 0.0f);
  // Yaw stays in [-pi, pi] after many turns, so it never loses precision.
  for (int i = 0; i < 100000; ++i) fly_step(c, {.mouse_delta = {400.0f, 0.0f}}, {}, 0.016);
  EXPECT_LE(std::abs(c.yaw()), 3.1416f);
}

}  // namespace
}  // namespace sylva::render
