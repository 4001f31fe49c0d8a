#pragma once
// Orbit camera for the editor viewport (GL-free; the fly camera is render::fly_step). The
// camera circles `target` at `distance`, yaw/pitch as render::Camera uses them, so switching
// between fly and orbit keeps the view: from_camera() puts the target `distance` ahead.

#include <sylva/render/camera.hpp>

#include <glm/glm.hpp>

namespace sylva::editor {

struct OrbitState {
  glm::dvec3 target{0.0};
  double distance = 50.0;  // metres, clamped to [0.5, 1e6]
  float yaw = 0.0f;        // radians
  float pitch = -0.4f;     // radians, clamped to (-pi/2, pi/2)
};

// Drag: rotate by mouse pixels (rad/px sensitivity); scroll: zoom by 10 % per notch; pan: move
// the target in the view plane by pixels at the target's distance.
void orbit_rotate(OrbitState& s, glm::vec2 mouse_delta, float sensitivity = 0.005f);
void orbit_zoom(OrbitState& s, float scroll_notches);
void orbit_pan(OrbitState& s, glm::vec2 mouse_delta, float fov_y, int viewport_height);
// Places the camera on the orbit (looking at the target).
void apply_orbit(const OrbitState& s, render::Camera& camera);
// The orbit that reproduces the camera with the target `distance` metres ahead.
OrbitState orbit_from_camera(const render::Camera& camera, double distance);

}  // namespace sylva::editor
