#include "camera_control.hpp"

#include <algorithm>
#include <cmath>

namespace sylva::editor {

void orbit_rotate(OrbitState& s, glm::vec2 d, float sensitivity) {
  s.yaw -= d.x * sensitivity;
  s.pitch = std::clamp(s.pitch - d.y * sensitivity, -1.55f, 1.55f);
}

void orbit_zoom(OrbitState& s, float notches) {
  s.distance = std::clamp(s.distance * std::pow(0.9, static_cast<double>(notches)), 0.5, 1.0e6);
}

void orbit_pan(OrbitState& s, glm::vec2 d, float fov_y, int viewport_height) {
  render::Camera c;
  apply_orbit(s, c);
  const double metres_per_px = 2.0 * s.distance * std::tan(0.5 * fov_y) / std::max(viewport_height, 1);
  s.target += (-glm::dvec3(c.right()) * static_cast<double>(d.x) + glm::dvec3(c.up()) * static_cast<double>(d.y)) * metres_per_px;
}

void apply_orbit(const OrbitState& s, render::Camera& camera) {
  camera.set_yaw_pitch(s.yaw, s.pitch);
  camera.set_position(s.target - glm::dvec3(camera.forward()) * s.distance);
}

OrbitState orbit_from_camera(const render::Camera& camera, double distance) {
  OrbitState s;
  s.yaw = camera.yaw();
  s.pitch = camera.pitch();
  s.distance = distance;
  s.target = camera.position() + glm::dvec3(camera.forward()) * distance;
  return s;
}

}  // namespace sylva::editor
