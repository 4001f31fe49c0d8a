// Camera maths (no GL): reversed-Z projection values, orientation conventions, camera-relative
// model matrices and the fly controller.
#include <sylva/render/camera.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::render {
namespace {

float depth_of(const glm::mat4& proj, float z) {
  const glm::vec4 c = proj * glm::vec4(0.0f, 0.0f, z, 1.0f);
  return c.z / c.w;
}

TEST(Projection, ReversedZInfinite) {
  const glm::mat4 p = reversed_z_perspective({.fov_y = 1.0f, .aspect = 2.0f, .near_plane = 0.5f});
  EXPECT_FLOAT_EQ(depth_of(p, -0.5f), 1.0f);           // near plane -> 1
  EXPECT_FLOAT_EQ(depth_of(p, -5.0f), 0.1f);           // near / distance
  EXPECT_GT(depth_of(p, -1.0e20f), 0.0f);              // never reaches 0
  EXPECT_LT(depth_of(p, -1.0e20f), 1.0e-19f);
  EXPECT_GT(depth_of(p, -10.0f), depth_of(p, -10.001f));  // nearer is larger
  const glm::vec4 side = p * glm::vec4(1.0f, 0.0f, -1.0f, 1.0f);
  EXPECT_NEAR(side.x / side.w, 1.0f / std::tan(0.5f) / 2.0f, 1.0e-6f);
}

TEST(Projection, ReversedZFinite) {
  const glm::mat4 p = reversed_z_perspective({.fov_y = 1.0f, .aspect = 1.0f, .near_plane = 0.1f, .far_plane = 1000.0f});
  EXPECT_NEAR(depth_of(p, -0.1f), 1.0f, 1.0e-6f);
  EXPECT_NEAR(depth_of(p, -1000.0f), 0.0f, 1.0e-6f);
  EXPECT_GT(depth_of(p, -500.0f), 0.0f);
}

TEST(Camera, OrientationConventions) {
  Camera c;
  EXPECT_NEAR(glm::length(c.forward() - glm::vec3(0, 0, -1)), 0.0f, 1.0e-6f);
  EXPECT_NEAR(glm::length(c.right() - glm::vec3(1, 0, 0)), 0.0f, 1.0e-6f);
  EXPECT_NEAR(glm::length(c.up() - glm::vec3(0, 1, 0)), 0.0f, 1.0e-6f);
  c.set_yaw_pitch(1.5707963f, 0.0f);  // positive yaw turns left, toward -x
  EXPECT_NEAR(glm::length(c.forward() - glm::vec3(-1, 0, 0)), 0.0f, 1.0e-6f);
  c.set_yaw_pitch(0.3f, 0.4f);
  EXPECT_NEAR(glm::dot(c.forward(), c.right()), 0.0f, 1.0e-6f);
  EXPECT_NEAR(glm::dot(c.forward(), c.up()), 0.0f, 1.0e-6f);
  EXPECT_GT(c.forward().y, 0.0f);  // positive pitch looks up
  // The view matrix maps forward to -z and right to +x.
  const glm::mat4 v = c.view_rotation();
  EXPECT_NEAR(glm::length(glm::vec3(v * glm::vec4(c.forward(), 0)) - glm::vec3(0, 0, -1)), 0.0f, 1.0e-6f);
  EXPECT_NEAR(glm::length(glm::vec3(v * glm::vec4(c.right(), 0)) - glm::vec3(1, 0, 0)), 0.0f, 1.0e-6f);
}

TEST(Camera, LookAt) {
  Camera c;
  c.set_position({1.0e6, 100.0, -2.0e6});
  c.look_at(glm::dvec3(1.0e6 + 10.0, 110.0, -2.0e6 - 10.0));
  const glm::vec3 expected = glm::normalize(glm::vec3(1, 1, -1));
  EXPECT_NEAR(glm::length(c.forward() - expected), 0.0f, 1.0e-5f);
  const float yaw = c.yaw();
  c.look_at(c.position());  // degenerate: unchanged
  EXPECT_EQ(c.yaw(), yaw);
  c.look_at(c.position() + glm::dvec3(0, 1, 0));  // straight up: pitch clamped below 90 degrees
  EXPECT_LT(c.pitch(), 1.5707963f);
  EXPECT_GT(c.pitch(), 1.56f);
}

TEST(Camera, RelativeModelIsExactFarFromOrigin) {
  Camera c;
  const glm::dvec3 camera_pos(1.0e7 + 0.123456, -3.0e6 + 0.5, 7.0e6 - 0.25);
  c.set_position(camera_pos);
  const glm::dvec3 object(camera_pos + glm::dvec3(0.001, 2.5, -10.0));
  const glm::mat4 m = c.relative_model(object);
  EXPECT_NEAR(m[3].x, 0.001f, 1.0e-7f);
  EXPECT_NEAR(m[3].y, 2.5f, 1.0e-7f);
  EXPECT_NEAR(m[3].z, -10.0f, 1.0e-6f);
  // Local transforms compose after the offset: a scaled, rotated local frame.
  glm::mat4 local(2.0f);
  local[3] = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  const glm::mat4 ml = c.relative_model(object, local);
  const glm::vec4 p = ml * glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);  // local (1,0,0) -> 2 + 1 along x
  EXPECT_NEAR(p.x, 0.001f + 3.0f, 1.0e-6f);
  EXPECT_NEAR(p.w, 1.0f, 0.0f);
  EXPECT_EQ(c.to_relative(object), glm::vec3(m[3]));
}

TEST(FlyCamera, MovesAlongForwardAndRight) {
  Camera c;
  FlySettings s;
  s.speed = 10.0f;
  fly_step(c, {.forward = true}, s, 0.5);
  EXPECT_NEAR(c.position().z, -5.0, 1.0e-9);
  fly_step(c, {.right = true, .fast = true}, s, 0.1);
  EXPECT_NEAR(c.position().x, 10.0, 1.0e-6);  // fast multiplier 10
  fly_step(c, {.forward = true, .right = true}, s, 1.0);  // diagonal is normalised
  EXPECT_NEAR(glm::length(c.position() - glm::dvec3(10.0, 0.0, -5.0)), 10.0, 1.0e-6);
  const glm::dvec3 before = c.position();
  fly_step(c, {.up = true}, s, 0.2);
  EXPECT_NEAR(c.position().y - before.y, 2.0, 1.0e-9);
}

TEST(FlyCamera, MouseTurnsAndPitchClamps) {
  Camera c;
  FlySettings s;
  fly_step(c, {.mouse_delta = {100.0f, 0.0f}}, s, 0.016);
  EXPECT_NEAR(c.yaw(), -0.25f, 1.0e-6f);  // mouse right turns right (negative yaw)
  fly_step(c, {.mouse_delta = {0.0f, -1.0e5f}}, s, 0.016);
  EXPECT_LT(c.pitch(), 1.5708f);
  EXPECT_GT(c.pitch(), 1.5f);
  fly_step(c, {.mouse_delta = {0.0f, 5.0f}, .look = false}, s, 0.016);
  EXPECT_GT(c.pitch(), 1.5f);  // look off: no turn
}

}  // namespace
}  // namespace sylva::render
