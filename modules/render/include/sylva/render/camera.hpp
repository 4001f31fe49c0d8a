#pragma once
// Perspective camera with reversed-Z depth and camera-relative rendering. GL-free maths except
// apply_reversed_z_state() (DESIGN.md §2 "Large coordinates").
//
// Reversed-Z: clip depth is 1 at the near plane and 0 at the far plane (or at infinity), used
// with glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), a 32-bit float depth buffer, clear depth 0
// and glDepthFunc(GL_GREATER). The float's exponent then spends its precision where
// perspective needs it, so 1e-2 m and 1e5 m both resolve (tests/reversed_z_gl_test.cpp).
//
// Camera-relative: the world position is a glm::dvec3. The view matrix holds only the
// rotation; model matrices translate by (object origin - camera position), subtracted in
// double and only then rounded to float, so vertex positions near the camera stay exact even
// 1e7 m from the world origin. Conventions: right-handed, y up, the camera looks along -z of
// its view space; yaw 0 looks along -z of the world, positive yaw turns left (toward -x),
// positive pitch looks up. Angles in radians, distances in metres.

#include <sylva/render/frustum.hpp>

#include <glm/glm.hpp>

namespace sylva::render {

struct PerspectiveParams {
  float fov_y = 1.0471976f;  // vertical field of view [rad], in (0, pi)
  float aspect = 16.0f / 9.0f;  // width / height, > 0
  float near_plane = 0.1f;   // metres, > 0
  float far_plane = 0.0f;    // metres; 0 (or infinity) = infinite far plane
};

// Reversed-Z perspective projection for a zero-to-one clip range (see above).
glm::mat4 reversed_z_perspective(const PerspectiveParams& p);

// glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), glDepthFunc(GL_GREATER), glClearDepth(0),
// depth test on. Needs a current GL context.
void apply_reversed_z_state();

class Camera {
 public:
  Camera() = default;

  // Position in world metres.
  const glm::dvec3& position() const { return position_; }
  void set_position(const glm::dvec3& p) { position_ = p; }

  // Orientation: yaw around world +y, then pitch around the camera's right axis.
  float yaw() const { return yaw_; }
  float pitch() const { return pitch_; }
  // Pitch is clamped to +-(pi/2 - 1e-3) so the view never flips.
  void set_yaw_pitch(float yaw, float pitch);
  // Points the camera at a world target (no-op when the target equals the position).
  void look_at(const glm::dvec3& target);

  const PerspectiveParams& perspective() const { return perspective_; }
  PerspectiveParams& perspective() { return perspective_; }
  void set_aspect(int width, int height);  // from a viewport, ignored when either is <= 0

  // Unit vectors in world space.
  glm::vec3 forward() const;
  glm::vec3 right() const;
  glm::vec3 up() const;

  // Rotation-only view matrix (world direction -> view space).
  glm::mat4 view_rotation() const;
  glm::mat4 projection() const { return reversed_z_perspective(perspective_); }
  // projection * view_rotation: multiply by a camera-relative position.
  glm::mat4 view_projection() const;

  // Model matrix for an object whose local frame has its origin at world `object_origin`:
  // translate(object_origin - position) * local, the subtraction in double.
  glm::mat4 relative_model(const glm::dvec3& object_origin, const glm::mat4& local = glm::mat4(1.0f)) const;
  // World point -> camera-relative float position.
  glm::vec3 to_relative(const glm::dvec3& world) const { return glm::vec3(world - position_); }

  Frustum frustum() const { return Frustum::from_matrix(view_projection(), position_); }

 private:
  glm::dvec3 position_{0.0};
  float yaw_ = 0.0f;
  float pitch_ = 0.0f;
  PerspectiveParams perspective_{};
};

// Input for one fly-camera step; produced by the window layer or by a script or test.
struct FlyInput {
  bool forward = false, back = false, left = false, right = false;  // W S A D
  bool up = false, down = false;  // E / Q (world up/down)
  bool fast = false;              // Shift
  glm::vec2 mouse_delta{0.0f};    // pixels since the last step, +x right, +y down
  bool look = true;               // whether mouse_delta turns the camera
};

struct FlySettings {
  float speed = 10.0f;           // metres per second
  float fast_multiplier = 10.0f; // speed factor while `fast`
  float mouse_sensitivity = 0.0025f;  // radians per pixel

  template <class V>
  void visit(V& v) {
    v(speed, "speed", {.min = 0.01f, .max = 1.0e5f, .unit = "m/s", .help = "Fly speed"});
    v(fast_multiplier, "fast_multiplier", {.min = 1.0f, .max = 1000.0f, .help = "Speed factor while Shift is held"});
    v(mouse_sensitivity, "mouse_sensitivity",
      {.min = 1.0e-5f, .max = 0.1f, .unit = "rad/px", .help = "Mouse look rate"});
  }
};

// WASD + mouse fly camera; pure maths so it is testable without a window.
// dt is clamped to [0, 1] s so a stalled frame never throws the camera kilometres away.
void fly_step(Camera& camera, const FlyInput& input, const FlySettings& settings, double dt);

}  // namespace sylva::render
