// Reversed-Z perspective, camera-relative matrices and the fly controller (camera.hpp).
#include <sylva/render/camera.hpp>

#include <sylva/core/assert.hpp>

#include <epoxy/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva::render {
namespace {
constexpr float kMaxPitch = 1.5707963f - 1.0e-3f;
}  // namespace

glm::mat4 reversed_z_perspective(const PerspectiveParams& p) {
  SYLVA_ASSERT(p.fov_y > 0.0f && p.fov_y < 3.14159f, "fov_y={} must be in (0, pi)", p.fov_y);
  SYLVA_ASSERT(p.aspect > 0.0f && std::isfinite(p.aspect), "aspect={} must be positive", p.aspect);
  SYLVA_ASSERT(p.near_plane > 0.0f, "near_plane={} must be positive", p.near_plane);
  const bool infinite = p.far_plane <= 0.0f || std::isinf(p.far_plane);
  SYLVA_ASSERT(infinite || p.far_plane > p.near_plane, "far_plane={} must exceed near_plane={}", p.far_plane,
               p.near_plane);
  // Depth d = (A z + B) / -z with d(-near) = 1 and d(-far) = 0 (d -> 0 as far -> infinity).
  const double f = 1.0 / std::tan(0.5 * static_cast<double>(p.fov_y));
  const double n = p.near_plane;
  glm::dmat4 m(0.0);
  m[0][0] = f / static_cast<double>(p.aspect);
  m[1][1] = f;
  m[2][3] = -1.0;
  if (infinite) {
    m[2][2] = 0.0;
    m[3][2] = n;
  } else {
    const double fr = p.far_plane;
    m[2][2] = n / (fr - n);
    m[3][2] = n * fr / (fr - n);
  }
  return glm::mat4(m);
}

void apply_reversed_z_state() {
  glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_GREATER);
  glClearDepth(0.0);
}

void Camera::set_yaw_pitch(float yaw, float pitch) {
  if (!std::isfinite(yaw) || !std::isfinite(pitch)) return;
  // Keep yaw in [-pi, pi] so it never loses precision after long sessions.
  yaw_ = static_cast<float>(std::remainder(static_cast<double>(yaw), 2.0 * 3.14159265358979323846));
  pitch_ = std::clamp(pitch, -kMaxPitch, kMaxPitch);
}

void Camera::look_at(const glm::dvec3& target) {
  const glm::dvec3 d = target - position_;
  const double len = glm::length(d);
  if (!(len > 0.0) || !std::isfinite(len)) return;
  const glm::dvec3 dir = d / len;
  set_yaw_pitch(static_cast<float>(std::atan2(-dir.x, -dir.z)),
                static_cast<float>(std::asin(std::clamp(dir.y, -1.0, 1.0))));
}

void Camera::set_aspect(int width, int height) {
  if (width > 0 && height > 0) perspective_.aspect = static_cast<float>(width) / static_cast<float>(height);
}

glm::vec3 Camera::forward() const {
  const double cy = std::cos(yaw_), sy = std::sin(yaw_);
  const double cp = std::cos(pitch_), sp = std::sin(pitch_);
  return glm::vec3(glm::dvec3(-sy * cp, sp, -cy * cp));
}

glm::vec3 Camera::right() const {
  return glm::vec3(glm::dvec3(std::cos(yaw_), 0.0, -std::sin(yaw_)));
}

glm::vec3 Camera::up() const { return glm::cross(right(), forward()); }

glm::mat4 Camera::view_rotation() const {
  const glm::vec3 f = forward();
  const glm::vec3 r = right();
  const glm::vec3 u = glm::cross(r, f);
  glm::mat4 v(1.0f);
  v[0][0] = r.x; v[1][0] = r.y; v[2][0] = r.z;
  v[0][1] = u.x; v[1][1] = u.y; v[2][1] = u.z;
  v[0][2] = -f.x; v[1][2] = -f.y; v[2][2] = -f.z;
  return v;
}

glm::mat4 Camera::view_projection() const {
  return glm::mat4(glm::dmat4(projection()) * glm::dmat4(view_rotation()));
}

glm::mat4 Camera::relative_model(const glm::dvec3& object_origin, const glm::mat4& local) const {
  const glm::vec3 offset(object_origin - position_);  // exact-ish: subtraction in double
  glm::mat4 m = local;
  // translate(offset) * local, column by column (for affine `local` only column 3 changes).
  for (int j = 0; j < 4; ++j) m[j] += glm::vec4(offset, 0.0f) * local[j].w;
  return m;
}

void fly_step(Camera& camera, const FlyInput& input, const FlySettings& settings, double dt) {
  if (!std::isfinite(dt)) dt = 0.0;
  dt = std::clamp(dt, 0.0, 1.0);
  if (input.look && std::isfinite(input.mouse_delta.x) && std::isfinite(input.mouse_delta.y)) {
    camera.set_yaw_pitch(camera.yaw() - input.mouse_delta.x * settings.mouse_sensitivity,
                         camera.pitch() - input.mouse_delta.y * settings.mouse_sensitivity);
  }
  glm::dvec3 move(0.0);
  const glm::dvec3 f(camera.forward());
  const glm::dvec3 r(camera.right());
  if (input.forward) move += f;
  if (input.back) move -= f;
  if (input.right) move += r;
  if (input.left) move -= r;
  if (input.up) move.y += 1.0;
  if (input.down) move.y -= 1.0;
  const double len = glm::length(move);
  if (len < 1.0e-9) return;
  double speed = settings.speed * (input.fast ? settings.fast_multiplier : 1.0f);
  camera.set_position(camera.position() + move / len * (speed * dt));
}

}  // namespace sylva::render
